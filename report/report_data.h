#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compaction_study_record.h"
#include "comparison_record.h"
#include "friction_study_record.h"
#include "result.h"
#include "scale_study_record.h"
#include "scene.h"
#include "slice_study_record.h"
#include "stability_study_record.h"
#include "tolerance_study_record.h"

namespace fibrecheck {

/// One comparison as the harness stored it: compare.json and the result files beside it.
struct StoredComparison {
  std::string folder;
  ComparisonRecord summary;  ///< compare.json
  Result user;               ///< the user's run
  Result truth;              ///< the ground truth it was measured against
  bool has_results = false;
  std::optional<Scene> scene;  ///< the scene itself, where the comparison kept it
};

/// One scene of a compaction study and the folder its compaction_study.json was found in: the
/// scene file and the kept states it names are relative to it.
struct StoredCompactionStudy {
  std::string folder;
  CompactionStudyScene study;
};

/// Everything the report reads: the harness's data, found anywhere below the folders given, as
/// the harness's own records.
struct ReportData {
  std::vector<StoredComparison> comparisons;
  std::vector<SliceStudyScene> slice_studies;             ///< slice_study.json entries
  std::vector<ToleranceStudyScene> tolerance_studies;     ///< tolerance_study.json entries
  std::vector<StabilityStudyScene> stability_studies;     ///< stability_study.json entries
  std::vector<StoredCompactionStudy> compaction_studies;  ///< compaction_study.json entries
  std::vector<ScaleStudy> scale_studies;                  ///< scale_study.json objects
  std::vector<FrictionPoint> friction_study;              ///< friction_study.json entries
  std::vector<std::string> sources;                       ///< the files read
};

/// Reads every compare.json, slice_study.json, tolerance_study.json, stability_study.json,
/// compaction_study.json, scale_study.json and friction_study.json below `folders`, in the order of
/// their paths. Throws InputError naming a folder that does not exist or a file that is not the
/// harness's (malformed, or a record without a field the harness writes).
ReportData read_report_data(const std::vector<std::string>& folders);

}  // namespace fibrecheck
