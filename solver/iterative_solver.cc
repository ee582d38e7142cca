#include "iterative_solver.h"

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_map>

#include "ambiguous_sides.h"
#include "carry_over.h"
#include "compliance_operator.h"
#include "contact_description.h"
#include "contact_detection.h"
#include "contact_results.h"
#include "convergence.h"
#include "fibre.h"
#include "fibre_stiffness.h"
#include "friction.h"
#include "load_path_solve.h"
#include "parallel_work.h"
#include "projected_cg.h"
#include "slip_origins.h"
#include "superposition.h"
#include "unresolvable_overlap.h"
#include "validity.h"

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

/// The iteration of §4.3.2 on one scene: holds the fibres, the contacts and the forces, and runs
/// detect → superpose → measure → update until a criterion of §4.3.6 stops it.
class IterativeSolver {
 public:
  IterativeSolver(const Scene& scene, const SolverOptions& options)
      : scene_(scene),
        options_(options),
        fibres_(make_fibres(scene)),
        superposition_(fibres_, scene),
        stiffness_(fibres_),
        margin_(candidate_margin(fibres_, options.margin_factor)),
        detector_(fibres_, scene, margin_),
        divergence_(options.overlap_tolerance),
        energy_window_(options.energy_window, options.energy_tolerance),
        mu_(scene.contact.friction),
        coulomb_(mu_ > 0.0 && scene.contact.friction_model == FrictionModel::coulomb),
        seed_friction_(mu_ > 0.0 && scene.contact.friction_model == FrictionModel::seed),
        use_working_set_(mu_ == 0.0 && (options.rule == UpdateRule::accelerated ||
                                        options.rule == UpdateRule::automatic)),
        candidate_superposition_(fibres_, scene) {}

  Result run();
  /// Starts from another state's contacts (the previous step of a load path): those found again
  /// keep their force.
  void start_from(std::vector<Contact> contacts, SlipOrigins origins) {
    contacts_ = std::move(contacts);
    origins_ = std::move(origins);
    attached_ = false;
  }
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// Where the next step's slip is measured from, after `run`.
  SlipOrigins end_state(const Result& result) const {
    return SlipOrigins(contacts_, u_a_, u_b_, result);
  }

 private:
  void detect_contacts();
  void enter_working_set();
  bool update_working_set();
  void leave_working_set();
  void compute_grid();
  bool moved_beyond_margin();
  void estimate_step();
  std::optional<std::string> find_unresolvable() const;
  /// A fresh candidate list; false, with the status `unresolvable`, when an overlap on it cannot be
  /// resolved.
  bool detect_again(Status& status, Criterion& criterion, std::string& message);
  void evaluate();
  void update_forces();
  bool update_tresca_bounds();
  void gather_forces();
  void run_projected_cg(long& iteration, Status& status, Criterion& criterion, std::string& message,
                        Clock::time_point start);
  Result assemble(Clock::time_point start);
  bool record_history(long iteration) const;

  const Scene& scene_;
  SolverOptions options_;
  std::vector<Fibre> fibres_;
  Superposition superposition_;
  FibreStiffness stiffness_;  ///< rule cg: the preconditioner
  double margin_;
  ContactDetector detector_;
  DivergenceMonitor divergence_;
  bool attached_ = false;  ///< the superposition and the step know the current contact list
  EnergyWindow energy_window_;
  double mu_;
  bool coulomb_;        ///< Coulomb friction: the tangential force projected onto μP's disk
  bool seed_friction_;  ///< the seed's friction rule (Eqs. 4.29–4.33)
  SlipOrigins origins_;
  /// Coulomb friction as a Tresca fixed point: the disk radius of each contact is μ times its
  /// normal force when the last inner problem settled; the inner problem (radii fixed) is convex.
  Eigen::VectorXd bound_;
  long tresca_updates_ = 0;
  double tresca_relaxation_ = 1.0;  ///< of the radius updates (adaptive, from 1 down to 1/64)
  double last_tresca_change_ = INFINITY;
  int tresca_falling_ = 0;
  bool tresca_settled_before_ = false;
  FrictionFigures tresca_;  ///< the inner problem's residuals at the last evaluation

