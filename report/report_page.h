#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gnuplot.h"
#include "report_writer.h"
#include "tables.h"

namespace fibrecheck {

/// The report being assembled in its folder: the Markdown and LaTeX bodies, the numbered tables
/// (tables/*.tex) and figures (figures/*.png|svg|pdf, drawn by gnuplot), and the numbers
/// (data/*.csv).
/// A section of the report writes through it; `finish` puts the title, the preamble and the list
/// of what was read around the bodies.
class ReportPage {
 public:
  explicit ReportPage(const std::string& folder);

  /// A section: its title and the paragraph that opens it.
  void section(const std::string& title, const std::string& text);
  /// One of the key findings, listed at the top of the report (a sentence, in the texts' markup).
  void finding(const std::string& text);
  /// The next numbered table, in the body or in the appendix (long tables a reader looks up
  /// rather than reads; `appendix_title` names the appendix section it opens there).
  void table(const Table& table);
  void appendix_table(const std::string& appendix_title, const Table& table);
  /// The next numbered figure, `name`.png and .svg, from a gnuplot script `body` over `series`
  /// (see Gnuplot::plot). A figure gnuplot cannot draw is left out and named in the summary.
  void figure(const std::string& name, const std::string& caption, const std::string& body,
              const std::vector<Gnuplot::Series>& series);
  /// data/`name`.csv.
  void csv(const std::string& name, const std::vector<std::string>& header,
           const std::vector<std::vector<std::string>>& rows);
  /// Writes report.md and report.tex; `sources` are the data files read.
  ReportSummary finish(const std::vector<std::string>& sources);

  ReportSummary& summary() { return summary_; }

 private:
  std::filesystem::path folder_;
  Gnuplot gnuplot_;
  std::ostringstream md_, tex_;
  /// Numbered after the body's tables, as LaTeX numbers them where they stand.
  std::vector<std::pair<std::string, Table>> appendix_;
  std::vector<std::string> findings_;
  std::vector<std::pair<std::string, std::string>> numbers_;  ///< "tab:x" → "Table 3"
  /// The Markdown with every "[#tab:x]" and "[#fig:x]" as the number it has.
  std::string with_numbers(std::string markdown) const;
  ReportSummary summary_;
};

}  // namespace fibrecheck
