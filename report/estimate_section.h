#pragma once

#include <vector>

#include "report_data.h"
#include "report_page.h"

namespace fibrecheck {

/// "Error estimates": how well each iterative run's own estimate of its iteration error matches
/// the iteration error measured against the reference on the same slices — a table of
/// effectivity indices (estimate / true error) per scene, for the user's run of each comparison
/// and the iterative runs of each tolerance study; a figure of estimated against true error over
/// all of them; and data/effectivity.csv.
void write_estimate_section(ReportPage& page, const std::vector<StoredComparison>& comparisons,
                            const std::vector<ToleranceStudyScene>& studies);

}  // namespace fibrecheck