  std::vector<Contact> contacts_;
  std::vector<Eigen::Vector3d> force_on_a_, u_a_, u_b_;
  /// The working set (frictionless contact, rules auto and accelerated): most candidates of a
  /// compacted tow never push (2% of them do in a 1 000-fibre tow), and one that neither pushes nor
  /// has momentum nor comes within δ of touching keeps P = 0 under the update. While it is on,
  /// `contacts_` holds only the others; every tenth iteration the overlaps of all candidates are
  /// measured again and the set revised. The step stays that of all candidates.
  bool use_working_set_ = false;
  bool working_ = false;  ///< contacts_ is the working set of candidates_
  std::vector<Contact> candidates_;
  std::vector<int> members_;               ///< index in candidates_ of each contacts_[i]
  Superposition candidate_superposition_;  ///< attached to candidates_
  std::vector<double> synced_overlap_;     ///< of every candidate at the last revision
  int revision_interval_ = 20;             ///< iterations between revisions
  int since_revision_ = 0;
  // Scratch of the revisions.
  std::vector<Eigen::Vector3d> revision_force_, revision_u_a_, revision_u_b_;
  std::vector<int> revision_slot_;
  std::vector<double> revision_overlap_;
  std::vector<std::vector<Eigen::Vector3d>> grid_u_, grid_u_at_detection_;
  Eigen::VectorXd previous_forces_;  ///< accelerated rule: the previous iterate P_{k−1}
  Eigen::VectorXd iterate_;          ///< accelerated rule: the current iterate P_k
  Eigen::VectorXd next_forces_;      ///< scratch: the forces of the next evaluation
  /// The same for the friction forces (Coulomb friction).
  std::vector<Eigen::Vector3d> previous_friction_, friction_iterate_, next_friction_;
  double momentum_t_ = 1.0;
  bool forces_gathered_ = false;  ///< force_on_a_ matches the contacts' forces
  int uphill_streak_ = 0;
  static constexpr int kRestartStreak = 20;
  double lambda_max_ = 0.0;
  double step_ = 0.0;
  double exact_energy_ = 0.0;
  Residuals residuals_;
  std::vector<std::string> warnings_;
  std::vector<HistoryEntry> history_;
};

void IterativeSolver::compute_grid() {
  const std::vector<double>& s = detector_.grid();
  grid_u_.resize(fibres_.size());
  const int n = static_cast<int>(fibres_.size());
#pragma omp parallel for schedule(dynamic, 16) if (n > 64)
  for (int f = 0; f < n; ++f) superposition_.fibre_field(f, force_on_a_, true, s, grid_u_[f]);
}

void IterativeSolver::gather_forces() {
  force_on_a_.resize(contacts_.size());
  const Contact* const contact = contacts_.data();
  Eigen::Vector3d* const force = force_on_a_.data();
  const int n = static_cast<int>(contacts_.size());
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (int k = 0; k < n; ++k) force[k] = contact[k].force_on_a();
  forces_gathered_ = true;
}

void IterativeSolver::detect_contacts() {
  // Deformed shape under the current forces, then a fresh candidate list. Contacts found again keep
  // their state (force, friction, the momentum of the accelerated rule); their place and normal
  // are those of the undeformed fibres anyway. W and its step are estimated again only when the
  // list changed.
  leave_working_set();
  gather_forces();
  compute_grid();
  std::vector<Contact> found = detector_.detect(grid_u_);
  const std::vector<long> origin = carry_over(contacts_, found);
  bool unchanged = !contacts_.empty() && found.size() == contacts_.size();
  for (std::size_t i = 0; unchanged && i < origin.size(); ++i)
    unchanged = origin[i] == static_cast<long>(i);
  const bool had_momentum = iterate_.size() == static_cast<Eigen::Index>(contacts_.size());
  Eigen::VectorXd iterate(static_cast<Eigen::Index>(found.size()));
  Eigen::VectorXd previous_iterate(iterate.size());
  std::vector<Eigen::Vector3d> friction_iterate(coulomb_ ? found.size() : 0);
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(coulomb_ ? iterate.size() : 0);
  const bool had_bounds = bound_.size() == static_cast<Eigen::Index>(contacts_.size());
  std::vector<Eigen::Vector3d> previous_friction(friction_iterate.size());
  const bool had_friction_momentum = friction_iterate_.size() == contacts_.size();
  for (std::size_t i = 0; i < found.size(); ++i) {
    const bool known = had_momentum && origin[i] >= 0;
    iterate[i] = known ? iterate_[origin[i]] : found[i].force;
    previous_iterate[i] = known ? previous_forces_[origin[i]] : found[i].force;
    if (!coulomb_) continue;
    bound[i] = had_bounds && origin[i] >= 0 ? bound_[origin[i]] : mu_ * found[i].force;
    const bool known_friction = had_friction_momentum && origin[i] >= 0;
    friction_iterate[i] = known_friction ? friction_iterate_[origin[i]] : found[i].friction;
    previous_friction[i] = known_friction ? previous_friction_[origin[i]] : found[i].friction;
  }
  contacts_ = std::move(found);
  if (mu_ > 0.0) origins_.set(contacts_);
  iterate_ = std::move(iterate);
  previous_forces_ = std::move(previous_iterate);
  friction_iterate_ = std::move(friction_iterate);
  bound_ = std::move(bound);
  previous_friction_ = std::move(previous_friction);
  grid_u_at_detection_ = grid_u_;
  if (!(unchanged && attached_)) {
    superposition_.attach(contacts_);
    if (options_.rule == UpdateRule::conjugate_gradient) stiffness_.attach(contacts_);
    attached_ = true;
    gather_forces();
    estimate_step();
  }
  if (use_working_set_) enter_working_set();
}

