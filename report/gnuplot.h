#pragma once

#include <string>
#include <utility>
#include <vector>

namespace fibrecheck {

/// Draws the report's figures with gnuplot, each as `<folder>/<name>.png`, `.svg` and `.pdf` (the
/// one pdflatex takes), from a script and data files kept in `<folder>/src/` (so that a reader can
/// restyle a figure and draw it again with `gnuplot src/<name>.gp` in the figures folder).
class Gnuplot {
 public:
  explicit Gnuplot(std::string folder);

  /// Whether a gnuplot program can be run (FIBRECHECK_GNUPLOT names it, else "gnuplot").
  bool available() const { return available_; }
  const std::string& program() const { return program_; }

  /// A series: its data file's rows (whitespace-separated numbers).
  struct Series {
    std::string rows;
  };

  /// Writes the series as src/<name>.<k>.dat (referred to in `body` as @DATAk@, k from
  /// 0) and the script, and draws the PNG and the SVG. Returns false (and a reason in `why`)
  /// when gnuplot failed or drew nothing.
  bool plot(const std::string& name, const std::string& body, const std::vector<Series>& series,
            std::string* why);

 private:
  std::string folder_, program_;
  bool available_ = false;
};

/// A series' rows, or one row of `columns` NaNs where it has none: gnuplot refuses to plot an
/// empty data file, and a series with nothing in it is still named in the legend.
std::string rows_or_nan(const std::string& rows, int columns = 2);

}  // namespace fibrecheck
