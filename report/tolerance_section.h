#pragma once

#include <vector>

#include "report_page.h"
#include "tolerance_study_record.h"

namespace fibrecheck {

/// "Accuracy against run time": per scene the error of every converged run against its run time
/// with each method's Pareto front (a figure), then the speed-up at equal error (a table, part of
/// the headline), data/speedup.csv and data/tolerance_study.csv.
void write_tolerance_section(ReportPage& page, const std::vector<ToleranceStudyScene>& studies);

}  // namespace fibrecheck