void IterativeSolver::enter_working_set() {
  // From the whole candidate list in contacts_: it becomes candidates_, and contacts_ its
  // working set.
  candidates_ = contacts_;
  candidate_superposition_.attach(candidates_);
  synced_overlap_.clear();
  members_.resize(candidates_.size());
  for (std::size_t i = 0; i < candidates_.size(); ++i) members_[i] = static_cast<int>(i);
  working_ = true;
  revision_interval_ = 20;
  since_revision_ = 0;
  update_working_set();
}

bool IterativeSolver::update_working_set() {
  // Overlaps of every candidate under the working set's forces (the others carry none).
  const int n = static_cast<int>(candidates_.size());
  const int m = static_cast<int>(contacts_.size());
  revision_force_.assign(candidates_.size(), Eigen::Vector3d::Zero());
  revision_slot_.assign(candidates_.size(), -1);
  for (int i = 0; i < m; ++i) {
    revision_force_[members_[i]] = contacts_[i].force_on_a();
    revision_slot_[members_[i]] = i;
  }
  candidate_superposition_.contact_displacements(candidates_, revision_force_, true, revision_u_a_,
                                                 revision_u_b_);
  // A candidate joins when its overlap, extrapolated from its own rise since the last revision
  // over three more such intervals, comes within 2·t_d of touching (at the first revision, when
  // it is within the candidate margin).
  const bool first = synced_overlap_.size() != candidates_.size();
  revision_overlap_.resize(candidates_.size());
  const ContactGeometry& geometry = detector_.geometry();
#pragma omp parallel for schedule(static) if (n > 4096)
  for (int i = 0; i < n; ++i)
    revision_overlap_[i] =
        geometry.overlap_along_normal(candidates_[i], revision_u_a_[i], revision_u_b_[i]);
  if (first) synced_overlap_ = revision_overlap_;
  const std::vector<double>& overlap = revision_overlap_;
  const std::vector<int>& slot = revision_slot_;
  const double near = 2.0 * options_.overlap_tolerance;
  const bool momentum = iterate_.size() == static_cast<Eigen::Index>(contacts_.size());
  std::vector<int> members;
  members.reserve(members_.size() + 64);
  for (int i = 0; i < n; ++i) {
    const int k = slot[i];
    const double predicted =
        first ? overlap[i] + margin_
              : overlap[i] + 3.0 * std::max(0.0, overlap[i] - synced_overlap_[i]);
    const bool needed =
        predicted > -near ||
        (k >= 0 && (contacts_[k].force > 0.0 ||
                    (momentum && (iterate_[k] > 0.0 || previous_forces_[k] > 0.0))));
    if (needed) members.push_back(static_cast<int>(i));
  }
  synced_overlap_.swap(revision_overlap_);
  // The next revision: twice as far off while none joins (up to 160 iterations), 20 after one did.
  int newcomers = 0;
  for (int i : members) newcomers += slot[i] < 0;
  revision_interval_ = newcomers > 0 ? 20 : std::min(2 * revision_interval_, 160);
  if (members == members_ && contacts_.size() == members.size()) return false;
  // Rebuild: members keep their state and momentum, newcomers start from P = 0.
  std::vector<Contact> working(members.size());
  Eigen::VectorXd iterate = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(members.size()));
  Eigen::VectorXd previous = iterate;
  for (std::size_t j = 0; j < members.size(); ++j) {
    const int k = slot[members[j]];
    working[j] = k >= 0 ? contacts_[k] : candidates_[members[j]];
    working[j].overlap = synced_overlap_[members[j]];
    if (k < 0) working[j].force = 0.0;
    if (k >= 0 && momentum) iterate[j] = iterate_[k], previous[j] = previous_forces_[k];
  }
  contacts_ = std::move(working);
  members_ = std::move(members);
  if (momentum) iterate_ = std::move(iterate), previous_forces_ = std::move(previous);
  superposition_.attach(contacts_);
  forces_gathered_ = false;
  return true;
}

