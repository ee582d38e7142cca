#include "iterative_solver.h"

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "ambiguous_sides.h"
#include "carry_over.h"
#include "compliance_operator.h"
#include "contact_detection.h"
#include "contact_results.h"
#include "convergence.h"
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
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
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
  void evaluate();
  void record(long iteration, long before);
  bool just_touching() const;
  bool must_measure_again();
  std::optional<Termination> diverging(long iteration, double residual);
  long update(long iteration);
  std::optional<Termination> follow_the_fibres(long done);

  void detect_contacts();
  void compute_grid();
  bool moved_beyond_margin();
  void estimate_step();
  std::optional<std::string> find_unresolvable() const;
  std::optional<Termination> detect_again();
  double watched_residual() const;
  void remember_best(double residual);
  void restore_best();
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
  FrictionFigures tresca_figures_;  ///< the inner problem's residuals at the last evaluation
  bool attached_ = false;  ///< the superposition and the step know the current contact list
  std::vector<std::vector<Eigen::Vector3d>> grid_u_, grid_u_at_detection_;
  Residuals residuals_;
  double exact_energy_ = 0.0;
  double energy_ = NAN;  ///< Eq. 4.34 at the last evaluation, where it was computed
  double lambda_max_ = 0.0;
  double step_ = 0.0;
  Eigen::VectorXd best_forces_;  ///< the state of the smallest residual, for a diverged run
  std::vector<Eigen::Vector3d> best_friction_;
  double best_residual_ = INFINITY;
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
      divergence_(options.overlap_tolerance),
      energy_window_(options.energy_window, options.energy_tolerance),
      mu_(scene.contact.friction),
      coulomb_(mu_ > 0.0 && scene.contact.friction_model == FrictionModel::coulomb),
      seed_friction_(mu_ > 0.0 && scene.contact.friction_model == FrictionModel::seed),
      rule_(make_force_update(options.rule, options.c, superposition_, fibres_, state_)),
      working_set_(superposition_, fibres_, scene, detector_.geometry(), margin_,
                   options.overlap_tolerance),
      use_working_set_(mu_ == 0.0 && rule_->allows_working_set()),
      tresca_(mu_, options.overlap_tolerance) {}

