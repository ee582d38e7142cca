#pragma once

// A comparison's record, as compare.json holds it: what the harness writes and the report reads.
// The JSON's field names are read by outside tools too: they do not change.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "metrics.h"

namespace fibrecheck {

/// One run of a comparison: who ran, how it ended, what it cost, its step c (N/mm).
struct RunSummary {
  std::string solver, rule, status, criterion;
  long iterations = 0;
  double wall_time_s = 0.0;
  double c = 0.0, c_stable_limit = 0.0;
};

nlohmann::json to_json(const RunSummary& run);
void from_json(const nlohmann::json& j, RunSummary& run);

/// One scene's comparison (DESIGN §6). The errors and pairs are there only when `comparable`.
struct ComparisonRecord {
  std::string scene;
  bool comparable = true;
  std::string reason;  ///< why not, when not comparable (`not_comparable`)
  /// By label: "user", "converged", "reference_slices", and "reference_continuous" where it ran.
  std::map<std::string, RunSummary> runs;
  std::string rule;                    ///< the user's run's
  double c = 0.0;                      ///< the user's run's, N/mm
  std::string ground_truth;            ///< the label of the run the errors are measured against
  double truth_error_estimate = -1.0;  ///< `ground_truth_error_estimate`
  Errors total;  ///< the user's run against the ground truth (flat in the object)
  Errors iteration, slicing, agreement;  ///< `iteration_error`, `slicing_error`, `agreement_error`
  /// `geometry_error`: the linearised reference against the deformed one on the same slices (NaN
  /// where the other geometry did not run); `geometry` is the user's run's contact geometry.
  Errors geometry;
  std::string geometry_model = "deformed";
  /// `error_estimate`: the user's run's own estimate of its iteration error; `effectivity`: that
  /// estimate over the iteration error measured (NaN where either is missing or the error is
  /// within what the truth can tell, measurable_above of the agreement).
  Errors estimate{NAN, NAN, NAN}, effectivity{NAN, NAN, NAN};
  std::vector<PairError> pairs;  ///< each pair's force of the user's run is `force_user`
  /// Files beside compare.json by label ("scene", "user", the runs' labels).
  std::map<std::string, std::string> files;

  /// The user's run.
  const RunSummary& user() const { return runs.at("user"); }
  /// The ground truth's run, or none where the record does not hold it.
  const RunSummary* truth() const {
    const auto run = runs.find(ground_truth);
    return run != runs.end() ? &run->second : nullptr;
  }
};

nlohmann::json to_json(const ComparisonRecord& record);
void from_json(const nlohmann::json& j, ComparisonRecord& record);

}  // namespace fibrecheck