void IterativeSolver::leave_working_set() {
  if (!working_) return;
  // Every candidate back in contacts_, the working set's state written into its own.
  const bool momentum = iterate_.size() == static_cast<Eigen::Index>(contacts_.size());
  Eigen::VectorXd iterate = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(candidates_.size()));
  Eigen::VectorXd previous = iterate;
  for (Contact& c : candidates_) c.force = 0.0;
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    candidates_[members_[i]] = contacts_[i];
    if (momentum) iterate[members_[i]] = iterate_[i], previous[members_[i]] = previous_forces_[i];
  }
  contacts_ = std::move(candidates_);
  candidates_.clear();
  if (momentum) iterate_ = std::move(iterate), previous_forces_ = std::move(previous);
  superposition_.attach(contacts_);
  forces_gathered_ = false;
  working_ = false;
}

bool IterativeSolver::moved_beyond_margin() {
  gather_forces();
  compute_grid();
  double largest = 0.0;
  for (std::size_t f = 0; f < fibres_.size(); ++f)
    for (std::size_t j = 0; j < grid_u_[f].size(); ++j)
      largest = std::max(largest, (grid_u_[f][j] - grid_u_at_detection_[f][j]).norm());
  return largest > 0.5 * margin_;
}

void IterativeSolver::estimate_step() {
  // The seed's rule steps by c·D (c/n per slice, Eq. 4.28): its stability limit is that of
  // D½·W·D½, in the units of the scene's c. The other rules step uniformly.
  // With Coulomb friction the step acts on the friction forces too: the limit is that of the
  // frictional Delassus operator.
  const bool seed = options_.rule == UpdateRule::seed;
  lambda_max_ = ComplianceOperator(superposition_, contacts_, seed, coulomb_).largest_eigenvalue();
  if (seed)
    step_ = *options_.c;
  else
    step_ = lambda_max_ > 0.0 ? 1.0 / lambda_max_ : 0.0;
  divergence_.set_unstable_step(step_ * lambda_max_ > 2.0);
}

std::optional<std::string> IterativeSolver::find_unresolvable() const {
  // An overlap at a point neither fibre can move (a pinned support of both, or a normal along both
  // axes) can never be removed: say so at once instead of iterating.
  std::vector<double> overlap(contacts_.size()), compliance(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    overlap[k] = contacts_[k].overlap;
    compliance[k] = self_compliance(contacts_[k], fibres_);
  }
  return find_unresolvable_overlap(contacts_, overlap, compliance, options_.overlap_tolerance,
                                   fibres_, scene_.walls);
}

bool IterativeSolver::detect_again(Status& status, Criterion& criterion, std::string& message) {
  detect_contacts();
  const auto why = find_unresolvable();
  if (!why) return true;
  evaluate();
  status = Status::unresolvable;
  criterion = Criterion::unresolvable;
  message = *why;
  return false;
}

void IterativeSolver::evaluate() {
  if (!forces_gathered_) gather_forces();
  superposition_.contact_displacements(contacts_, force_on_a_, true, u_a_, u_b_, &exact_energy_);
  detector_.geometry().measure(contacts_, u_a_, u_b_, coulomb_);
  residuals_ = measure_residuals(contacts_);
  if (coulomb_) tresca_ = tresca_figures(contacts_, bound_);
}