Result IterativeSolver::run() {
  const auto start = Clock::now();
  detect_contacts();
  warnings_ = ambiguous_side_warnings(state_.contacts, fibres_, scene_.walls);
  if (auto why = find_unresolvable()) {
    evaluate();
    return finish({Status::unresolvable, Criterion::unresolvable, *why}, 0, start);
  }
  Termination end;
  long iteration = 1, previous = 0;
  while (iteration <= options_.max_iterations) {
    evaluate();
    record(iteration, previous);
    previous = iteration;
    const double residual = watched_residual();
    if (!std::isfinite(residual) || !std::isfinite(exact_energy_)) {
      end = {Status::diverged, Criterion::non_finite, "non-finite forces or displacements"};
      break;
    }
    remember_best(residual);
    if (just_touching()) {
      if (!must_measure_again()) {
        end = {Status::converged, Criterion::contact, ""};
        break;
      }
      ++iteration;
      continue;
    }
    if (options_.energy_tolerance > 0.0 && energy_window_.push(energy_)) {
      end = {Status::converged, Criterion::energy, ""};
      break;
    }
    if (auto verdict = diverging(iteration, residual)) {
      end = *verdict;
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
  if (end.status == Status::max_iterations) {
    iteration = options_.max_iterations;
    end.message = capped_message();
  }
  return finish(end, std::min(iteration, options_.max_iterations), start);
}

// The deformed fibres under the current forces (superposition, §4.3.1) and every contact's
// overlap on them (Eqs. 4.14–4.15), with the residuals the criteria watch.
void IterativeSolver::evaluate() {
  if (!state_.forces_gathered) state_.gather_forces();
  superposition_.contact_displacements(state_.contacts, state_.force_on_a, true, state_.u_a,
                                       state_.u_b, &exact_energy_);
  detector_.geometry().measure(state_.contacts, state_.u_a, state_.u_b, coulomb_);
  residuals_ = measure_residuals(state_.contacts);
  if (coulomb_) tresca_figures_ = tresca_figures(state_.contacts, state_.bound);
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
bool IterativeSolver::just_touching() const {
  const double t = options_.overlap_tolerance;
  const bool friction_settled =
      !coulomb_ || (tresca_figures_.stick_residual < t && tresca_figures_.slip_residual < t);
  return residuals_.overlap < t && residuals_.gap_force < t && friction_settled;
}

// Before stopping: no candidate outside the working set may overlap, no contact outside the
// candidate list may have appeared, and the Tresca radii must be Coulomb's. True when one of them
// changed the problem, which must then be measured again.
bool IterativeSolver::must_measure_again() {
  if (working_set_.active() && working_set_.revise(state_)) return true;
  if (moved_beyond_margin()) {
    detect_contacts();
    return true;
  }
  if (coulomb_ && tresca_.update(state_, fibres_)) {
    rule_->restart(state_);
    divergence_.reset();
    return true;
  }
  return false;
}

std::optional<Termination> IterativeSolver::diverging(long iteration, double residual) {
  const auto verdict = divergence_.observe(iteration, residual);
  if (verdict == DivergenceMonitor::Verdict::fine) return std::nullopt;
  const bool growth = verdict == DivergenceMonitor::Verdict::growth;
  std::ostringstream out;
  out.precision(3);
  out << (growth ? "residual grew without bound" : "no progress: the update oscillates")
      << " (c = " << step_ << " N/mm; the step is stable below about " << 2.0 / lambda_max_
      << " N/mm, 2/lambda_max of the compliance it steps on)";
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
  context.tolerance = options_.overlap_tolerance;
  context.max_products = options_.max_iterations - iteration;
  const long work = rule_->update(state_, context);
  if (working_set_.active() && working_set_.due()) working_set_.revise(state_);
  return work;
}

// The candidates were found with a margin before they touch: when the fibres have moved by half
// of it since, they are found again. Under the working set the shape is checked every 50
// iterations (a deflection field of every fibre costs more than an iteration on the set), the
// other rules every 10; a rule that solves each candidate list whole only when it is solved.
std::optional<Termination> IterativeSolver::follow_the_fibres(long done) {
  const int every = rule_->solves_each_list() ? 0 : working_set_.active() ? 50 : 10;
  if (every == 0 || done % every != 0 || !moved_beyond_margin()) return std::nullopt;
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
  working_set_.leave(state_);
  state_.gather_forces();
  compute_grid();
  std::vector<Contact> found = detector_.detect(grid_u_);
  const std::vector<long> origin = carry_over(state_.contacts, found);
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

bool IterativeSolver::moved_beyond_margin() {
  state_.gather_forces();
  compute_grid();
  double largest = 0.0;
  for (std::size_t f = 0; f < fibres_.size(); ++f)
    for (std::size_t j = 0; j < grid_u_[f].size(); ++j)
      largest = std::max(largest, (grid_u_[f][j] - grid_u_at_detection_[f][j]).norm());
  return largest > 0.5 * margin_;
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
  evaluate();
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
  evaluate();
}

void IterativeSolver::report_progress(long iteration, Clock::time_point start) {
  if (!options_.progress || seconds_since(last_progress_) < options_.progress_interval_s) return;
  last_progress_ = Clock::now();
  options_.progress({iteration, options_.max_iterations, residuals_.overlap, residuals_.gap_force,
                     options_.overlap_tolerance,
                     working_set_.active() ? working_set_.candidates() : state_.contacts.size(),
                     seconds_since(start)});
}

std::string IterativeSolver::capped_message() const {
  std::ostringstream out;
  out.precision(3);
  out << "stopped after " << options_.max_iterations << " iterations with overlap residual "
      << residuals_.overlap << " mm and gap-force residual " << residuals_.gap_force
      << " mm (tolerance " << options_.overlap_tolerance << " mm)";
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
  record.residuals = residuals_;
  record.warnings = warnings_;
  record.history = history_;
  Result r = iterative_result(scene_, options_, fibres_, superposition_, detector_, state_, record);
  r.wall_time_s = seconds_since(start);
  return r;
}

}  // namespace

Result solve_iteratively(const Scene& scene, const SolverOptions& options) {
  // A load path: each step starts from the contacts and forces the previous one ended with.
  std::vector<Contact> state;
  SlipOrigins origins;
  Result r = solve_load_path(scene, [&](const Scene& step, const Result* previous) {
    IterativeSolver solver(step, options);
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
