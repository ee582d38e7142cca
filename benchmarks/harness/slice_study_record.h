#pragma once

// The slice study's records, as slice_study.json holds them: what the harness writes and the
// report reads. The JSON's field names are read by outside tools too: they do not change.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "metrics.h"

namespace fibrecheck {

/// One slice count: the iterative solver with the scene's rule and tolerance at n slices, against
/// the scene's ground truth.
struct SliceStudyPoint {
  int slices = 0;
  double time_s = 0.0;  ///< `iterative_time_s`
  long iterations = 0;
  std::string status;
  Errors errors;
};

struct SliceStudyScene {
  std::string scene, rule;
  double tolerance = 0.0;              ///< t_d of the iterative runs, mm (`overlap_tolerance`)
  double truth_time_s = 0.0;           ///< the ground truth's run time
  double truth_error_estimate = -1.0;  ///< its line force's estimated relative error (−1: exact)
  std::vector<SliceStudyPoint> points;
  Errors order;  ///< observed order of convergence per metric (error ∝ n^−order; NaN: none)
};

nlohmann::json to_json(const SliceStudyPoint& point);
void from_json(const nlohmann::json& j, SliceStudyPoint& point);
nlohmann::json to_json(const SliceStudyScene& scene);
void from_json(const nlohmann::json& j, SliceStudyScene& scene);

}  // namespace fibrecheck