bool IterativeSolver::update_tresca_bounds() {
  // Coulomb holds once the radii are μ times the normal forces they produced: a slipping
  // contact's radius must be μP, a sticking one's friction within μP. Each violation times the
  // contact's compliance is the slip it could still cause; and the answer must satisfy Coulomb's
  // law itself as the result reports it (no slip where |F| < μP, slip along F where |F| = μP):
  // near the edge of the cone a radius a little short of μP lets a contact slide freely.
  // Slipping on its circle (a zero radius lets the contact slip freely: its radius must become μP
  // too).
  auto on_its_circle = [&](Eigen::Index i, double size) {
    return !(bound_[i] > 0.0) || size >= (1.0 - 1e-9) * bound_[i];
  };
  double change = 0.0;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const double g = mu_ * contacts_[k].force;
    const Eigen::Index i = static_cast<Eigen::Index>(k);
    const double size = contacts_[k].friction.norm();
    const bool slipping = on_its_circle(i, size);
    change = std::max(change, (slipping ? std::fabs(g - bound_[i]) : std::max(0.0, size - g)) *
                                  self_compliance(contacts_[k], fibres_));
  }
  const FrictionFigures coulomb = friction_figures(contacts_, mu_, FrictionModel::coulomb);
  change = std::max({change, coulomb.stick_residual, coulomb.slip_residual});
  ++tresca_updates_;
  // Relaxed when the violation stops falling: the plain map g ← μP settles into cycles on
  // compacted tows of 100 fibres (a radius whose own normal force falls faster than it grows).
  // Halved when the violation grows, grown again while it falls steadily. Once it is below the
  // tolerance the radii become μP exactly, and the inner problem is solved once more with them
  // unless they already were: the answer is then that of radii within the tolerance of μP.
  const bool settled = change < options_.overlap_tolerance;
  // Settled twice in a row: the last inner problem had the radii μP of the one before, so that
  // scaling its slipping contacts to their own μP moves nothing by more than the tolerance.
  const bool exact_before = tresca_relaxation_ == 1.0 && tresca_settled_before_;
  tresca_settled_before_ = settled;
  if (settled)
    tresca_relaxation_ = 1.0;
  else if (change > last_tresca_change_)
    tresca_relaxation_ = std::max(tresca_relaxation_ * 0.5, 1.0 / 64.0), tresca_falling_ = 0;
  else if (++tresca_falling_ >= 3)
    tresca_relaxation_ = std::min(tresca_relaxation_ * 1.5, 1.0), tresca_falling_ = 0;
  last_tresca_change_ = change;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Eigen::Index i = static_cast<Eigen::Index>(k);
    Eigen::Vector3d& F = contacts_[k].friction;
    const double size = F.norm();
    const bool slipping = on_its_circle(i, size);
    bound_[i] += tresca_relaxation_ * (mu_ * contacts_[k].force - bound_[i]);
    // A contact that slipped on its old circle slips on the new one. At the end, one that slipped
    // with no friction (it pushed only after the last inner problem, with a force too small to
    // matter: μP·C below the tolerance) takes μP along its slip, as the projected step would.
    const double slip = contacts_[k].slip.norm();
    if (slipping && size > 0.0)
      F *= bound_[i] / size;
    else if (slipping && slip > 0.0 && settled && exact_before)
      F = bound_[i] / slip * contacts_[k].slip;
    if (coulomb_ && friction_iterate_.size() == contacts_.size()) friction_iterate_[k] = F;
  }
  if (settled && exact_before) return false;
  // A new inner problem: the momentum of the last one does not carry over.
  momentum_t_ = 1.0;
  previous_forces_ = iterate_;
  previous_friction_ = friction_iterate_;
  divergence_.reset();
  return true;
}

