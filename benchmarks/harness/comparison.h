#pragma once

#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "comparison_record.h"
#include "metrics.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// How wrong is the iterative method on this scene, and why (DESIGN §6)? One scene's runs:
///  - `user`: the iterative solver as the scene says (what a user gets);
///  - `converged`: the same, its overlap tolerance at 1e-4 of the scene's (no iteration error);
///  - `slices`: the reference on the same slices (the exact answer of the sliced problem);
///  - `continuous`: the reference's continuous line contact, where the scene has line contacts or
///    walls (the ground truth; without them the sliced problem is the problem itself).
/// `total` is the user's error against the ground truth, split into `iteration` (user against
/// `slices`: what the stopping criterion leaves) and `slicing` (`slices` against `continuous`:
/// what the slices leave); `agreement` checks the cross-check itself (`converged` against
/// `slices`, which must agree to the reference's round-off).
struct Comparison {
  std::string scene;
  bool comparable = true;
  std::string reason;  ///< why not, when not comparable
  Result user, converged, slices;
  std::optional<Result> continuous;
  /// The reference on the same slices in the other contact geometry (DESIGN §3), where it ran.
  std::optional<Result> other_geometry;
  ErrorReport total, iteration, slicing, agreement;
  /// The linearised reference against the deformed one, same slices: what the small-deflection
  /// contact costs on the scene (empty where the other geometry did not run or did not converge).
  ErrorReport geometry;
  /// How well the ground truth knows its line force (relative; −1 when it is exact or unknown).
  double truth_error_estimate = -1.0;

  const Result& truth() const { return continuous ? *continuous : slices; }
};

/// The solvers the harness runs, given by the caller (the harness itself links no solver).
struct Solvers {
  std::function<Result(const Scene&)> iterative;
  /// The reference on the scene's slices.
  std::function<Result(const Scene&)> reference_slices;
  /// The reference's continuous line contact, refined until its line force is extrapolated.
  std::function<Result(const Scene&)> reference_continuous;
  /// The reference's continuous line contact at refinement K (n·2^K cells), for its own cost.
  std::function<Result(const Scene&, int)> reference_refined;
};

/// The ground truth of a scene: the continuous reference where it has line or wall contacts,
/// else the reference on slices (point contacts only: slicing changes nothing).
Result ground_truth(const Scene& scene, const Solvers& solvers);

/// The ground truth computed once and kept in `folder` as `<scene>.truth.result.json`: a study
/// run again reads it instead.
Result stored_ground_truth(const Scene& scene, const Solvers& solvers, const std::string& folder);

/// The seed rule's stable limit on the scene's c (its result's `c_stable_limit`), from one
/// iteration of it.
double seed_stable_limit(const Scene& scene, const Solvers& solvers);

/// Whether the scene has line or wall contacts to refine (tow fibres in pairs, or walls).
bool needs_continuous_reference(const Scene& scene);

/// Runs the four solutions of one scene and compares them. `progress` hears one line a run.
Comparison compare_scene(const Scene& scene, const Solvers& solvers,
                         const std::function<void(const std::string&)>& progress = {});

/// Compares results already computed (`continuous` and `other_geometry` may be absent).
Comparison compare_results(const std::string& scene, const Result& user, const Result& converged,
                           const Result& slices, const std::optional<Result>& continuous,
                           const std::string& reason = "",
                           const std::optional<Result>& other_geometry = std::nullopt);

/// The scene in the contact geometry it does not ask for.
Scene in_other_geometry(const Scene& scene);

/// The label of the reference on slices in the other geometry: "reference_slices_linearised" or
/// "reference_slices_deformed".
std::string other_geometry_label(const Scene& scene);

/// The comparison's record (DESIGN §6): errors, their split, per-pair rows, and every run's
/// time, iterations, rule and c. Result files are named in `files` (label → file name).
ComparisonRecord record_of(const Comparison& comparison,
                           const std::vector<std::pair<std::string, std::string>>& files = {});

/// The comparison as `compare.json`: its record.
nlohmann::json to_json(const Comparison& comparison,
                       const std::vector<std::pair<std::string, std::string>>& files = {});

/// Writes one scene's comparison into `folder`: scene.json, every run's result
/// (user.result.json, converged.result.json, reference_slices.result.json and, where it ran,
/// reference_continuous.result.json) and compare.json naming them.
void write_comparison(const std::string& folder, const Scene& scene, const Comparison& comparison);

/// A short table of comparisons, one line each.
std::string comparison_table(const std::vector<Comparison>& comparisons);

}  // namespace fibrecheck
