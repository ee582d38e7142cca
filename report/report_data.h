#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// One comparison as the harness stored it: compare.json and the result files beside it.
struct StoredComparison {
  std::string folder;
  nlohmann::json summary;  ///< compare.json
  Result user;             ///< the user's run
  Result truth;            ///< the ground truth it was measured against
  bool has_results = false;
  std::optional<Scene> scene;  ///< the scene itself, where the comparison kept it
};

/// Everything the report reads: the harness's data, found anywhere below the folders given.
struct ReportData {
  std::vector<StoredComparison> comparisons;
  nlohmann::json slice_studies = nlohmann::json::array();      ///< slice_study.json entries
  nlohmann::json tolerance_studies = nlohmann::json::array();  ///< tolerance_study.json entries
  nlohmann::json stability_studies = nlohmann::json::array();  ///< stability_study.json entries
  /// compaction_study.json entries, each with the `folder` it was found in.
  nlohmann::json compaction_studies = nlohmann::json::array();
  nlohmann::json scale_studies = nlohmann::json::array();  ///< scale_study.json objects
  std::vector<std::string> sources;                        ///< the files read
};

/// Reads every compare.json, slice_study.json, tolerance_study.json, stability_study.json,
/// compaction_study.json and scale_study.json
/// below `folders`. Throws InputError naming a folder that does not exist or a file that is not
/// the harness's.
ReportData read_report_data(const std::vector<std::string>& folders);

}  // namespace fibrecheck