void IterativeSolver::update_forces() {
  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  const double mu = mu_;
  const bool coulomb = coulomb_;
  const bool seed = options_.rule == UpdateRule::seed;
  const bool accelerated = options_.rule == UpdateRule::accelerated;
  Contact* const contact = contacts_.data();
  Eigen::VectorXd& next = next_forces_;
  next.resize(n);
  if (coulomb) next_friction_.resize(n);
  Eigen::Vector3d* const next_friction = next_friction_.data();
  const double* const bound = bound_.data();
  // §4.3.2: P' = max(0, P + c·d); under rule seed slices take c/n (Eq. 4.28). Coulomb friction
  // steps the same way on the slip, F' = the point of the disk |F| ≤ μP' nearest to F + c·s
  // (Eq. 4.31). The accelerated rule's restart test (gradient restart: −(d, s)·(r_{k+1} − r_k) > 0)
  // is summed in the same pass.
  // The restart test is summed in fixed blocks, added in order: the same decisions on any number
  // of threads.
  constexpr Eigen::Index kBlock = 8192;
  const Eigen::Index blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> uphill_part(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (Eigen::Index b = 0; b < blocks; ++b) {
    double part = 0.0;
    for (Eigen::Index k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
      const Contact& c = contact[k];
      const double step = seed ? step_ * c.weight : step_;
      next[k] = std::max(0.0, c.force + step * c.overlap);
      if (accelerated) part += -c.overlap * (next[k] - iterate_[k]);
      if (!coulomb) continue;
      next_friction[k] = onto_coulomb_disk(c.friction + step * c.slip, bound[k]);
      if (accelerated) part += -c.slip.dot(next_friction[k] - friction_iterate_[k]);
    }
    uphill_part[b] = part;
  }
  double uphill = 0.0;
  for (double part : uphill_part) uphill += part;
  if (accelerated) {
    // Nesterov momentum on the same projected step, restarted when the step has pointed uphill on
    // kRestartStreak iterations in a row. Single uphill steps come and go as force-free contacts
    // turn their normals and contacts open; restarting on each (the plain gradient restart) cost
    // 30–50% more iterations on generated tows of 19–300 fibres.
    uphill_streak_ = uphill > 0.0 ? uphill_streak_ + 1 : 0;
    const bool restart = uphill_streak_ >= kRestartStreak;
    if (restart) uphill_streak_ = 0, momentum_t_ = 1.0;
    const double t_next = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum_t_ * momentum_t_));
    const double beta = (momentum_t_ - 1.0) / t_next;
    momentum_t_ = restart ? 1.0 : t_next;
    previous_forces_.swap(iterate_);  // P_{k−1} ← P_k, without copying
    iterate_.swap(next);              // P_k ← P'
    next.resize(n);
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
    for (Eigen::Index k = 0; k < n; ++k)
      next[k] = std::max(0.0, iterate_[k] + beta * (iterate_[k] - previous_forces_[k]));
    if (coulomb) {
      previous_friction_.swap(friction_iterate_);
      friction_iterate_.swap(next_friction_);
      next_friction_.resize(n);
      for (Eigen::Index k = 0; k < n; ++k)
        next_friction_[k] = onto_coulomb_disk(
            friction_iterate_[k] + beta * (friction_iterate_[k] - previous_friction_[k]),
            bound_[k]);
    }
  }
  const ContactGeometry& geometry = detector_.geometry();
  const bool seed_friction = seed_friction_;
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (Eigen::Index k = 0; k < n; ++k) {
    Contact& c = contact[k];
    if (coulomb) c.friction = next_friction_[k];
    if (seed_friction)  // §4.3.4: keep last iteration's resultant, split on the deformed normal
      c.friction = coulomb_capped_friction(
          force_on_a_[k], geometry.deformed_normal(c, u_a_[k], u_b_[k]), next[k], mu);
    c.force = next[k];
    force_on_a_[k] = c.force_on_a();  // gathered here, saving a pass over the contacts
  }
  forces_gathered_ = true;
}

bool IterativeSolver::record_history(long iteration) const {
  if (iteration <= 100) return true;
  // About 40 entries per decade beyond the first hundred.
  const double decade = std::log10(static_cast<double>(iteration));
  const double previous = std::log10(static_cast<double>(iteration - 1));
  return std::floor(decade * 40.0) != std::floor(previous * 40.0);
}

