#pragma once

#include <string>
#include <vector>

#include "report_data.h"

namespace fibrecheck {

/// What `write_report` made.
struct ReportSummary {
  int tables = 0;
  int figures = 0;
  std::vector<std::string> missing;  ///< figures not drawn, and why
  std::string headline;              ///< the headline tables as text, for the terminal
};

/// Writes the report of `data` into `folder` (DESIGN §6): report.md with numbered tables and
/// figures in the manner of a thesis results chapter, report.tex with tables/*.tex (booktabs) and
/// figures/*.png|svg|pdf (gnuplot), and data/*.csv. It formats what the harness measured and
/// computes no physics. Without gnuplot the tables still come out and `missing` says why the figures did
/// not.
ReportSummary write_report(const ReportData& data, const std::string& folder);

}  // namespace fibrecheck
