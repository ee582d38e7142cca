#pragma once

#include <vector>

#include "report_page.h"
#include "scale_study_record.h"

namespace fibrecheck {

/// "Scale": per study the cost of every run against the tow size (a table, the fitted exponents
/// in its caption) and the converged runs' time against the number of fibres (a figure).
void write_scale_section(ReportPage& page, const std::vector<ScaleStudy>& studies);

}  // namespace fibrecheck