Result IterativeSolver::run() {
  const auto start = Clock::now();
  detect_contacts();
  warnings_ = ambiguous_side_warnings(contacts_, fibres_, scene_.walls);
  if (auto why = find_unresolvable()) {
    evaluate();
    Result result = assemble(start);
    result.status = Status::unresolvable;
    result.criterion = Criterion::unresolvable;
    result.message = *why;
    return result;
  }

  Status status = Status::max_iterations;
  Criterion criterion = Criterion::max_iterations;
  std::string message;
  const bool energy_each_iteration = options_.energy_tolerance > 0.0;
  Eigen::VectorXd best_forces;
  std::vector<Eigen::Vector3d> best_friction;
  double best_residual = INFINITY;
  auto last_progress = Clock::now();
  long iteration = 0;
  const bool projected = options_.rule == UpdateRule::conjugate_gradient;
  if (projected) run_projected_cg(iteration, status, criterion, message, start);
  for (iteration = projected ? iteration : 1; !projected && iteration <= options_.max_iterations;
       ++iteration) {
    evaluate();
    // With Coulomb friction the slips must settle too: they are part of the residual watched.
    const double residual =
        coulomb_ ? std::max({residuals_.total(), tresca_.stick_residual, tresca_.slip_residual})
                 : residuals_.total();
    double energy = NAN;
    if (energy_each_iteration || record_history(iteration))
      energy = superposition_.trapezium_energy(force_on_a_, scene_.contact.slices);
    if (record_history(iteration)) history_.push_back({iteration, residuals_.max_overlap, energy});

    if (!std::isfinite(residual) || !std::isfinite(exact_energy_)) {
      status = Status::diverged;
      criterion = Criterion::non_finite;
      message = "non-finite forces or displacements";
      break;
    }
    if (residual < best_residual) {
      best_residual = residual;
      best_forces.resize(static_cast<Eigen::Index>(contacts_.size()));
      best_friction.resize(contacts_.size());
      for (std::size_t k = 0; k < contacts_.size(); ++k) {
        best_forces[k] = contacts_[k].force;
        best_friction[k] = contacts_[k].friction;
      }
    }
    const bool friction_settled =
        !coulomb_ || (tresca_.stick_residual < options_.overlap_tolerance &&
                      tresca_.slip_residual < options_.overlap_tolerance);
    if (residuals_.overlap < options_.overlap_tolerance &&
        residuals_.gap_force < options_.overlap_tolerance && friction_settled) {
      // Before stopping, make sure no candidate outside the working set overlaps and no contact
      // outside the candidate list appeared.
      if (working_ && update_working_set()) continue;
      if (moved_beyond_margin()) {
        detect_contacts();
        continue;
      }
      if (coulomb_ && update_tresca_bounds()) continue;
      status = Status::converged;
      criterion = Criterion::contact;
      break;
    }
    if (energy_each_iteration && energy_window_.push(energy)) {
      status = Status::converged;
      criterion = Criterion::energy;
      break;
    }
    const auto verdict = divergence_.observe(iteration, residual);
    if (verdict != DivergenceMonitor::Verdict::fine) {
      std::ostringstream out;
      out.precision(3);
      out << (verdict == DivergenceMonitor::Verdict::growth ? "residual grew without bound"
                                                            : "no progress: the update oscillates")
          << " (c = " << step_ << " N/mm; the step is stable below about " << 2.0 / lambda_max_
          << " N/mm, 2/lambda_max of the compliance it steps on)";
      status = Status::diverged;
      criterion = verdict == DivergenceMonitor::Verdict::growth ? Criterion::growth
                                                                : Criterion::oscillation;
      message = out.str();
      break;
    }
    if (options_.progress && seconds_since(last_progress) >= options_.progress_interval_s) {
      last_progress = Clock::now();
      options_.progress({iteration, options_.max_iterations, residuals_.overlap,
                         residuals_.gap_force, options_.overlap_tolerance,
                         working_ ? candidates_.size() : contacts_.size(), seconds_since(start)});
    }
    update_forces();
    if (working_ && ++since_revision_ >= revision_interval_) {
      since_revision_ = 0;
      update_working_set();
    }
    // The working set's rules move the fibres smoothly: their shape is checked against the
    // candidate margin every 50 iterations (a deflection field of every fibre at the grid costs
    // more than an iteration on the working set); the others every 10.
    if (iteration % (working_ ? 50 : 10) == 0 && moved_beyond_margin()) {
      // The divergence monitor keeps its best residual across re-detections: a rule that moves
      // the fibres enough to re-detect every few iterations (the seed's friction rule on a
      // compacted 100-fibre tow, residual 0.03 mm) would otherwise never be judged stalled.
      if (!detect_again(status, criterion, message)) break;
    }
  }
  if (status == Status::diverged &&
      best_forces.size() == static_cast<Eigen::Index>(contacts_.size())) {
    // Report the best state seen, never a non-finite one.
    for (std::size_t k = 0; k < contacts_.size(); ++k) {
      contacts_[k].force = best_forces[k];
      contacts_[k].friction = best_friction[k];
    }
    forces_gathered_ = false;
    evaluate();
  }
  if (status == Status::max_iterations) {
    iteration = options_.max_iterations;
    std::ostringstream out;
    out.precision(3);
    out << "stopped after " << iteration << " iterations with overlap residual "
        << residuals_.overlap << " mm and gap-force residual " << residuals_.gap_force
        << " mm (tolerance " << options_.overlap_tolerance << " mm)";
    if (options_.rule != UpdateRule::accelerated)
      out << "; rule accelerated needs far fewer iterations where the compliance is "
             "ill-conditioned (line contacts near supports, tows)";
    else
      out << "; raise solver.max_iterations or loosen solver.overlap_tolerance";
    message = out.str();
  }
  Result result = assemble(start);
  result.status = status;
  result.criterion = criterion;
  result.message = message;
  result.iterations = std::min(iteration, options_.max_iterations);
  return result;
}

