#pragma once

#include <vector>

#include "report_page.h"
#include "slice_study_record.h"

namespace fibrecheck {

/// "Accuracy against the number of slices": per scene the errors against n with their observed
/// orders (a figure), then one table of every scene's points, and data/slice_study.csv.
void write_slice_section(ReportPage& page, const std::vector<SliceStudyScene>& studies);

}  // namespace fibrecheck
