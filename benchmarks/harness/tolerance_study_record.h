#pragma once

// The tolerance study's records, as tolerance_study.json holds them: what the harness writes and
// the report reads. The JSON's field names are read by outside tools too: they do not change.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "metrics.h"

namespace fibrecheck {

struct TolerancePoint {
  /// "seed 0.5", "auto", "accelerated", "accelerated (force)" (stopped by solver.force_tolerance,
  /// then `parameter` is that tolerance), "reference"
  std::string method;
  double parameter = 0;  ///< t_d (mm) for the iterative rules, K for the reference
  int slices = 0;
  double time_s = 0;
  long iterations = 0;
  std::string status;
  Errors errors;
  bool pareto = false;  ///< on its method's Pareto front of error against time
  /// Iterative runs: their own estimate of the iteration error (`error_estimate`) and its
  /// effectivity index against the reference on the same slices (NaN where the error is within
  /// what that reference can tell, measurable_above).
  Errors estimate{NAN, NAN, NAN}, effectivity{NAN, NAN, NAN};
};

struct SpeedUp {
  double error_level = 0;
  double iterative_time_s = NAN, reference_time_s = NAN;  ///< NaN: no run of that kind reached it
  std::string iterative_method;  ///< the fastest iterative run that reaches the level
  double speedup() const { return reference_time_s / iterative_time_s; }
};

struct ToleranceStudyScene {
  std::string scene;
  std::string truth;  ///< "reference_continuous" or "reference_slices" (`ground_truth`)
  double truth_error_estimate = -1.0;
  std::vector<TolerancePoint> points;
  std::vector<SpeedUp> speedups;
};

nlohmann::json to_json(const TolerancePoint& point);
void from_json(const nlohmann::json& j, TolerancePoint& point);
nlohmann::json to_json(const SpeedUp& speedup);
void from_json(const nlohmann::json& j, SpeedUp& speedup);
nlohmann::json to_json(const ToleranceStudyScene& scene);
void from_json(const nlohmann::json& j, ToleranceStudyScene& scene);

}  // namespace fibrecheck
