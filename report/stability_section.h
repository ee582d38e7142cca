#pragma once

#include <vector>

#include "report_page.h"
#include "stability_study_record.h"

namespace fibrecheck {

/// "Stability of the force update": per swept scene the iterations of the seed's rule against
/// c / c_crit (a figure); then the step sweep, the stiffness sweep and the extreme catalogue as
/// tables (each where it has rows), and data/stability.csv.
void write_stability_section(ReportPage& page, const std::vector<StabilityStudyScene>& studies);

}  // namespace fibrecheck
