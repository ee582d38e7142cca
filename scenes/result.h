#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fibrecheck {

/// One point of a contact: where it acts and the force the first fibre of the pair receives.
struct ContactPoint {
  double position = 0.0;  ///< fraction of the length of fibres[0] from its start
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< mm, midpoint of the two centreline points
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< N, on fibres[0]
  /// Its parts (N, on fibres[0]): along the contact normal and the friction force (§4.3.4).
  Eigen::Vector3d normal_force = Eigen::Vector3d::Zero();
  Eigen::Vector3d friction_force = Eigen::Vector3d::Zero();
  /// With friction (μ > 0): "stick" (|F| < μN) or "slip" (|F| = μN); empty without.
  std::string state;
};

/// All contact points between one pair (fibre–fibre or fibre–wall).
struct ContactResult {
  std::array<std::string, 2> fibres;  ///< [idA, idB] or [fibreId, wallId]
  std::string kind;                   ///< "point" | "line" | "wall"
  double total_force = 0.0;           ///< N, magnitude of the resultant
  double normal_force = 0.0;          ///< N, magnitude of the normal parts' resultant
  double friction_force = 0.0;        ///< N, magnitude of the friction forces' resultant
  std::vector<ContactPoint> points;
  /// The reference's continuous line contact only (line and wall pairs): `total_force`
  /// extrapolated to infinitely many line points from its refinements (N).
  std::optional<double> extrapolated_force;
};

struct FibreResult {
  std::string id;
  /// One [dx,dy,dz] (mm) per sample at s = 0, 1/(samples−1), …, 1.
  std::vector<Eigen::Vector3d> displacement;
  /// The bending moments [M1, M2] (N·mm) in the fibre's planes (t, e1) and (t, e2) at the same
  /// samples (may be empty in results written without them).
  std::vector<Eigen::Vector2d> moment;
};

struct WallResult {
  std::string id;
  double force = 0.0;     ///< N, sum of the normal reactions
  double pressure = 0.0;  ///< MPa, force / area of the tow's footprint on the wall
  double area = 0.0;      ///< mm²
};

struct HistoryEntry {
  long iteration = 0;
  double max_overlap = 0.0;    ///< mm
  double strain_energy = 0.0;  ///< N·mm
};

/// How a run ended (DESIGN §5). Only `converged` is an answer; the others come with a message.
enum class Status {
  converged,       ///< a stopping criterion of §4.3.6 (or the exact contact solve) was met
  max_iterations,  ///< the cap on iterations came first
  diverged,        ///< growth, oscillation or non-finite numbers
  unresolvable,    ///< an overlap where no force can act (both fibres pinned there)
  beyond_reach     ///< the solver would need more memory than the machine has (the reference)
};

/// What ended the run.
enum class Criterion {
  contact,     ///< every contact just touching: |d| < t_d where a force acts, d < t_d elsewhere
  energy,      ///< the last n_i strain energies within t_U of the current one
  force,       ///< every contact just touching and the estimated force error within its tolerance
  active_set,  ///< the reference's active set solved exactly and the candidates settled
  max_iterations,  ///< the iteration cap
  growth,          ///< the residual grew without bound
  oscillation,     ///< no progress for a long stretch (c ≥ 2/λmax(W))
  non_finite,      ///< a non-finite force, displacement or energy
  unresolvable,    ///< see Status::unresolvable
  memory           ///< see Status::beyond_reach
};

const char* to_string(Status status);
const char* to_string(Criterion criterion);
/// The inverse of to_string; throws InputError naming `source` and the field otherwise.
Status parse_status(const std::string& text, const std::string& source);
Criterion parse_criterion(const std::string& text, const std::string& source);

/// One finished step of a load path (DESIGN §5 `steps[]`).
struct StepResult {
  double compaction = 1.0;
  double load_factor = 1.0;
  double fibre_volume_fraction = 0.0;
  std::vector<std::pair<std::string, double>> wall_pressure;  ///< per wall id, MPa
  double strain_energy = 0.0;       ///< N·mm, as the result's `strain_energy`
  double contacts_per_fibre = 0.0;  ///< contact points carrying force, each counted on both sides
  long iterations = 0;
  long geometric_updates = 0;    ///< the step's updates of the normals (deformed contact)
  long fixed_point_updates = 0;  ///< Coulomb friction: the step's as the result's `friction` counts
  /// mm, Coulomb's law on the step's answer as the result's `friction` reports it (0 without
  /// friction): the largest slip at a sticking point, and against the friction at a slipping one.
  double stick_residual = 0.0, slip_residual = 0.0;
  double wall_time_s = 0.0;
  Status status = Status::converged;
};

/// What only a finite-element solution has: the complementarity problem's largest |P·d| (N·mm),
/// its active-set steps summed over the outer iterations, the unknowns of the last mesh, the
/// strain energy Σ∫M²/(2EI) over the elements (N·mm) from the moment unknowns, and how its
/// continuous line contact was refined.
struct FiniteElementFigures {
  double complementarity_residual = 0.0;
  long active_set_iterations = 0;
  long unknowns = 0;
  double strain_energy_elements = 0.0;
  /// Continuous line contact refined until extrapolated: the refinement K it ended at, the
  /// observed order of the line force's convergence, and the estimated relative error of the
  /// extrapolated line force (0, 0, −1 when not extrapolated).
  int refinement = 0;
  double line_force_order = 0.0;
  double line_force_error_estimate = -1.0;
};

/// The seed's own test of an answer in the deformed configuration (§4.3.6 on Eq. 4.15), whatever
/// contact model produced it: the largest |gap| between displaced centres at a contact that pushes
/// and the largest overlap of displaced centres at a candidate that does not (mm).
struct DeformedTest {
  double gap_where_pushing = 0.0;
  double overlap_where_free = 0.0;
};

