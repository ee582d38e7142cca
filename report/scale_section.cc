#include "scale_section.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

namespace fibrecheck {

namespace {

/// A series' name: "iterative, accelerated", "reference, 2 processes", "Siconos lemke".
std::string series_name(const std::string& solver, const std::string& method, int processes) {
  if (solver == "iterative") return "iterative, " + method;
  if (solver == "fem")
    return "reference, " + std::to_string(processes) + " process" + (processes == 1 ? "" : "es");
  return "Siconos " + method;
}

std::string series_name(const ScalePoint& p) {
  return series_name(p.solver, p.method, p.processes);
}

Table scale_table(const ScaleStudy& study) {
  Table t;
  t.label = "scale";
  t.caption = "Cost against tow size (" + std::to_string(study.slices) + " slices, seed " +
              std::to_string(study.seed) +
              "): candidate and pushing contacts, iterations, time, time per iteration and peak "
              "memory, resident and proportional (for the reference, resident over all its "
              "processes per finite-element unknown); for Siconos, its distance from the "
              "reference's answer.";
  t.header = {"Fibres",    "Run",          "Status",     "Candidates",
              "Active",    "Iterations",   "Time (s)",   "ms/iteration",
              "Peak (MB)", "Propor. (MB)", "kB/unknown", "Against reference"};
  for (const ScalePoint& p : study.points) {
    const bool iterative = p.solver != "fem";
    const double unknowns = static_cast<double>(p.unknowns);
    t.rows.push_back(
        {count(p.fibres), series_name(p), p.status, count(p.candidates), count(p.active),
         count(p.iterations), seconds(p.time_s), iterative ? sci(p.ms_per_iteration()) : "–",
         fixed3(p.peak_memory_mb),
         p.peak_proportional_memory_mb > 0.0 ? fixed3(p.peak_proportional_memory_mb) : "–",
         // The reference's peak over all its processes, per finite-element unknown.
         unknowns > 0.0 ? fixed3(1024.0 * p.peak_memory_mb * p.processes / unknowns) : "–",
         p.agreement >= 0.0 ? sci(p.agreement) : "–"});
  }
  return t;
}

/// "Time grows as fibres^a with a: …", each exponent named like its points (the reference's
/// with their process count); empty without exponents.
std::string exponents_sentence(const ScaleStudy& study) {
  std::string exponents;
  for (const ScaleExponent& e : study.exponents) {
    std::ostringstream line;
    line.precision(2);
    line << std::fixed << series_name(e.solver, e.method, e.processes) << " " << e.time;
    exponents += (exponents.empty() ? "" : "; ") + line.str();
  }
  return exponents.empty() ? "" : " Time grows as fibres^a with a: " + exponents + ".";
}

/// Whether Siconos ran at this size, on the problem the reference's run on the most processes
/// exported (forming the whole W to do so).
bool exported(const ScaleStudy& study, int fibres) {
  return std::any_of(study.points.begin(), study.points.end(), [&](const ScalePoint& p) {
    return p.solver == "siconos" && p.fibres == fibres;
  });
}

/// "Two processes of the reference hold … of one process's peak": for every size the reference
/// ran on one process and on more, resident, proportional and resident above the program's own
/// floor (the libraries' pages every process holds, whatever it solves); empty without such a
/// pair.
std::string processes_sentence(const ScaleStudy& study) {
  const double floor = study.program_floor_memory_mb;
  std::ostringstream out;
  out.precision(2);
  out << std::fixed;
  int pairs = 0;
  for (const ScalePoint& one : study.points) {
    if (one.solver != "fem" || one.processes != 1 || one.status != "converged") continue;
    for (const ScalePoint& many : study.points) {
      if (many.solver != "fem" || many.fibres != one.fibres || many.processes < 2 ||
          many.status != "converged" || !(one.peak_memory_mb > 0.0))
        continue;
      out << (pairs++ == 0 ? "" : "; ") << one.fibres << " fibres, " << many.processes
          << " processes: " << many.peak_memory_mb / one.peak_memory_mb;
      if (one.peak_proportional_memory_mb > 0.0 && many.peak_proportional_memory_mb > 0.0)
        out << " / " << many.peak_proportional_memory_mb / one.peak_proportional_memory_mb;
      if (floor > 0.0 && one.peak_memory_mb > floor)
        out << " / " << (many.peak_memory_mb - floor) / (one.peak_memory_mb - floor);
      if (exported(study, one.fibres)) out << " (exporting its problem for Siconos)";
    }
  }
  if (pairs == 0) return "";
  std::ostringstream measures;
  measures << "resident / proportional";
  if (floor > 0.0)
    measures << " / resident above the " << std::lround(floor)
             << " MB the program holds when it only starts and prints its help";
  return " The reference's peak per process on several processes over that on one, " +
         measures.str() + ": " + out.str() + ".";
}

/// A measure of the converged runs against fibres (log-log), one series per solver and method.
void against_fibres_figure(ReportPage& page, const ScaleStudy& study, const std::string& name,
                           const std::string& caption, const std::string& ylabel,
                           double ScalePoint::*value) {
  std::vector<std::string> names;
  std::map<std::string, std::ostringstream> rows;
  for (const ScalePoint& p : study.points) {
    if (p.status != "converged" || !(p.*value > 0.0)) continue;
    const std::string series_title = series_name(p);
    if (std::find(names.begin(), names.end(), series_title) == names.end())
      names.push_back(series_title);
    rows[series_title] << p.fibres << " " << p.*value << "\n";
  }
  std::vector<Gnuplot::Series> series;
  std::string plot;
  for (const std::string& title : names) {
    const int k = static_cast<int>(series.size());
    series.push_back({rows[title].str()});
    plot += std::string(plot.empty() ? "" : ", ") + "@DATA" + std::to_string(k) +
            "@ using 1:2 with linespoints pt " + std::to_string(5 + 2 * k) +
            " ps 1.5 lw 2 title '" + title + "'";
  }
  if (plot.empty()) return;
  page.figure(name, caption,
              "set xlabel 'fibres'\nset ylabel '" + ylabel +
                  "'\nset logscale xy\nset autoscale xfix\nset format y '10^{%L}'\nset key "
                  "outside top center horizontal\nset grid\nset offsets graph 0.05, graph 0.05, "
                  "0, 0\nplot " +
                  plot,
              series);
}

// The largest tow the iterative solver took, with its time, and the reference's largest.
std::optional<std::string> scale_finding(const std::vector<ScaleStudy>& studies) {
  const ScalePoint *iterative = nullptr, *reference = nullptr;
  auto keep_largest = [](const ScalePoint*& largest, const ScalePoint& p) {
    if (!largest || p.fibres > largest->fibres ||
        (p.fibres == largest->fibres && p.time_s < largest->time_s))
      largest = &p;
  };
  for (const ScaleStudy& study : studies)
    for (const ScalePoint& p : study.points) {
      if (p.status != "converged") continue;
      if (p.solver == "iterative") keep_largest(iterative, p);
      if (p.solver == "fem") keep_largest(reference, p);
    }
  if (!iterative) return std::nullopt;
  std::ostringstream out;
  out << "The iterative solver took a " << iterative->fibres << "-fibre tow (" << iterative->slices
      << " slices) in " << seconds(iterative->time_s) << " s";
  if (reference)
    out << "; the reference's largest, " << reference->fibres << " fibres, took "
        << seconds(reference->time_s) << " s on " << reference->processes << " process"
        << (reference->processes > 1 ? "es" : "");
  out << " ([#tab:scale]).";
  return out.str();
}

}  // namespace

void write_scale_section(ReportPage& page, const std::vector<ScaleStudy>& studies) {
  if (studies.empty()) return;
  page.section(
      "Scale",
      "Generated tows of growing size (fibrecheck study scale), each run its own process: the "
      "iterative solver's rules, the reference under mpiexec and Siconos on the reference's "
      "exported contact problem (Lemke's pivoting, projected Gauss-Seidel and a Newton method on "
      "the linear complementarity problem). Time is the solver's own (without start-up and "
      "files). Peak memory is the process's (the largest process's under mpiexec), resident and "
      "proportional: the program maps the finite-element libraries, about 150 MB, which every "
      "process's resident memory counts in full and the machine holds once; the proportional set "
      "size counts each shared page as the share of each process that maps it (sampled every "
      "tenth of a second), so that the processes' figures add up to what the machine holds. For "
      "the reference the iterations are its "
      "outer iterations; its active-set passes are in its result files. The reference run that "
      "exports its contact problem for Siconos (on the most processes) forms the whole compliance "
      "matrix W on every process to do so; without that, each process holds only its own "
      "fibres' influence matrices and W is never formed.");
  for (const ScaleStudy& study : studies) {
    Table t = scale_table(study);
    t.caption += exponents_sentence(study) + processes_sentence(study);
    page.table(t);
    against_fibres_figure(page, study, "scale_time",
                          "Solver time against the number of fibres (log-log), converged runs "
                          "only (exponents in [#tab:scale]'s caption).",
                          "time (s)", &ScalePoint::time_s);
    against_fibres_figure(
        page, study, "scale_memory",
        "Peak memory against the number of fibres (log-log), converged runs "
        "only: the process's resident memory (the largest process's under mpiexec).",
        "peak memory (MB)", &ScalePoint::peak_memory_mb);
    against_fibres_figure(page, study, "scale_proportional_memory",
                          "Peak proportional memory against the number of fibres (log-log), "
                          "converged runs only: the pages the process shares with others (the "
                          "libraries' code) counted as its share.",
                          "peak proportional memory (MB)",
                          &ScalePoint::peak_proportional_memory_mb);
  }
  if (auto finding = scale_finding(studies)) page.finding(*finding);
}

}  // namespace fibrecheck
