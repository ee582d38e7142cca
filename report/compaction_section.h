#pragma once

#include <vector>

#include "report_data.h"
#include "report_page.h"

namespace fibrecheck {

/// "Compaction": per scene the compaction curves of every run with the van Wyk and Toll fits, the
/// strain energy per step, the iterative curves' differences from the reference's, and
/// cross-sections of the kept states (figures); then the fits and the agreement as tables.
void write_compaction_section(ReportPage& page, const std::vector<StoredCompactionStudy>& studies);

}  // namespace fibrecheck
