#pragma once

#include <array>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "result.h"

namespace fibrecheck {

/// The comparison metrics of DESIGN §6, each relative and the worst over the scene:
///  - deflection: max over fibres and samples of ‖u_run − u_truth‖ / max‖u_truth‖;
///  - force: max over contact pairs of |F_run − F_truth| / F_truth on `total_force` (a pair only
///    one side has counts with the other's force as zero; pairs whose force is below 1e-9 of the
///    largest are measured against the largest);
///  - energy: |U_run − U_truth| / U_truth on `strain_energy_exact` (½ΣP·v).
struct Errors {
  double deflection = 0.0;
  double force = 0.0;
  double energy = 0.0;
  /// The largest of the three.
  double worst() const;
};

/// One contact pair of a comparison: the total force of each side (N) and its relative error; for
/// line and wall contacts also the error of the force distribution along the line, the largest
/// difference of the two cumulative force curves along fibres[0] relative to the truth's total
/// (a Kolmogorov distance, which needs no common points).
struct PairError {
  std::string kind;
  std::array<std::string, 2> fibres;
  double force_run = 0.0, force_truth = 0.0;
  double error = 0.0;
  double distribution_error = -1.0;  ///< −1 for point contacts
};

struct ErrorReport {
  Errors errors;
  std::vector<PairError> pairs;
};

/// A pair's force as the truth gives it: its extrapolated force where the reference extrapolated
/// its line contact (ContactResult::extrapolated_force), else its total force.
double truth_force(const ContactResult& pair);

/// The errors of `run` against `truth`, two results of the same scene (fibres matched by id,
/// contact pairs by kind and fibre ids in either order). Throws InputError naming `what` when the
/// two cannot be results of one scene (different fibres or sample counts).
ErrorReport measure_errors(const Result& run, const Result& truth, const std::string& what);

/// An iterative result's own estimate of its iteration error as Errors (NaN where it has none).
Errors estimated_errors(const Result& run);

/// The effectivity index of an error estimate, estimate / true error per metric: NaN where the
/// true error is at most `floor` (1e-10: round-off of the reference, nothing to estimate) or the
/// estimate is missing.
Errors effectivity(const Errors& estimate, const Errors& truth, double floor = 1e-10);
/// The same with a floor per metric.
Errors effectivity(const Errors& estimate, const Errors& truth, const Errors& floor);

/// What a ground truth can tell, per metric: the error below which an effectivity index is not
/// measured. Two converged solutions of one problem by different methods (the iterative method
/// converged far, the reference) differ by their round-off — on line contacts the compliance's
/// condition number times the machine's precision, 1e-9 to 1e-8 in line force at 100 slices — and
/// where deformed fibres cross, by where each settles the crossing's place; an error within three
/// times that `agreement` is not the run's own. Never below 1e-10.
Errors measurable_above(const Errors& agreement);

/// Least-squares slope of log(error) against log(n) over the points with error > 0: the observed
/// order of convergence p in error ∝ n^−p (returned as p; NaN with fewer than two usable points).
double observed_order(const std::vector<double>& n, const std::vector<double>& error);

/// {deflection_error, force_error, energy_error}; null for an error that is not a number.
nlohmann::json to_json(const Errors& errors);
void from_json(const nlohmann::json& j, Errors& errors);
/// Without `distribution_error` the pair is a point contact's.
nlohmann::json to_json(const PairError& pair);
void from_json(const nlohmann::json& j, PairError& pair);

}  // namespace fibrecheck
