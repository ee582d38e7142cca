#pragma once

// The slice study. Question: how fast does the iterative method's error fall as the slices that
// approximate a line contact grow (Figures 4.11–4.12, Eq. 4.28), and what does each slice count
// cost?
//
// Sample run:
//   fibrecheck study slices scenes/parallel_fibres.json --slices 2,4,8,16,32,64,128 --out study

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "comparison.h"
#include "metrics.h"
#include "scene.h"

namespace fibrecheck {

struct SliceStudyOptions {
  std::vector<int> slices = {2, 4, 8, 16, 32, 64, 128};
  bool quiet = false;
};

/// One slice count: the iterative solver with the scene's rule and tolerance at n slices, against
/// the scene's ground truth.
struct SliceStudyPoint {
  int slices = 0;
  double time_s = 0.0;
  long iterations = 0;
  std::string status;
  Errors errors;
};

struct SliceStudyScene {
  std::string scene, rule;
  double tolerance = 0.0;              ///< t_d of the iterative runs, mm
  double truth_time_s = 0.0;           ///< the ground truth's run time
  double truth_error_estimate = -1.0;  ///< its line force's estimated relative error (−1: exact)
  std::vector<SliceStudyPoint> points;
  Errors order;  ///< observed order of convergence per metric (error ∝ n^−order)
};

/// Runs the study on each scene, writing every point to `folder` when done (and skipping the
/// points already there), then `slice_study.json` and `slice_study.csv`.
std::vector<SliceStudyScene> run_slice_study(const std::vector<Scene>& scenes,
                                             const SliceStudyOptions& options,
                                             const Solvers& solvers, const std::string& folder);

nlohmann::json to_json(const SliceStudyScene& scene);

}  // namespace fibrecheck