void IterativeSolver::run_projected_cg(long& iteration, Status& status, Criterion& criterion,
                                       std::string& message, Clock::time_point start) {
  // Rule cg: each candidate list's quadratic programme solved by preconditioned conjugate
  // gradients with projections (projected_cg.h); then, as for the other rules, the overlaps are
  // measured afresh through the superposition, and the candidates found again if the fibres moved
  // beyond the margin. `iteration` counts applications of W, one per iteration of the other rules.
  const double tolerance = options_.overlap_tolerance;
  auto last_progress = Clock::now();
  ContactQuadraticProgramme problem;
  problem.compliance = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    ComplianceOperator(superposition_, contacts_).apply(x, y);
  };
  problem.preconditioner = [&](const Eigen::VectorXd& r, const std::vector<unsigned char>& free,
                               Eigen::VectorXd& z) { stiffness_.apply(r, free, z); };
  Eigen::VectorXd P, g;
  status = Status::max_iterations;
  criterion = Criterion::max_iterations;
  iteration = 1;
  while (true) {
    evaluate();
    const double residual = residuals_.total();
    const double energy = superposition_.trapezium_energy(force_on_a_, scene_.contact.slices);
    history_.push_back({iteration, residuals_.max_overlap, energy});
    if (!std::isfinite(residual) || !std::isfinite(exact_energy_)) {
      status = Status::diverged;
      criterion = Criterion::non_finite;
      message = "non-finite forces or displacements";
      return;
    }
    if (options_.progress && seconds_since(last_progress) >= options_.progress_interval_s) {
      last_progress = Clock::now();
      options_.progress({iteration, options_.max_iterations, residuals_.overlap,
                         residuals_.gap_force, tolerance, contacts_.size(), seconds_since(start)});
    }
    if (residuals_.overlap < tolerance && residuals_.gap_force < tolerance) {
      if (moved_beyond_margin()) {
        if (!detect_again(status, criterion, message)) return;
        continue;
      }
      status = Status::converged;
      criterion = Criterion::contact;
      return;
    }
    if (iteration >= options_.max_iterations) return;
    const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
    P.resize(n);
    g.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      P[k] = contacts_[k].force;
      g[k] = -contacts_[k].overlap;
    }
    problem.largest_eigenvalue = lambda_max_;
    // Half the tolerance by the recurrence, so that the overlaps measured afresh meet it.
    const ProjectedCgOutcome outcome =
        solve_by_projected_cg(problem, P, g, 0.5 * tolerance, options_.max_iterations - iteration);
    iteration += std::max(1L, outcome.compliance_products);
    iteration = std::min(iteration, options_.max_iterations);
    for (Eigen::Index k = 0; k < n; ++k) contacts_[k].force = P[k];
    forces_gathered_ = false;
  }
}

Result IterativeSolver::assemble(Clock::time_point start) {
  leave_working_set();
  Result r;
  r.scene = scene_.name;
  r.solver = "iterative";
  r.rule = to_string(options_.rule);
  gather_forces();
  r.strain_energy = superposition_.trapezium_energy(force_on_a_, scene_.contact.slices);
  superposition_.contact_displacements(contacts_, force_on_a_, true, u_a_, u_b_,
                                       &r.strain_energy_exact);
  r.max_overlap = residuals_.max_overlap;
  r.gap_force_residual = residuals_.gap_force;
  r.c = step_;
  r.c_stable_limit = lambda_max_ > 0.0 ? 2.0 / lambda_max_ : 0.0;
  r.axial_load_dropped = superposition_.axial_load_dropped(contacts_, force_on_a_);
  r.candidates = static_cast<long>(contacts_.size());
  r.warnings = warnings_;
  if (mu_ > 0.0) {
    detector_.geometry().measure(contacts_, u_a_, u_b_, true);
    r.friction = friction_figures(contacts_, mu_, scene_.contact.friction_model);
    r.friction->fixed_point_updates = tresca_updates_;
  }

  r.stages.push_back("superposition");
  if (detector_.broad_phase()) r.stages.push_back("broad_phase");
  if (detector_.point_search()) r.stages.push_back("point_contacts");
  if (detector_.slicing()) r.stages.push_back("slices");
  if (detector_.walls()) r.stages.push_back("walls");
  if (mu_ > 0.0)
    r.stages.push_back(std::string("friction_") + to_string(scene_.contact.friction_model));
  if (options_.energy_tolerance > 0.0) r.stages.push_back("energy_criterion");
  r.stages.push_back(std::string("update_") + to_string(options_.rule));

  const int samples = scene_.output.samples;
  std::vector<double> s(samples);
  for (int j = 0; j < samples; ++j) s[j] = static_cast<double>(j) / (samples - 1);
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    FibreResult fr;
    fr.id = fibres_[f].id;
    superposition_.fibre_field(static_cast<int>(f), force_on_a_, true, s, fr.displacement,
                               &fr.moment);
    r.fibres.push_back(std::move(fr));
  }

  r.contacts = contact_results(contacts_, fibres_, scene_.walls, force_on_a_, u_a_, u_b_, mu_);
  r.walls = wall_results(contacts_, fibres_, scene_.walls);
  r.history = history_;
  assess_validity(r, fibres_);
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
