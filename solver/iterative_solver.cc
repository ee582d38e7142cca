#include "iterative_solver.h"

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "ambiguous_sides.h"
#include "carry_over.h"
#include "compliance_operator.h"
#include "contact_detection.h"
#include "contact_results.h"
#include "convergence.h"
#include "error_estimate.h"
#include "fibre.h"
#include "force_update.h"
#include "iteration_state.h"
#include "iterative_result.h"
#include "load_path_solve.h"
#include "slip_origins.h"
#include "superposition.h"
#include "termination.h"
#include "tresca_radii.h"
#include "unresolvable_overlap.h"
#include "working_set.h"

namespace fibrecheck {

SolverOptions SolverOptions::from_scene(const Scene& scene) {
  SolverOptions o;
  o.rule = scene.solver.rule;
  o.c = scene.solver.c;
  o.overlap_tolerance = scene.overlap_tolerance();
  o.energy_tolerance = scene.solver.energy_tolerance;
  o.energy_window = scene.solver.energy_window;
  o.force_tolerance = scene.solver.force_tolerance;
  o.max_iterations = scene.solver.max_iterations;
  return o;
}

bool SolverOptions::is_valid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (rule == UpdateRule::seed && !c) return fail("rule seed needs the step c");
  if (c && !(*c > 0.0 && std::isfinite(*c))) return fail("c must be positive and finite");
  if (!(overlap_tolerance > 0.0)) return fail("overlap tolerance must be positive");
  if (energy_tolerance < 0.0) return fail("energy tolerance must not be negative");
  if (energy_window < 1) return fail("energy window must be at least 1");
  if (max_iterations < 1) return fail("max iterations must be at least 1");
  if (!(margin_factor > 0.0)) return fail("margin factor must be positive");
  if (!(exact_answer_below >= 0.0)) return fail("exact_answer_below must not be negative");
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double longest_fibre(const std::vector<Fibre>& fibres) {
  double longest = 0.0;
  for (const Fibre& f : fibres) longest = std::max(longest, f.length);
  return longest;
}

/// Whether the history keeps iteration `now`, the last one having been `before`: every iteration up
/// to 100, then about 40 per decade.
bool record_history(long now, long before) {
  if (now <= 100) return true;
  return std::floor(std::log10(static_cast<double>(now)) * 40.0) !=
         std::floor(std::log10(static_cast<double>(before)) * 40.0);
}

/// The iteration of §4.3.2 on one scene (one load step): detect the candidate contacts on the
/// deformed fibres, superpose the beam deflections of every force, measure the overlaps, update
/// the forces by the rule, and repeat until a criterion of §4.3.6 stops it.
class IterativeSolver {
 public:
  IterativeSolver(const Scene& scene, const SolverOptions& options);

  Result run();
  /// Starts from another state's contacts (the previous step of a load path): those found again
  /// keep their force.
  void start_from(std::vector<Contact> contacts, SlipOrigins origins) {
    state_.contacts = std::move(contacts);
    origins_ = std::move(origins);
    attached_ = false;
  }
  const std::vector<Contact>& contacts() const { return state_.contacts; }
  /// Where the next step's slip is measured from, after `run`.
  SlipOrigins end_state(const Result& result) const {
    return SlipOrigins(state_.contacts, state_.u_a, state_.u_b, result);
  }

 private:
  void evaluate(bool follow_geometry);
  void follow_crossings();
  bool follows_the_fibres_now(long iteration, double residual);
  void record(long iteration, long before);
  bool just_touching(double t) const;
  bool coulomb_holds(double t);
  FrictionFigures coulomb_figures() const {
    return friction_figures(state_.contacts, mu_, scene_.contact.friction_model);
  }
  std::optional<Termination> forces_accurate_enough();
  void take_the_answer(std::vector<Contact> answer);
  bool must_measure_again();
  bool settle_normals_exactly(double residual);
  void sequence_starts_afresh();
  std::optional<Termination> diverging(long iteration, double residual);
  Termination stalled_within_scene_tolerance(const Termination& verdict,
                                             bool at_best_update = false);
  long update(long iteration);
  std::optional<Termination> follow_the_fibres(long done);

  void detect_contacts();
  void compute_grid();
  double largest_move();
  void estimate_step();
  std::optional<std::string> find_unresolvable() const;
  std::optional<Termination> detect_again();
  double watched_residual() const;
  void remember_best(double residual);
  void restore_best();
  void remember_best_update(double residual);
  bool return_to_best_update();
  void report_progress(long iteration, Clock::time_point start);
  std::string capped_message() const;
  Result finish(const Termination& end, long iterations, Clock::time_point start);

