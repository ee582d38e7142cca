#pragma once

#include <string>
#include <vector>

namespace fibrecheck {

/// A numbered table of the report: its caption says what produced it (scene, rule, tolerance,
/// slices); cells are text, already formatted.
struct Table {
  std::string label;    ///< e.g. "comparison" (file tables/comparison.tex, \label{tab:comparison})
  std::string caption;  ///< one sentence or two, without the number
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// The table in Markdown (a pipe table, its caption above as "Table N. …").
std::string markdown(const Table& table, int number);

/// The table as a LaTeX table environment with booktabs rules, to be \input; special characters of
/// the cells and caption escaped.
std::string latex(const Table& table);

/// A number for a table: three significant digits in scientific notation ("1.23e-04"), "–" for
/// NaN.
std::string sci(double value);
/// A time in seconds with four significant digits.
std::string seconds(double value);
/// A number with three decimals ("0.452"), "–" for NaN.
std::string fixed3(double value);

/// Text with LaTeX's special characters escaped.
std::string latex_escape(const std::string& text);

}  // namespace fibrecheck