/// An iterative result's own estimate of its iteration error (against the exact answer of its
/// sliced problem), relative as DESIGN §6 defines the errors.
struct ErrorEstimate {
  double deflection = 0.0;
  double force = 0.0;
  double energy = 0.0;
  /// Active-set passes of the estimate, and whether the last left the pushing set unchanged.
  int passes = 0;
  bool settled = true;
  double time_s = 0.0;  ///< what making it cost (`wall_time_s`)
};

/// An estimate of the slicing error of a result: how far its deflections, contact forces and
/// strain energy lie from those of the continuous line contact, from a second run of the scene at
/// fewer slices and the orders at which the slice study sees the errors fall (relative, as DESIGN
/// §6 defines the errors).
struct SlicingEstimate {
  double deflection = 0.0;
  double force = 0.0;
  double energy = 0.0;
  int slices = 0;         ///< of the result
  int coarse_slices = 0;  ///< of the second run
  /// The assumed orders p of error ∝ n^−p.
  double deflection_order = 0.0, force_order = 0.0, energy_order = 0.0;
  /// A check of them (`observed_orders`): the orders the differences show from a third run at
  /// `coarser_slices` (NaN where a difference is zero or no third run was made).
  int coarser_slices = 0;
  double observed_deflection_order = NAN, observed_force_order = NAN, observed_energy_order = NAN;
  double time_s = 0.0;  ///< what the further runs cost (`wall_time_s`)
};

/// How well a frictional state meets Coulomb's law (μ > 0): the largest slip at a sticking point
/// (mm), the largest slip not along its friction force at a slipping point (mm, the part across F
/// and any part against it), and the largest excess of |F| over μN (N).
struct FrictionFigures {
  std::string model;  ///< "coulomb" | "seed"
  double mu = 0.0;
  double stick_residual = 0.0;
  double slip_residual = 0.0;
  double cone_residual = 0.0;
  long sticking = 0;  ///< points carrying force that stick
  long slipping = 0;  ///< and that slip
  /// Outer steps of the frictional solve: the iterative solver's Tresca radius updates, the
  /// reference's Newton steps.
  long fixed_point_updates = 0;
};

/// The result of either solver (DESIGN §5); the harness cannot tell the solvers apart.
struct Result {
  std::string scene;
  std::string solver;                 ///< "iterative" | "fem"
  std::string rule;                   ///< update rule (iterative) or method (fem)
  std::string geometry = "deformed";  ///< the contact model: "deformed" | "linearised"
  Status status = Status::max_iterations;
  Criterion criterion = Criterion::max_iterations;
  std::string message;
  long iterations = 0;
  double wall_time_s = 0.0;
  double strain_energy = 0.0;        ///< N·mm, trapezium rule at the slice spacing (Eq. 4.34)
  double strain_energy_exact = 0.0;  ///< N·mm, ½ΣP·v (with ½∫q·v for uniform loads)
  double max_overlap = 0.0;          ///< mm, largest overlap left (≤ 0 when all separate)
  double gap_force_residual = 0.0;   ///< mm, largest gap carrying a force
  double c = 0.0;                    ///< N/mm, step used (per point contact)
  double c_stable_limit = 0.0;       ///< N/mm, estimate of 2/λmax(W)
  double axial_load_dropped = 0.0;   ///< N, sum of |axial parts| dropped by the beam model
  /// Contact candidates of the final state (points the detector found within its margin, pushing
  /// or not): the size of the contact problem.
  long candidates = 0;
  /// Validity of small-deflection beam theory: the largest transverse displacement over the
  /// fibre's radius and the largest slope (rad) of any fibre, from the result's samples.
  double max_deflection_over_radius = 0.0;
  double max_slope = 0.0;
  DeformedTest deformed_test;
  /// Iterative results: the estimate of their iteration error, from the final state alone.
  std::optional<ErrorEstimate> error_estimate;
  /// On request (`solve --estimate-slicing`): the estimate of its slicing error.
  std::optional<SlicingEstimate> slicing_estimate;
  /// Deformed contact: how often the normals (and crossings) were made to follow the displaced
  /// centres between linearised problems (the reference: its exact solves beyond the first).
  long geometric_updates = 0;
  /// Iterative results: states that took the error estimate's answer (their linearised problem
  /// solved exactly on its pushing set), to settle the normals or to meet force_tolerance.
  long exact_answers = 0;
  /// Present in results of the finite-element reference.
  std::optional<FiniteElementFigures> finite_elements;
  /// Present when the scene has friction (μ > 0).
  std::optional<FrictionFigures> friction;
  std::vector<std::string> stages;
  std::vector<std::string> warnings;
  std::vector<FibreResult> fibres;
  std::vector<ContactResult> contacts;
  std::vector<WallResult> walls;
  std::vector<HistoryEntry> history;
  /// Scenes with a load path: one entry per finished step (the fields above are the last step's).
  std::vector<StepResult> steps;
};

/// Replaces every non-finite number of the result by zero; true when there was one. Both solvers
/// call it last, so that no result ever holds a NaN or an infinity (a converged status then
/// becomes `diverged`, criterion `non_finite`).
bool replace_non_finite(Result& result);

/// Two lines a person reads: status, criterion, iterations, time, energies, overlap (and the
/// message, if any, on a third).
std::string brief_report(const Result& result);

nlohmann::json result_to_json(const Result& result);
/// Reads a result back; throws InputError naming `source` and the field on a malformed result.
Result result_from_json(const nlohmann::json& document, const std::string& source);
Result read_result(const std::string& path);
/// Writes the result atomically (temporary file + rename).
void write_result(const std::string& path, const Result& result);

}  // namespace fibrecheck
