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

#include <string>
#include <vector>

#include "comparison.h"
#include "scene.h"
#include "tolerance_study_record.h"

namespace fibrecheck {

struct ToleranceStudyOptions {
  /// t_d as multiples of the smallest fibre radius.
  std::vector<double> tolerances = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
  /// The iterative runs also at these multiples of the scene's slices: its error against the
  /// continuous ground truth is that of its slices as much as that of its stopping criterion.
  std::vector<int> slice_factors = {1, 2, 4};
  /// Runs of the default rule stopped by its force estimate instead (solver.force_tolerance),
  /// at these relative force tolerances and the scene's t_d.
  std::vector<double> force_tolerances = {1e-2, 1e-3, 1e-4};
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

std::vector<ToleranceStudyScene> run_tolerance_study(const std::vector<Scene>& scenes,
                                                     const ToleranceStudyOptions& options,
                                                     const Solvers& solvers,
                                                     const std::string& folder);

/// Marks each method's Pareto front and fills the speed-ups at `levels` (NaN where no run of a
/// kind reaches a level).
void pareto_and_speedups(ToleranceStudyScene& scene, const std::vector<double>& levels);

}  // namespace fibrecheck