  const Scene& scene_;
  SolverOptions options_;
  std::vector<Fibre> fibres_;
  Superposition superposition_;
  double margin_;
  ContactDetector detector_;
  DivergenceMonitor divergence_;
  EnergyWindow energy_window_;
  double mu_;
  bool coulomb_;        ///< Coulomb friction, as a Tresca fixed point
  bool seed_friction_;  ///< the seed's friction rule (Eqs. 4.29–4.33)
  SlipOrigins origins_;
  IterationState state_;
  std::unique_ptr<ForceUpdate> rule_;
  WorkingSet working_set_;
  bool use_working_set_;
  TrescaRadii tresca_;
  /// Deformed contact under rules auto and accelerated: normals follow the displaced centres only
  /// between the linearised problems (the seed's rule follows them at every iteration).
  bool lagged_normals_;
  long geometric_updates_ = 0;
  double least_after_update_ = INFINITY;  ///< the smallest residual an update of the normals left
  /// Of what the last update left: the residual the linearised problem is solved to before
  /// normals next follow; a tenth, down to a hundredth after updates that made no progress.
  double follow_fraction_ = 0.1;
  static constexpr double kSmallestFollowFraction = 0.01;
  double follow_below_ = INFINITY;    ///< the residual at which normals next follow the fibres
  double last_force_estimate_ = NAN;  ///< relative, when force_tolerance last asked
  double least_since_followed_ = INFINITY;  ///< the linearised problem's smallest residual so far
  long least_since_followed_at_ = 0;        ///< and the iteration that reached it
  /// Iterations without a new smallest residual after which a linearised problem within t_d is
  /// taken as solved as far as it goes.
  static constexpr long kFollowPatience = 1000;
  double follow_floor_ = 1.0;         ///< of t_d: the smallest residual an update waits for
  double best_followed_ = INFINITY;   ///< the smallest residual an update left
  int updates_without_progress_ = 0;  ///< since an update last left a new smallest residual
  static constexpr int kPatientUpdates = 30;
  static constexpr int kMaxCrossingMoves = 5;
  int crossing_moves_ = 0;          ///< updates from within t_d that moved a crossing
  bool crossings_moved_ = false;    ///< at the last evaluation
  FrictionFigures tresca_figures_;  ///< the inner problem's residuals at the last evaluation
  bool attached_ = false;  ///< the superposition and the step know the current contact list
  std::vector<std::vector<Eigen::Vector3d>> grid_u_, grid_u_at_detection_;
  long shape_check_interval_ = 0;     ///< iterations between checks of the fibres' shape
  long next_shape_check_ = 0;         ///< the iteration of the next one
  std::vector<int> crossing_fibres_;  ///< fibres with crossings (deformed contact)
  std::vector<std::vector<Eigen::Vector3d>> crossing_grid_u_;  ///< theirs at the grid
  Residuals residuals_;
  double exact_energy_ = 0.0;
  /// t_d the criteria and rules work to: the scene's, made smaller where the force estimate asks.
  double overlap_tolerance_;
  std::optional<ErrorEstimate> estimate_;  ///< of the state the run stopped in, if made there
  static constexpr int kMaxCorrections = 3;
  int corrections_ = 0;  ///< states that took the estimate's answer for force_tolerance
  static constexpr int kMaxExactAnswers = 2;
  /// The second answer is asked for only from a residual this share of the first's.
  static constexpr double kExactAnswerProgress = 0.1;
  int normal_answers_ = 0;                 ///< estimates asked to settle the normals
  double last_exact_residual_ = INFINITY;  ///< the residual of the update that last asked
  long exact_answers_ = 0;                 ///< states that took the estimate's answer, for either
  double energy_ = NAN;  ///< Eq. 4.34 at the last evaluation, where it was computed
  double lambda_max_ = 0.0;
  double step_ = 0.0;
  Eigen::VectorXd best_forces_;  ///< the state of the smallest residual, for a diverged run
  std::vector<Eigen::Vector3d> best_friction_;
  double best_residual_ = INFINITY;
  /// Under lagged normals, the state right after the update that left the smallest residual
  /// within the scene's t_d: its contacts (the working set's members, `members` their places in
  /// the candidate list, or every candidate with `members` empty), in detection `detection`.
  struct BestUpdate {
    double residual = INFINITY;
    long detection = -1;
    std::vector<int> members;
    std::vector<Contact> contacts;
  } best_update_;
  long detections_ = 0;  ///< candidate lists found so far
  Clock::time_point last_progress_ = Clock::now();
  std::vector<std::string> warnings_;
  std::vector<HistoryEntry> history_;
};

IterativeSolver::IterativeSolver(const Scene& scene, const SolverOptions& options)
    : scene_(scene),
      options_(options),
      fibres_(make_fibres(scene)),
      superposition_(fibres_, scene),
      margin_(candidate_margin(fibres_, options.margin_factor)),
      detector_(fibres_, scene, margin_),
      divergence_(options.overlap_tolerance, longest_fibre(fibres_)),
      energy_window_(options.energy_window, options.energy_tolerance),
      mu_(scene.contact.friction),
      coulomb_(mu_ > 0.0 && scene.contact.friction_model == FrictionModel::coulomb),
      seed_friction_(mu_ > 0.0 && scene.contact.friction_model == FrictionModel::seed),
      rule_(make_force_update(options.rule, options.c, superposition_, fibres_, state_)),
      working_set_(superposition_, fibres_, scene, detector_.geometry(), margin_,
                   options.overlap_tolerance),
      use_working_set_(mu_ == 0.0 && rule_->allows_working_set()),
      tresca_(mu_, options.overlap_tolerance),
      lagged_normals_(scene.contact.geometry == ContactGeometryModel::deformed &&
                      options.rule != UpdateRule::seed),
      overlap_tolerance_(options.overlap_tolerance) {}

Result IterativeSolver::run() {
  const auto start = Clock::now();
  detect_contacts();
  warnings_ = ambiguous_side_warnings(state_.contacts, fibres_, scene_.walls);
  if (auto why = find_unresolvable()) {
    evaluate(true);
    return finish({Status::unresolvable, Criterion::unresolvable, *why}, 0, start);
  }
  Termination end;
  long iteration = 1, previous = 0;
  while (iteration <= options_.max_iterations) {
    evaluate(!lagged_normals_);
    record(iteration, previous);
    previous = iteration;
    // Under lagged normals the criteria judge the state right after its normals followed it.
    const bool judged = !lagged_normals_ || follows_the_fibres_now(iteration, watched_residual());
    const double residual = watched_residual();
    if (!std::isfinite(residual) || !std::isfinite(exact_energy_)) {
      end = {Status::diverged, Criterion::non_finite, "non-finite forces or displacements"};
      break;
    }
    if (judged) remember_best(residual);
    if (judged && lagged_normals_) remember_best_update(residual);
    if (judged && lagged_normals_ && !just_touching(overlap_tolerance_) &&
        settle_normals_exactly(residual)) {
      ++iteration;
      continue;
    }
    if (judged && just_touching(overlap_tolerance_)) {
      if (must_measure_again()) {
        ++iteration;
        continue;
      }
      if (auto stop = forces_accurate_enough()) {
        end = *stop;
        break;
      }
    }
    if (options_.energy_tolerance > 0.0 && energy_window_.push(energy_)) {
      end = {Status::converged, Criterion::energy, ""};
      break;
    }
    if (auto verdict = diverging(iteration, residual)) {
      end = stalled_within_scene_tolerance(*verdict, return_to_best_update());
      break;
    }
    report_progress(iteration, start);
    const long work = update(iteration);
    if (auto trouble = follow_the_fibres(iteration)) {
      end = *trouble;
      break;
    }
    iteration += work;
  }
  if (end.status == Status::diverged) restore_best();
  if (end.status == Status::max_iterations && overlap_tolerance_ < options_.overlap_tolerance) {
    evaluate(true);
    end = stalled_within_scene_tolerance(end);
  }
  if (end.status == Status::max_iterations && return_to_best_update())
    end = stalled_within_scene_tolerance(end, true);
  if (end.status == Status::max_iterations) {
    iteration = options_.max_iterations;
    end.message = capped_message();
  }
  return finish(end, std::min(iteration, options_.max_iterations), start);
}

// The deformed fibres under the current forces (superposition, §4.3.1) and every contact's
// overlap on them (Eqs. 4.14–4.15), with the residuals the criteria watch.
void IterativeSolver::evaluate(bool follow_geometry) {
  if (!state_.forces_gathered) state_.gather_forces();
  const bool deformed = detector_.geometry().deformed() && follow_geometry;
  crossings_moved_ = false;
  if (deformed && detector_.point_search() &&
      (!lagged_normals_ || crossing_moves_ < kMaxCrossingMoves))
    follow_crossings();
  superposition_.contact_displacements(state_.contacts, state_.force_on_a, true, state_.u_a,
                                       state_.u_b, &exact_energy_);
  detector_.geometry().measure(state_.contacts, state_.u_a, state_.u_b, coulomb_, deformed);
  residuals_ = measure_residuals(state_.contacts);
  if (coulomb_) tresca_figures_ = tresca_figures(state_.contacts, state_.bound);
}

// Deformed contact: each crossing steps towards the closest points of the deformed fibres
// (Eqs. 4.16–4.24 on their tangent lines where it acts), and its load point with it, where they
// come closer by more than a tenth of t_d.
void IterativeSolver::follow_crossings() {
  crossing_fibres_ = fibres_with_crossings(state_.contacts);
  if (crossing_fibres_.empty()) return;
  crossing_grid_u_.resize(fibres_.size());
  for (int f : crossing_fibres_)
    superposition_.fibre_field(f, state_.force_on_a, true, detector_.grid(), crossing_grid_u_[f]);
  superposition_.contact_displacements(state_.contacts, state_.force_on_a, true, state_.u_a,
                                       state_.u_b);
  if (!detector_.follow_crossings(crossing_grid_u_, state_.contacts, state_.u_a, state_.u_b,
                                  0.1 * overlap_tolerance_))
    return;
  superposition_.move_points(state_.contacts, crossing_fibres_);
  crossings_moved_ = true;
}

// The strain energy (Eq. 4.34) where the energy criterion or the history needs it.
void IterativeSolver::record(long iteration, long before) {
  const bool keep = record_history(iteration, before);
  energy_ = NAN;
  if (options_.energy_tolerance > 0.0 || keep)
    energy_ = superposition_.trapezium_energy(state_.force_on_a, scene_.contact.slices);
  if (keep) history_.push_back({iteration, residuals_.max_overlap, energy_});
}

// With Coulomb friction the slips of the inner problem must settle too.
double IterativeSolver::watched_residual() const {
  if (!coulomb_) return residuals_.total();
  return std::max(
      {residuals_.total(), tresca_figures_.stick_residual, tresca_figures_.slip_residual});
}

// The contact criterion of §4.3.6: no overlap and no force across a gap beyond t_d (and with
// Coulomb friction, the inner problem's slips settled).
bool IterativeSolver::just_touching(double t) const {
  const bool friction_settled =
      !coulomb_ || (tresca_figures_.stick_residual < t && tresca_figures_.slip_residual < t);
  return residuals_.overlap < t && residuals_.gap_force < t && friction_settled;
}

// Coulomb's law itself, judged against μN and not against the radii of the last inner problem: a
// run that stops between two settings of the radii can have its inner problem solved to the last
// bit while contacts inside their disks still slip by far more than t_d. Where the radii stand a
// hair short of μP, the contacts on their circles are taken for sticking ones with all their slip:
// the state is then put on the cone, as a settled fixed point is, and measured again; where that
// does not hold either, the run ends in the state it stopped in.
bool IterativeSolver::coulomb_holds(double t) {
  if (!coulomb_) return true;
  auto holds = [&] {
    const FrictionFigures law = coulomb_figures();
    return law.stick_residual < t && law.slip_residual < t;
  };
  if (holds()) return true;
  const IterationState stopped_in = state_;
  const Residuals residuals = residuals_;
  const FrictionFigures inner = tresca_figures_;
  const double energy = exact_energy_;
  tresca_.onto_coulomb_cone(state_);
  evaluate(true);
  if (just_touching(t) && holds()) return true;
  state_ = stopped_in;
  residuals_ = residuals;
  tresca_figures_ = inner;
  exact_energy_ = energy;
  if (detector_.geometry().deformed())
    superposition_.move_points(state_.contacts, fibres_with_crossings(state_.contacts));
  return false;
}

// The state takes the estimate's answer (forces, frictions, and on the deformed fibres the
// crossings' places and the normals), with Coulomb friction on the cone, and the rule starts from
// it afresh.
void IterativeSolver::take_the_answer(std::vector<Contact> answer) {
  state_.contacts = std::move(answer);
  if (detector_.geometry().deformed())
    superposition_.move_points(state_.contacts, fibres_with_crossings(state_.contacts));
  if (coulomb_) tresca_.onto_coulomb_cone(state_);
  state_.forces_gathered = false;
  const Eigen::Index n = static_cast<Eigen::Index>(state_.contacts.size());
  if (state_.iterate.size() == n) {
    for (Eigen::Index k = 0; k < n; ++k)
      state_.iterate[k] = state_.contacts[static_cast<std::size_t>(k)].force;
    state_.previous = state_.iterate;
  }
  rule_->restart(state_);
  divergence_.reset();
  sequence_starts_afresh();
}

// The contact criterion met: with a force tolerance the run also asks its own error estimate.
// Where the estimated force error is still above the tolerance, the state takes the estimate's
// answer of its linearised problem (Newton steps of the contact problem, with Coulomb friction of
// the frictional one) and the iteration goes on from there (with Coulomb friction the radii
// follow: every contact on its circle slips with μ times its new force; the seed's friction rule
// takes no correction, its friction being the last resultant's). An answer the estimate did not
// settle is not taken. After kMaxCorrections of them, or instead of one not taken, t_d shrinks, by
// the factor the force error must (forces converge about in proportion to the overlaps left),
// down to a millionth of the scene's t_d, where the run stops with a warning.
std::optional<Termination> IterativeSolver::forces_accurate_enough() {
  const double wanted = options_.force_tolerance;
  if (!(wanted > 0.0)) return Termination{Status::converged, Criterion::contact, ""};
  working_set_.leave(state_);
  std::vector<Contact> answer;
  estimate_ = estimate_iteration_error(scene_, fibres_, detector_, state_.contacts, &answer);
  last_force_estimate_ = estimate_->force;
  if (estimate_->force < wanted) return Termination{Status::converged, Criterion::force, ""};
  if (corrections_ < kMaxCorrections && !seed_friction_ && estimate_->settled) {
    ++corrections_;
    ++exact_answers_;
    take_the_answer(std::move(answer));
  } else {
    const double floor = 1e-6 * options_.overlap_tolerance;
    if (overlap_tolerance_ <= floor) {
      std::ostringstream out;
      out.precision(3);
      out << "the estimated force error " << estimate_->force << " is above force_tolerance "
          << wanted << " with t_d made " << overlap_tolerance_ << " mm";
      warnings_.push_back(out.str());
      return Termination{Status::converged, Criterion::contact, ""};
    }
    const double shrink = std::clamp(0.5 * wanted / estimate_->force, 1e-3, 0.5);
    overlap_tolerance_ = std::max(shrink * overlap_tolerance_, floor);
    sequence_starts_afresh();
  }
  estimate_.reset();
  if (use_working_set_) working_set_.enter(state_);
  return std::nullopt;
}

// Under lagged normals the linearised problems converge to the deformed contact's answer by a
// constant factor per update (fibres that lean on each other roll, and on a compacted tow the
// factor is close to one), each update costing a decade or more of the accelerated iteration.
// Near the end the pushing set is the answer's, and the error estimate's answer — the linearised
// problem solved exactly on its pushing set by Newton's steps with the slices' normals turning, the
// crossings following its own displaced fibres — lands within t_d in an answer or two. It is taken
// where an update left a residual above t_d but below `exact_answer_below` times it, at most twice
// a run and the second from a tenth of the residual the first was asked from: where the pushing
// set still switches the estimate falls back to a projected solve of every candidate, which on
// compacted tows is costly and takes the residual down little, and from a tenth as far Newton's
// steps keep their pushing set.
// Frictionless only: with friction the estimate's Newton steps settle only from within about
// 1e-6 mm. True when the state took the answer.
bool IterativeSolver::settle_normals_exactly(double residual) {
  if (mu_ > 0.0 || normal_answers_ >= kMaxExactAnswers ||
      !(residual < options_.exact_answer_below * overlap_tolerance_) ||
      !(residual < kExactAnswerProgress * last_exact_residual_))
    return false;
  ++normal_answers_;
  last_exact_residual_ = residual;
  working_set_.leave(state_);
  std::vector<Contact> answer;
  const bool settled =
      estimate_iteration_error(scene_, fibres_, detector_, state_.contacts, &answer, true).settled;
  if (settled) {
    take_the_answer(std::move(answer));
    ++exact_answers_;
  }
  if (use_working_set_) working_set_.enter(state_);
  return settled;
}

// Before stopping: no candidate outside the working set may overlap, no contact outside the
// candidate list may have appeared, and the Tresca radii must be Coulomb's. True when one of them
// changed the problem, which must then be measured again.
bool IterativeSolver::must_measure_again() {
  if (working_set_.active() && working_set_.outside_overlaps(state_, overlap_tolerance_) &&
      working_set_.revise(state_))
    return true;
  if (largest_move() > 0.5 * margin_) {
    detect_contacts();
    return true;
  }
  if (coulomb_ && tresca_.update(state_, fibres_)) {
    rule_->restart(state_);
    divergence_.reset();
    sequence_starts_afresh();
    return true;
  }
  return false;
}

// The problem the sequence of linearised problems converges to has changed (new Tresca radii, a
// correction from the estimate, a smaller t_d): its progress is judged from here.
void IterativeSolver::sequence_starts_afresh() {
  best_followed_ = INFINITY;
  updates_without_progress_ = 0;
}

// Rules auto and accelerated solve the deformed contact as a sequence of problems, each linearised
// about the normals (and crossings) of the configuration the one before left: the projected
// iteration on the deformed gaps themselves cycles on compacted tows, where fibres slide round
// each other. Normals and crossings follow the displaced centres once the linearised problem's
// residual has fallen below a tenth of what the last update left (down to a hundredth, after
// updates that made no progress), or below t_d (less, down to a hundredth, after updates from
// there that left more), or when it has stayed within t_d without a new smallest residual for
// kFollowPatience iterations (a contact beside a support, whose slip the forces barely move, can
// hold it above that hundredth for ever); the contact criterion is judged right after an update,
// on the normals the state's own forces give. True when they followed (the residuals are then
// those after the update).
bool IterativeSolver::follows_the_fibres_now(long iteration, double residual) {
  if (!lagged_normals_) return false;
  const double t = overlap_tolerance_;
  if (!std::isfinite(follow_below_)) follow_below_ = std::max(follow_fraction_ * residual, t);
  if (residual < least_since_followed_)
    least_since_followed_ = residual, least_since_followed_at_ = iteration;
  const bool settled_within_t =
      residual < t && iteration - least_since_followed_at_ > kFollowPatience;
  if (!(residual <= follow_below_) && !settled_within_t) return false;
  least_since_followed_ = INFINITY;
  evaluate(true);
  ++geometric_updates_;
  // Crossings move at most kMaxCrossingMoves times from a state within t_d: their tangents come
  // from the detection grid, and near the answer the estimate's error can step them back and forth.
  if (crossings_moved_ && residual < t) ++crossing_moves_;
  state_.forces_gathered = false;
  evaluate(false);
  const double after = watched_residual();
  least_after_update_ = std::min(least_after_update_, after);
  // An update from within t_d that leaves more than t_d: the next one waits for a smaller
  // residual, so that the normals' own change, not the linearised problem's, decides.
  if (residual < t && !(after < t)) follow_floor_ = std::max(0.5 * follow_floor_, 0.01);
  // Progress of the sequence is judged by what each update leaves, kPatientUpdates of them at
  // most without a new best; the divergence monitor watches each linearised problem on its own.
  divergence_.reset();
  if (after < best_followed_) {
    best_followed_ = after;
    updates_without_progress_ = 0;
  } else {
    ++updates_without_progress_;
    // One that made none asks the next linearised problem for a finer answer: normals taken
    // from a rough one turn by its error, and on compacted tows those turns keep groups of
    // fibres sliding round each other without end.
    follow_fraction_ = std::max(follow_fraction_ / 3.0, kSmallestFollowFraction);
  }
  follow_below_ = std::max(follow_fraction_ * after, follow_floor_ * t);
  return true;
}

// A run whose t_d was made smaller to meet force_tolerance and that stalls there, or runs out of
// iterations there (a contact next to a support, whose overlap the forces barely move, can hold
// the residual above the smaller t_d; with Coulomb friction, contacts wedged against each other
// can slow the iteration to a crawl), still meets the scene's own contact criterion: it is
// converged, with a warning that the force tolerance was not reached. So is a run that ends in the
// best state an update of the normals left within the scene's t_d (`at_best_update`), with a
// warning that the force tolerance was not shown to be reached.
Termination IterativeSolver::stalled_within_scene_tolerance(const Termination& verdict,
                                                            bool at_best_update) {
  const double t = options_.overlap_tolerance;
  const bool stalled =
      verdict.criterion == Criterion::oscillation || verdict.criterion == Criterion::max_iterations;
  const bool t_d_made_smaller = overlap_tolerance_ < t;
  if (!stalled || !(t_d_made_smaller || at_best_update) || !just_touching(t) || !coulomb_holds(t))
    return verdict;
  const char* how =
      verdict.criterion == Criterion::oscillation ? "stalled" : "ran out of iterations";
  std::ostringstream out;
  out.precision(3);
  if (t_d_made_smaller)
    out << "force_tolerance " << options_.force_tolerance << " not reached: the iteration " << how
        << " with t_d made " << overlap_tolerance_ << " mm for the estimated force error "
        << last_force_estimate_ << ", its residual " << watched_residual()
        << " mm within the scene's t_d";
  else
    out << "force_tolerance " << options_.force_tolerance
        << " not shown to be reached: the sequence of problems linearised about the normals " << how
        << "; it ends in the best state an update of the normals left, within the scene's t_d "
        << "(residual " << watched_residual() << " mm)";
  warnings_.push_back(out.str());
  return Termination{Status::converged, Criterion::contact, ""};
}

std::optional<Termination> IterativeSolver::diverging(long iteration, double residual) {
  if (updates_without_progress_ >= kPatientUpdates) {
    std::ostringstream out;
    out.precision(3);
    out << "no progress: " << kPatientUpdates << " updates of the normals to the displaced "
        << "centres left no residual below " << best_followed_ << " mm";
    return Termination{Status::diverged, Criterion::oscillation, out.str()};
  }
  const auto verdict = divergence_.observe(iteration, residual);
  if (verdict == DivergenceMonitor::Verdict::fine) return std::nullopt;
  const bool growth = verdict == DivergenceMonitor::Verdict::growth;
  std::ostringstream out;
  out.precision(3);
  out << (growth ? "residual grew without bound" : "no progress: the update oscillates");
  if (step_ * lambda_max_ > 2.0)
    out << " (c = " << step_ << " N/mm; the step is stable below about " << 2.0 / lambda_max_
        << " N/mm, 2/lambda_max of the compliance it steps on)";
  else
    out << " with its step within the stable limit (c = " << step_
        << " N/mm, below 2/lambda_max = " << 2.0 / lambda_max_ << " N/mm)";
  return Termination{Status::diverged, growth ? Criterion::growth : Criterion::oscillation,
                     out.str()};
}

// §4.3.2: the forces of every contact from the overlaps just measured, by the rule; returns the
// iterations this took.
long IterativeSolver::update(long iteration) {
  UpdateContext context;
  context.step = step_;
  context.mu = mu_;
  context.coulomb = coulomb_;
  context.seed_friction = seed_friction_;
  context.geometry = &detector_.geometry();
  context.lambda_max = lambda_max_;
  context.tolerance =
      lagged_normals_ ? std::min(overlap_tolerance_, follow_below_) : overlap_tolerance_;
  context.max_products = options_.max_iterations - iteration;
  const long work = rule_->update(state_, context);
  if (working_set_.active() && working_set_.due()) working_set_.revise(state_);
  return work;
}

// The candidates were found with a margin before they touch: when the fibres have moved by half
// of it since, they are found again. Under the working set the shape is checked every 50
// iterations (a deflection field of every fibre costs more than an iteration on the set), the
// other rules every 10; a rule that solves each candidate list whole only when it is solved.
// While the fibres have moved less than a quarter of the way, the checks grow sparser, up to
// eight times: near the answer they hardly move.
std::optional<Termination> IterativeSolver::follow_the_fibres(long done) {
  if (rule_->solves_each_list() || done < next_shape_check_) return std::nullopt;
  const long every = working_set_.active() ? 50 : 10;
  const double moved = largest_move();
  shape_check_interval_ =
      moved < 0.125 * margin_ ? std::clamp(2 * shape_check_interval_, every, 8 * every) : every;
  next_shape_check_ = done + shape_check_interval_;
  if (!(moved > 0.5 * margin_)) return std::nullopt;
  return detect_again();
}

void IterativeSolver::compute_grid() {
  const std::vector<double>& s = detector_.grid();
  grid_u_.resize(fibres_.size());
  const int n = static_cast<int>(fibres_.size());
#pragma omp parallel for schedule(dynamic, 16) if (n > 64)
  for (int f = 0; f < n; ++f) superposition_.fibre_field(f, state_.force_on_a, true, s, grid_u_[f]);
}

// The deformed shape under the current forces, then a fresh candidate list. Contacts found again
// keep their state (force, friction, iterates); W and its step are estimated again only when the
// list changed.
void IterativeSolver::detect_contacts() {
  ++detections_;
  working_set_.leave(state_);
  state_.gather_forces();
  compute_grid();
  std::vector<Contact> found = detector_.detect(grid_u_);
  const std::vector<long> origin = carry_over(state_.contacts, found);
  detector_.keep_crossing_places(grid_u_, found, state_.contacts, origin);
  // Under lagged normals a contact found again keeps the normal of its linearised problem.
  if (lagged_normals_)
    for (std::size_t i = 0; i < found.size(); ++i)
      if (origin[i] >= 0) {
        const Contact& before = state_.contacts[static_cast<std::size_t>(origin[i])];
        found[i].normal = before.normal;
        found[i].tangent = before.tangent;
        found[i].tangents = before.tangents;
      }
  bool unchanged = !state_.contacts.empty() && found.size() == state_.contacts.size();
  for (std::size_t i = 0; unchanged && i < origin.size(); ++i)
    unchanged = origin[i] == static_cast<long>(i);
  state_.take_over(std::move(found), origin, coulomb_, mu_);
  if (mu_ > 0.0) origins_.set(state_.contacts);
  grid_u_at_detection_ = grid_u_;
  if (!(unchanged && attached_)) {
    superposition_.attach(state_.contacts);
    rule_->attach(state_.contacts);
    attached_ = true;
    state_.gather_forces();
    estimate_step();
  }
  if (use_working_set_) working_set_.enter(state_);
}

// How far the fibres have moved since the candidates were found, at the detection grid (mm).
double IterativeSolver::largest_move() {
  state_.gather_forces();
  compute_grid();
  double largest = 0.0;
  for (std::size_t f = 0; f < fibres_.size(); ++f)
    for (std::size_t j = 0; j < grid_u_[f].size(); ++j)
      largest = std::max(largest, (grid_u_[f][j] - grid_u_at_detection_[f][j]).norm());
  return largest;
}

// The rule's step on this candidate list, from λmax of the operator it steps on: D½·W·D½ for the
// seed's rule (c/n per slice), W for the others; with Coulomb friction the frictional operator.
void IterativeSolver::estimate_step() {
  lambda_max_ = ComplianceOperator(superposition_, state_.contacts, rule_->weighted(), coulomb_)
                    .largest_eigenvalue();
  step_ = rule_->step(lambda_max_);
  divergence_.set_unstable_step(step_ * lambda_max_ > 2.0);
}

// An overlap at a point neither fibre can move (a pinned support of both, or a normal along both
// axes) can never be removed: said at once instead of iterated on.
std::optional<std::string> IterativeSolver::find_unresolvable() const {
  const std::vector<Contact>& contacts = state_.contacts;
  std::vector<double> overlap(contacts.size()), compliance(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    overlap[k] = contacts[k].overlap;
    compliance[k] = self_compliance(contacts[k], fibres_);
  }
  return find_unresolvable_overlap(contacts, overlap, compliance, options_.overlap_tolerance,
                                   fibres_, scene_.walls);
}

// A fresh candidate list, and the status `unresolvable` when an overlap on it cannot be resolved.
// The divergence monitor keeps its best residual across re-detections: a rule that moves the
// fibres enough to re-detect every few iterations would otherwise never be judged stalled.
std::optional<Termination> IterativeSolver::detect_again() {
  detect_contacts();
  const auto why = find_unresolvable();
  if (!why) return std::nullopt;
  evaluate(true);
  return Termination{Status::unresolvable, Criterion::unresolvable, *why};
}

void IterativeSolver::remember_best(double residual) {
  if (!(residual < best_residual_)) return;
  best_residual_ = residual;
  best_forces_.resize(static_cast<Eigen::Index>(state_.contacts.size()));
  best_friction_.resize(state_.contacts.size());
  for (std::size_t k = 0; k < state_.contacts.size(); ++k) {
    best_forces_[k] = state_.contacts[k].force;
    best_friction_[k] = state_.contacts[k].friction;
  }
}

// A diverged run reports the best state it saw, never a non-finite one.
void IterativeSolver::restore_best() {
  if (best_forces_.size() != static_cast<Eigen::Index>(state_.contacts.size())) return;
  for (std::size_t k = 0; k < state_.contacts.size(); ++k) {
    state_.contacts[k].force = best_forces_[k];
    state_.contacts[k].friction = best_friction_[k];
  }
  state_.forces_gathered = false;
  evaluate(true);
}

// Under lagged normals a sequence of linearised problems can wander once it is within the scene's
// t_d: a fibre that rolls off another is followed a little at each update until a neighbour
// catches it, and what the updates leave grows for a while. The state right after the best
// update within the scene's t_d is kept, so that a run stopped later (no progress, or out of
// iterations) ends in the best state it was in, judged as it was. Frictionless only: with friction
// a state's residuals also hang on the Tresca radii of its time.
void IterativeSolver::remember_best_update(double residual) {
  if (mu_ > 0.0 || !(residual < options_.overlap_tolerance)) return;
  if (best_update_.detection == detections_ && !(residual < best_update_.residual)) return;
  best_update_.residual = residual;
  best_update_.detection = detections_;
  best_update_.contacts = state_.contacts;
  best_update_.members.clear();
  if (working_set_.active()) best_update_.members = working_set_.members();
}

// Where an update left a state within the scene's t_d on the current candidate list: the state
// is judged as an update would judge it (its normals follow its displaced centres), and returns
// to the best update's if that was better. False where there is no such update.
bool IterativeSolver::return_to_best_update() {
  if (best_update_.detection != detections_) return false;
  working_set_.leave(state_);
  evaluate(true);
  state_.forces_gathered = false;
  evaluate(false);
  if (watched_residual() <= best_update_.residual) return true;
  std::vector<Contact> contacts = std::move(best_update_.contacts);
  if (!best_update_.members.empty()) {
    std::vector<Contact> candidates = state_.contacts;
    for (Contact& c : candidates) c.force = 0.0;
    for (std::size_t k = 0; k < contacts.size(); ++k)
      candidates[static_cast<std::size_t>(best_update_.members[k])] = contacts[k];
    contacts = std::move(candidates);
  }
  best_update_ = BestUpdate{};
  take_the_answer(std::move(contacts));
  evaluate(false);
  return true;
}

void IterativeSolver::report_progress(long iteration, Clock::time_point start) {
  if (!options_.progress || seconds_since(last_progress_) < options_.progress_interval_s) return;
  last_progress_ = Clock::now();
  IterationProgress p;
  p.iteration = iteration;
  p.max_iterations = options_.max_iterations;
  p.overlap_residual = residuals_.overlap;
  p.gap_force_residual = residuals_.gap_force;
  p.tolerance = options_.overlap_tolerance;
  p.working_tolerance = overlap_tolerance_;
  p.normal_updates = geometric_updates_;
  p.radius_updates = tresca_.updates();
  p.coulomb = coulomb_;
  p.contacts = working_set_.active() ? working_set_.candidates() : state_.contacts.size();
  p.elapsed_s = seconds_since(start);
  options_.progress(p);
}

std::string IterativeSolver::capped_message() const {
  std::ostringstream out;
  out.precision(3);
  out << "stopped after " << options_.max_iterations << " iterations with overlap residual "
      << residuals_.overlap << " mm and gap-force residual " << residuals_.gap_force
      << " mm (tolerance " << options_.overlap_tolerance << " mm)";
  // Under the deformed contact a state can meet t_d along the normals it was solved with while
  // the normals of its displaced centres still turn: said, or the residuals above read as a
  // contradiction.
  if (lagged_normals_ && geometric_updates_ > 0 &&
      !(least_after_update_ < options_.overlap_tolerance))
    out << "; the normals had not settled: each of the " << geometric_updates_
        << " updates of the normals to the displaced centres left at least " << least_after_update_
        << " mm";
  if (overlap_tolerance_ < options_.overlap_tolerance)
    out << "; its force tolerance had made t_d " << overlap_tolerance_ << " mm";
  if (coulomb_) {
    const FrictionFigures law = coulomb_figures();
    out << "; the Tresca radii had been set " << tresca_.updates()
        << " times, the last inner problem's stick residual " << tresca_figures_.stick_residual
        << " mm, slip residual " << tresca_figures_.slip_residual
        << " mm; against muN the stick residual is " << law.stick_residual
        << " mm, the slip residual " << law.slip_residual << " mm";
  }
  if (options_.rule != UpdateRule::accelerated)
    out << "; rule accelerated needs far fewer iterations where the compliance is "
           "ill-conditioned (line contacts near supports, tows)";
  else
    out << "; raise solver.max_iterations or loosen solver.overlap_tolerance";
  return out.str();
}

Result IterativeSolver::finish(const Termination& end, long iterations, Clock::time_point start) {
  working_set_.leave(state_);
  IterationRecord record;
  record.termination = end;
  record.iterations = iterations;
  record.step = step_;
  record.lambda_max = lambda_max_;
  record.tresca_updates = tresca_.updates();
  record.geometric_updates = geometric_updates_;
  record.exact_answers = exact_answers_;
  record.residuals = residuals_;
  record.warnings = warnings_;
  record.history = history_;
  Result r = iterative_result(scene_, options_, fibres_, superposition_, detector_, state_, record);
  if (estimate_)
    r.error_estimate = estimate_;
  else if (end.criterion != Criterion::non_finite && end.status != Status::unresolvable)
    r.error_estimate = estimate_iteration_error(scene_, fibres_, detector_, state_.contacts);
  r.wall_time_s = seconds_since(start);
  return r;
}

}  // namespace

Result solve_iteratively(const Scene& scene, const SolverOptions& options) {
  // A load path: each step starts from the contacts and forces the previous one ended with.
  std::vector<Contact> state;
  SlipOrigins origins;
  int steps_begun = 0;
  Result r = solve_load_path(scene, [&](const Scene& step, const Result* previous) {
    SolverOptions step_options = options;
    const int k = ++steps_begun, n = static_cast<int>(scene.steps.size());
    if (options.progress && n > 0)
      step_options.progress = [&options, k, n](IterationProgress p) {
        p.step = k, p.steps = n;
        options.progress(p);
      };
    IterativeSolver solver(step, step_options);
    if (previous) solver.start_from(state, origins);
    Result result = solver.run();
    state = solver.contacts();
    origins = solver.end_state(result);
    return result;
  });
  replace_non_finite(r);
  return r;
}

}  // namespace fibrecheck
