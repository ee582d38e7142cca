#include "gnuplot.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "atomic_file.h"

namespace fibrecheck {

Gnuplot::Gnuplot(std::string folder) : folder_(std::move(folder)) {
  const char* named = std::getenv("FIBRECHECK_GNUPLOT");
  program_ = named && *named ? named : "gnuplot";
  const std::string probe = "'" + program_ + "' -e 'exit' >/dev/null 2>&1";
  available_ = std::system(probe.c_str()) == 0;
}

namespace {

/// Linear axes end at the data with a small margin rather than at the next tic, so that data
/// fill the frame; logarithmic axes keep gnuplot's whole decades, whose tics carry the labels. A
/// script's own ranges and offsets come after this and win.
std::string fitted_ranges(const std::string& script) {
  const bool log_x = script.find("set logscale x") != std::string::npos;
  const bool log_y = script.find("set logscale y") != std::string::npos ||
                     script.find("set logscale xy") != std::string::npos;
  std::string out;
  if (!log_x) out += "set autoscale xfix\n";
  if (!log_y) out += "set autoscale yfix\n";
  const char* x_margin = log_x ? "0" : "graph 0.04";
  const char* y_margin = log_y ? "0" : "graph 0.06";
  out += std::string("set offsets ") + x_margin + ", " + x_margin + ", " + y_margin + ", " +
         y_margin + "\n";
  return out;
}

}  // namespace

bool Gnuplot::plot(const std::string& name, const std::string& body,
                   const std::vector<Series>& series, std::string* why) {
  namespace fs = std::filesystem;
  const fs::path src = fs::path(folder_) / "src";
  fs::create_directories(src);
  std::string script = body;
  for (std::size_t k = 0; k < series.size(); ++k) {
    const std::string file = "src/" + name + "." + std::to_string(k) + ".dat";
    write_file_atomically((fs::path(folder_) / file).string(), series[k].rows);
    const std::string placeholder = "@DATA" + std::to_string(k) + "@";
    for (std::size_t at = script.find(placeholder); at != std::string::npos;
         at = script.find(placeholder, at + file.size() + 2))
      script.replace(at, placeholder.size(), "'" + file + "'");
  }
  std::ostringstream gp;
  gp << "# " << name << ": drawn by fibrecheck report; run `gnuplot src/" << name
     << ".gp` in the figures folder to draw it again.\n"
     << "set terminal pngcairo size 960,640 font 'Sans,14' enhanced\n"
     << "set output '" << name << ".png'\n"
     << fitted_ranges(script) << script << "\n"
     << "set terminal svg size 960,640 font 'Sans,14' enhanced\n"
     << "set output '" << name << ".svg'\n"
     << "replot\n"
     << "set terminal pdfcairo size 5in,3.33in font 'Sans,9' enhanced\n"
     << "set output '" << name << ".pdf'\n"
     << "replot\n";
  write_file_atomically((src / (name + ".gp")).string(), gp.str());
  if (!available_) {
    if (why) *why = "gnuplot (" + program_ + ") cannot be run";
    return false;
  }
  const std::string command =
      "cd '" + folder_ + "' && '" + program_ + "' src/" + name + ".gp > src/" + name + ".log 2>&1";
  const int status = std::system(command.c_str());
  const fs::path png = fs::path(folder_) / (name + ".png");
  if (status != 0 || !fs::exists(png) || fs::file_size(png) == 0) {
    if (why) *why = "gnuplot failed on src/" + name + ".gp (see src/" + name + ".log)";
    return false;
  }
  return true;
}

std::string rows_or_nan(const std::string& rows, int columns) {
  if (!rows.empty()) return rows;
  std::string nan_row;
  for (int c = 0; c < columns; ++c) nan_row += c == 0 ? "nan" : " nan";
  return nan_row + "\n";
}

}  // namespace fibrecheck
