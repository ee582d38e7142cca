#pragma once

#include <functional>
#include <optional>
#include <string>

#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// What the iteration reports while it runs (for progress on long runs).
struct IterationProgress {
  long iteration = 0;
  long max_iterations = 0;
  double overlap_residual = 0.0;    ///< mm
  double gap_force_residual = 0.0;  ///< mm
  double tolerance = 0.0;           ///< t_d, mm
  /// The t_d the iteration works to now: smaller than `tolerance` where the force tolerance made
  /// it so.
  double working_tolerance = 0.0;
  long normal_updates = 0;  ///< of the normals to the displaced centres, so far
  long radius_updates = 0;  ///< of the Tresca radii (Coulomb friction), so far
  bool coulomb = false;
  std::size_t contacts = 0;
  double elapsed_s = 0.0;
  int step = 0;   ///< of a load path, from 1
  int steps = 0;  ///< of the load path; 0 without one
};

/// Options of the iterative solver. Defaults come from the scene (`from_scene`); the command line
/// may override rule, c and slices.
struct SolverOptions {
  UpdateRule rule = UpdateRule::accelerated;
  std::optional<double> c;       ///< N/mm; required by rule seed
  double overlap_tolerance = 0;  ///< t_d, mm
  double energy_tolerance = 0;   ///< t_U, N·mm; 0 = off
  int energy_window = 10;        ///< n_i
  double force_tolerance = 0;    ///< relative; 0 = the seed's criteria alone
  long max_iterations = 100000;
  /// Candidate contacts are found this fraction of the smallest radius before they touch.
  double margin_factor = 0.1;
  /// Deformed contact, frictionless, rules auto, accelerated and cg: an update of the normals that
  /// leaves a residual above t_d but below this many t_d takes the error estimate's answer (0:
  /// never; the sequence of linearised problems alone).
  double exact_answer_below = 100.0;
  /// Called about once a second with the state of the iteration.
  std::function<void(const IterationProgress&)> progress;
  double progress_interval_s = 1.0;

  static SolverOptions from_scene(const Scene& scene);
  /// False with a reason when the options cannot be used.
  bool is_valid(std::string* error) const;
};

/// Runs the iterative method of the seed chapter on a validated scene and returns the result in
/// the shared schema (DESIGN §5). Never throws for a valid scene: numerical trouble becomes the
/// status `diverged`, `unresolvable` or `max_iterations` with a message.
Result solve_iteratively(const Scene& scene, const SolverOptions& options);

}  // namespace fibrecheck
