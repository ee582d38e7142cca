#include "report_writer.h"

#include "compaction_section.h"
#include "comparison_section.h"
#include "estimate_section.h"
#include "friction_section.h"
#include "report_page.h"
#include "scale_section.h"
#include "slice_section.h"
#include "stability_section.h"
#include "tolerance_section.h"

namespace fibrecheck {

ReportSummary write_report(const ReportData& data, const std::string& folder) {
  ReportPage page(folder);
  write_comparison_section(page, data.comparisons);
  write_slice_section(page, data.slice_studies);
  write_tolerance_section(page, data.tolerance_studies);
  write_estimate_section(page, data.comparisons, data.tolerance_studies);
  write_stability_section(page, data.stability_studies);
  write_compaction_section(page, data.compaction_studies);
  write_friction_section(page, data.friction_study);
  write_scale_section(page, data.scale_studies);
  return page.finish(data.sources);
}

}  // namespace fibrecheck
