#pragma once

#include <vector>

#include "friction_study_record.h"
#include "report_page.h"

namespace fibrecheck {

/// "The seed's friction rule": per tow size how each run of the seed's rule and of Coulomb
/// friction ended over μ and the fibre volume fraction (a figure), a table of both friction models'
/// runs side by side, a key finding, and data/friction.csv.
void write_friction_section(ReportPage& page, const std::vector<FrictionPoint>& points);

}  // namespace fibrecheck
