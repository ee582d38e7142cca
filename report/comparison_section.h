#pragma once

#include <vector>

#include "report_data.h"
#include "report_page.h"

namespace fibrecheck {

/// "Accuracy on each scene": the comparison table (the user's run against the ground truth, split
/// into iteration and slicing errors; the headline), and per scene with results its
/// cross-section, the convergence history of the user's run and the most deflected fibre by both
/// solvers.
void write_comparison_section(ReportPage& page, const std::vector<StoredComparison>& comparisons);

}  // namespace fibrecheck
