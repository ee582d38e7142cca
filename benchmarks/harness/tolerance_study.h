#pragma once

// The tolerance study. Question: how much accuracy does each method buy for its run time, and how
// much faster than the implicit reference is the iterative method at equal error?
//
// Each update rule of the iterative method (`seed` at fractions of its stable step, `auto`,
// `accelerated`) is run at overlap tolerances t_d over several decades and at several slice counts,
// and the reference's
// continuous line contact at several refinements; every point's error is measured against the
// scene's ground truth (its worst of the deflection, force and energy errors, DESIGN §6). Each
// method's Pareto front, and at each error level the fastest run of either kind that reaches it,
// give the speed-up at equal error.
//
// Sample run:
//   fibrecheck study tolerance scenes/small_tow_19.json --out study

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "comparison.h"
#include "metrics.h"
#include "scene.h"

namespace fibrecheck {

struct ToleranceStudyOptions {
  /// t_d as multiples of the smallest fibre radius.
  std::vector<double> tolerances = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
  /// The iterative runs also at these multiples of the scene's slices: its error against the
  /// continuous ground truth is that of its slices as much as that of its stopping criterion.
  std::vector<int> slice_factors = {1, 2, 4};
  /// The seed's c as fractions of its stable limit 2/λmax(D½WD½).
  std::vector<double> seed_fractions = {0.9};
  /// The reference's refinements K (continuous line contact; scenes with point contacts only run
  /// the reference once, exact).
  std::vector<int> refinements = {0, 1, 2, 3};
  std::vector<double> error_levels = {1e-2, 1e-3};
  /// A cap on each iterative run, so that a slow rule ends as `max_iterations`, not a hang.
  long max_iterations = 50000;
  /// Measure against the reference on the scene's own slices instead of the continuous line
  /// contact: the solution method alone, for tows whose continuous reference is out of reach
  /// (the iterative runs then keep the scene's slices, and the reference is one exact point).
  bool against_slices = false;
  bool quiet = false;
};

struct TolerancePoint {
  std::string method;    ///< "seed 0.5", "auto", "accelerated", "reference"
  double parameter = 0;  ///< t_d (mm) for the iterative rules, K for the reference
  int slices = 0;
  double time_s = 0;
  long iterations = 0;
  std::string status;
  Errors errors;
  bool pareto = false;  ///< on its method's Pareto front of error against time
};

struct SpeedUp {
  double error_level = 0;
  double iterative_time_s = NAN, reference_time_s = NAN;
  std::string iterative_method;  ///< the fastest iterative run that reaches the level
  double speedup() const { return reference_time_s / iterative_time_s; }
};

struct ToleranceStudyScene {
  std::string scene;
  std::string truth;  ///< "reference_continuous" or "reference_slices"
  double truth_error_estimate = -1.0;
  std::vector<TolerancePoint> points;
  std::vector<SpeedUp> speedups;
};

std::vector<ToleranceStudyScene> run_tolerance_study(const std::vector<Scene>& scenes,
                                                     const ToleranceStudyOptions& options,
                                                     const Solvers& solvers,
                                                     const std::string& folder);

/// Marks each method's Pareto front and fills the speed-ups at `levels` (NaN where no run of a
/// kind reaches a level).
void pareto_and_speedups(ToleranceStudyScene& scene, const std::vector<double>& levels);

nlohmann::json to_json(const ToleranceStudyScene& scene);

}  // namespace fibrecheck
