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
/// the cells and caption escaped, text columns flush left and numeric ones right, the whole
/// scaled down to the line width where it is wider.
std::string latex(const Table& table);

/// A number for a table: three significant digits in scientific notation ("1.23e-04"), "–" for
/// NaN.
std::string sci(double value);
/// A time in seconds with four significant digits.
std::string seconds(double value);
/// A number with three decimals ("0.452"), "–" for NaN.
std::string fixed3(double value);
/// A count (iterations, contacts), its digits grouped in threes by a thin space from 10 000 up
/// ("366 784"; "3370" as it is), as the SI brochure writes numbers; LaTeX gets "\,".
std::string count(long value);

/// Text with LaTeX's special characters escaped, its UTF-8 symbols as LaTeX and its numbers in
/// scientific notation typeset (4.85e-08 as 4.85 × 10⁻⁸).
std::string latex_escape(const std::string& text);

/// A text of the report as LaTeX: "$…$" is mathematics and goes through as it is, "[@key]" cites
/// (\cite{key}), "[#tab:label]" and "[#fig:label]" refer to a table or figure (Table~\ref{…}),
/// the rest is latex_escape'd.
std::string latex_text(const std::string& text);

}  // namespace fibrecheck
