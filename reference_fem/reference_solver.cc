#include "reference_solver.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include "ambiguous_sides.h"
#include "carry_over.h"
#include "frictional_working_set.h"
#include "line_force_extrapolation.h"
#include "load_path_solve.h"
#include "memory_reach.h"
#include "nonnegative_active_set.h"
#include "primal_dual_active_set.h"
#include "process_sums.h"
#include "reference_solver_class.h"
#include "tresca_fixed_point.h"
#include "unresolvable_overlap.h"

namespace fibrecheck {

namespace {
/// Passes of the primal-dual active set before the active set of nonnegative_active_set finishes
/// from where it stopped.
constexpr int kPrimalDualPasses = 50;
}  // namespace

ReferenceSolver::ReferenceSolver(const Scene& scene, const ReferenceOptions& options)
    : scene_(scene),
      options_(options),
      comm_(options.communicator),
      rank_(dealii::Utilities::MPI::this_mpi_process(comm_)),
      processes_(dealii::Utilities::MPI::n_mpi_processes(comm_)),
      pcout_(std::cout, options.print_timing && rank_ == 0),
      // Timed on each process alone (no collective call per phase: a process with nothing to
      // mesh must not hold the others up); the statistics over processes are gathered at the end.
      timer_(MPI_COMM_SELF, pcout_, dealii::TimerOutput::never, dealii::TimerOutput::wall_times),
      fibres_(make_fibres(scene)),
      tolerance_(scene.overlap_tolerance()),
      detector_(fibres_, scene, candidate_margin(fibres_),
                options.line_contact == LineContact::continuous
                    ? LineQuadrature::gauss(continuous_cells(scene, options.refine))
                    : LineQuadrature::slices(scene.contact.slices)),
      grid_u_(fibres_.size(),
              std::vector<Eigen::Vector3d>(detector_.grid().size(), Eigen::Vector3d::Zero())),
      mu_(scene.contact.friction),
      within_reach_(memory_within_reach(comm_)) {
  owned_.assign(fibres_.size(), 0);
  for (std::size_t f = rank_; f < fibres_.size(); f += processes_) owned_[f] = 1;
  const int samples = scene.output.samples;
  for (int j = 0; j < samples; ++j) sample_s_.push_back(static_cast<double>(j) / (samples - 1));
  mesh_file_ =
      (std::filesystem::temp_directory_path() /
       ("fibrecheck_reference_" + std::to_string(getpid()) + "_" + std::to_string(rank_) + ".msh"))
          .string();
}

ReferenceSolver::~ReferenceSolver() {
  std::error_code ignored;
  std::filesystem::remove(mesh_file_, ignored);
}

// run: like deal.II's step-41, the candidates on the fibres under the scene's loads first; then
// mesh them, assemble and solve the contact problem, and detect again on the deformed fibres,
// until nothing new overlaps.
Result ReferenceSolver::run() {
  const auto start = std::chrono::steady_clock::now();
  deform_under_scene_loads();
  detect();
  take_last_step_forces();
  const std::vector<std::string> ambiguous =
      ambiguous_side_warnings(contacts_, fibres_, scene_.walls);
  OuterEnd end = OuterEnd::candidates_changing;
  int outer = 1;
  for (; outer <= options_.max_outer_iterations; ++outer) {
    make_grid();
    setup_system();
    if (trouble_.beyond_reach) {
      for (Contact& c : contacts_) c.force = 0.0;
      end = OuterEnd::no_answer;
      break;
    }
    assemble_system();
    solve(outer > 1 ? Start::last_answer : Start::frictionless);
    if (detector_.geometry().deformed() && trouble_.why.empty()) follow_the_deformed_fibres();
    if (!trouble_.why.empty()) {
      end = OuterEnd::no_answer;
      break;
    }
    const bool unchanged = update_active_set();
    report_progress(outer);
    if (unchanged) {
      end = OuterEnd::settled;
      break;
    }
  }
  // The last solve used the candidates before the final detection: mesh them again.
  if (end == OuterEnd::candidates_changing) {
    make_grid();
    setup_system();
  }
  Result r = reference_outcome(scene_.name, end, trouble_, options_.max_outer_iterations);
  output_results(r);
  hand_over_contact_problem(r.status);
  describe_run(r, ambiguous, std::min(outer, options_.max_outer_iterations), start);
  return r;
}

// The candidates of the first outer iteration are those of the fibres under the scene's loads: a
// mesh of the fibres alone (nodes at supports, slices, loads and the crossings of the undeformed
// fibres), solved once. Without loads the fibres stay straight.
void ReferenceSolver::deform_under_scene_loads() {
  if (scene_.loads.empty()) return;
  make_grid();
  setup_system();
  deform();
}

// Candidates on the finite-element fibres as last deformed (the shared detection); a contact found
// again keeps its force, and a pushing contact stays a candidate. `u_a` and `u_b` get the
// displacements of the finite-element fibres where each candidate acts.
void ReferenceSolver::detect(std::vector<Eigen::Vector3d>& u_a, std::vector<Eigen::Vector3d>& u_b) {
  std::vector<Contact> found = detector_.detect(grid_u_);
  const std::vector<long> origin = carry_over(contacts_, found);
  detector_.keep_crossing_places(grid_u_, found,
                                 moved_crossings_.empty() ? contacts_ : moved_crossings_, origin);
  moved_crossings_.clear();
  contacts_ = std::move(found);
  displacements_at_contacts(u_a, u_b);
  if (detector_.geometry().deformed()) place_on_the_finite_elements(u_a, u_b);
  if (mu_ > 0.0) origins_.set(contacts_);
}

void ReferenceSolver::detect() {
  std::vector<Eigen::Vector3d> u_a, u_b;
  detect(u_a, u_b);
}

// The detection measures the candidates on its grid, whose linear interpolation of a fibre that
// point forces bend errs by about h²κ/8, and a normal taken from it is off by that over the
// distance of the centres. Each candidate's normal and overlap are measured again at the
// finite-element fibres, so that every solve starts from the normals of its own configuration.
void ReferenceSolver::place_on_the_finite_elements(const std::vector<Eigen::Vector3d>& u_a,
                                                   const std::vector<Eigen::Vector3d>& u_b) {
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    detector_.geometry().follow(contacts_[k], u_a[k], u_b[k]);
    contacts_[k].overlap = detector_.geometry().overlap(contacts_[k], u_a[k], u_b[k]);
  }
}

// A load step of a path starts where the last one ended: a candidate the last step had takes its
// force and friction, and the first active set starts from the contacts that pushed there. The
// step's own candidates and slip origins stay as detected.
void ReferenceSolver::take_last_step_forces() {
  if (last_step_.empty()) return;
  std::unordered_map<std::uint64_t, const Contact*> last;
  for (const Contact& c : last_step_) last[c.key()] = &c;
  pushing_.assign(contacts_.size(), 0);
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    auto it = last.find(contacts_[k].key());
    if (it == last.end()) continue;
    contacts_[k].force = it->second->force;
    contacts_[k].friction = it->second->friction;
    pushing_[k] = contacts_[k].force > 0.0 ? 1 : 0;
  }
}

// make_grid: this process's fibres, with nodes at every contact station and sample position,
// meshed by Gmsh and read by deal.II.
void ReferenceSolver::make_grid() {
  dealii::TimerOutput::Scope scope(timer_, "make_grid");
  collect_stations();
  saddle_.reset();
  influence_.reset();
  frictional_influence_.reset();
  model_.reset();
  // A process with more processes than fibres may own none: it then only takes part in the sums.
  const bool owns = std::any_of(owned_.begin(), owned_.end(), [](char o) { return o != 0; });
  MeshOptions mesh = mesh_options();
  mesh.fibres = owned_;
  // Beyond reach, only the fibres under the scene's loads are solved (no node at the stations), or
  // nothing at all.
  if (trouble_.beyond_reach) mesh.contact_stations.assign(fibres_.size(), {});
  if (trouble_.fibres_beyond_reach) return;
  {
    dealii::TimerOutput::Scope gmsh(timer_, "make_grid: Gmsh");
    if (owns) write_mesh(scene_, mesh, mesh_file_);
  }
  dealii::TimerOutput::Scope read(timer_, "make_grid: GridIn");
  if (owns)
    model_ = std::make_unique<BeamModel>(scene_, mesh_file_, owned_, options_.beam_solver,
                                         options_.degree);
}

// setup_system: degrees of freedom, supports, the sparsity pattern.
void ReferenceSolver::setup_system() {
  dealii::TimerOutput::Scope scope(timer_, "setup_system");
  if (model_) model_->setup_system();
}

// solve: the complementarity problem, exactly, starting from the last pushing set; with friction
// then Coulomb's law from the frictionless answer, or straight from the last frictional answer
// (a geometric update of the deformed contact changes that answer little). An overlap at a point
// neither fibre can move (both pinned there) has no answer; a contact there that does not overlap
// is left out.
void ReferenceSolver::solve(Start start) {
  dealii::TimerOutput::Scope scope(timer_, "solve");
  const Eigen::Index n = d0_.size();
  if (trouble_.non_finite) {
    trouble_.why = "the finite-element solutions are not finite (a singular beam system?)";
    for (Contact& c : contacts_) c.force = 0.0;
    return;
  }
  std::vector<double> overlap(d0_.data(), d0_.data() + n), compliance(n);
  // Held as saddle points, a contact nothing can move is one whose every side is pinned.
  const std::vector<char> pinned = saddle_ ? saddle_->immovable() : std::vector<char>();
  const Eigen::VectorXd diagonal = saddle_               ? Eigen::VectorXd()
                                   : compliance_shared() ? influence_->diagonal()
                                                         : W_.diagonal();
  for (Eigen::Index k = 0; k < n; ++k)
    compliance[k] = saddle_ ? (pinned[k] ? 0.0 : std::numeric_limits<double>::max()) : diagonal[k];
  if (auto why = find_unresolvable_overlap(contacts_, overlap, compliance, tolerance_, fibres_,
                                           scene_.walls)) {
    trouble_.why = *why;
    for (Contact& c : contacts_) c.force = 0.0;
    return;
  }
  const double immovable = immovable_compliance(fibres_);
  std::vector<char> excluded(n, 0);
  for (Eigen::Index k = 0; k < n; ++k) excluded[k] = compliance[k] <= immovable ? 1 : 0;
  // Overlaps are decided far below the scene's tolerance, but not below the round-off of the
  // finite-element data (about 1e-14 of the largest overlap under the loads): a line force is
  // barely determined by the overlaps (a force near a pinned end moves nothing), so a coarser
  // threshold leaves a fine continuous line contact with too few points pushing.
  threshold_ =
      std::max(1e-6 * tolerance_, 1e-13 * (d0_.size() > 0 ? d0_.cwiseAbs().maxCoeff() : 0.0));
  if (mu_ > 0.0 && start == Start::last_answer) {
    pushing_.resize(n, 0);
    P_.conservativeResize(n);
    solve_friction(excluded, start);
  } else if (solve_frictionless(excluded) && mu_ > 0.0) {
    solve_friction(excluded, Start::frictionless);
  }
  if (options_.contact_problem) keep_contact_problem(excluded);
}

// The frictionless problem P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 by the active set, from the pushing set
// of the last outer iteration; every contact's force is its answer (zero when there is none).
bool ReferenceSolver::solve_frictionless(const std::vector<char>& excluded) {
  const Eigen::Index n = d0_.size();
  pushing_.resize(n, 0);
  const AssembledCompliance assembled(W_);
  const ContactCompliance& W = saddle_ ? static_cast<const ContactCompliance&>(*saddle_)
                               : compliance_shared()
                                   ? *influence_
                                   : static_cast<const ContactCompliance&>(assembled);
  // The primal-dual active set changes the set as much as it needs in a pass, and from a warm
  // start (the pushing set of the last geometric update or outer iteration) it takes a handful.
  // From cold its first set is every contact that overlaps under the loads alone, on a tow many
  // times the set that pushes at the end, whose W_SS takes more memory to factorise than the rest
  // of the contact problem; the block active set, which grows its set from nothing, starts there.
  // Held as saddle points each pass is a whole factorisation, and the primal-dual set goes first.
  // Where it cycles the block active set finishes from its last set.
  ActiveSetSolve solved;
  const bool warm = std::any_of(pushing_.begin(), pushing_.end(), [](char p) { return p != 0; });
  if (saddle_ || warm) {
    solved = primal_dual_active_set(W, d0_, threshold_, excluded, kPrimalDualPasses, P_, pushing_);
    active_set_iterations_ += solved.passes;
  }
  if (!solved.solved) {
    solved = nonnegative_active_set(W, d0_, threshold_, excluded,
                                    options_.max_active_set_iterations, P_, pushing_);
    active_set_iterations_ += solved.passes;
  }
  if (solved.singular)
    trouble_.why =
        "the pushing contacts' compliance matrix is singular (contacts that constrain the "
        "same motion twice)";
  else if (!solved.solved)
    trouble_.why = "the active-set method did not finish in " +
                   std::to_string(options_.max_active_set_iterations) + " passes";
  for (Eigen::Index k = 0; k < n; ++k) contacts_[k].force = solved.solved ? P_[k] : 0.0;
  return solved.solved;
}

// solve_friction: Coulomb's law at every candidate, exactly (tresca_fixed_point.h) on a working set
// of them (frictional_working_set.h), from the frictionless answer just found (or the normal forces
// of the last frictional answer) and the friction forces the candidates carried over.
void ReferenceSolver::solve_friction(const std::vector<char>& excluded, Start start) {
  FrictionalProblem& problem = friction_problem_;
  problem.excluded = excluded;
  const Eigen::Index n = d0_.size();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(problem.offset[n]);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const Eigen::Index o = problem.offset[k];
    r[o] = start == Start::last_answer ? c.force : P_[k];
    if (c.tangents >= 1) r[o + 1] = c.tangent.dot(c.friction);
    if (c.tangents == 2) r[o + 2] = c.second_tangent().dot(c.friction);
  }
  TrescaOptions options;
  options.threshold = threshold_;
  options.tolerance = tolerance_;
  options.slack = friction_slack_;
  options.max_active_set_passes = options_.max_active_set_iterations;
  const AssembledCompliance assembled(problem.W);
  const ContactCompliance& W = frictional_influence_
                                   ? static_cast<const ContactCompliance&>(*frictional_influence_)
                                   : assembled;
  const TrescaSolve solved = tresca_on_working_set(W, problem, options, r);
  active_set_iterations_ += solved.active_set_passes;
  newton_steps_ += solved.newton_steps;
  tresca_updates_ += solved.updates;
  newton_finishes_ += solved.finished_by_newton ? 1 : 0;
  if (solved.settled && solved.settled_to > solved.aimed &&
      solved.settled_to > friction_settled_to_)
    friction_settled_to_ = solved.settled_to, friction_aimed_ = solved.aimed;
  if (!solved.settled) {
    trouble_.why = solved.trouble;
    trouble_.friction_unsettled = true;
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    Contact& c = contacts_[k];
    const Eigen::Index o = problem.offset[k];
    c.force = std::max(r[o], 0.0);
    c.friction.setZero();
    if (c.tangents >= 1) c.friction += r[o + 1] * c.tangent;
    if (c.tangents == 2) c.friction += r[o + 2] * c.second_tangent();
    P_[k] = c.force;
    pushing_[k] = c.force > 0.0 ? 1 : 0;
  }
}

void ReferenceSolver::keep_contact_problem(const std::vector<char>& excluded) {
  ContactProblem& p = exported_;
  p.scene = scene_.name;
  p.mu = mu_;
  p.contacts.clear();
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& c = contacts_[k];
    ProblemContact pc;
    pc.kind = to_string(c.kind);
    pc.fibres.push_back(fibres_[c.a].id);
    if (c.kind != ContactKind::wall) pc.fibres.push_back(fibres_[c.b].id);
    pc.tangents = mu_ > 0.0 ? c.tangents : 0;
    pc.excluded = excluded[k] != 0;
    p.contacts.push_back(std::move(pc));
  }
  set_offsets(p);
  p.W = mu_ > 0.0 ? friction_problem_.W : W_;
  p.q = mu_ > 0.0 ? friction_problem_.q : d0_;
  p.reaction = Eigen::VectorXd::Zero(p.offset.back());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& c = contacts_[k];
    const Eigen::Index o = p.offset[k];
    p.reaction[o] = c.force;
    if (p.contacts[k].tangents >= 1) p.reaction[o + 1] = c.tangent.dot(c.friction);
    if (p.contacts[k].tangents == 2) p.reaction[o + 2] = c.second_tangent().dot(c.friction);
  }
}

// The step's contact problem as last solved, with the step's status, to options_.contact_problem.
void ReferenceSolver::hand_over_contact_problem(Status status) {
  if (!options_.contact_problem) return;
  if (exported_.offset.empty()) set_offsets(exported_);
  exported_.status = to_string(status);
  options_.contact_problem(exported_);
}

// update_active_set: candidates again on the deformed fibres. The answer stands unless a new
// candidate overlaps (or, on the deformed fibres, a crossing moved off its station).
bool ReferenceSolver::update_active_set() {
  dealii::TimerOutput::Scope scope(timer_, "update_active_set");
  std::set<std::uint64_t> known;
  for (const Contact& c : contacts_) known.insert(c.key());
  std::map<std::uint64_t, char> was_pushing;
  for (std::size_t k = 0; k < contacts_.size(); ++k)
    was_pushing[contacts_[k].key()] = k < pushing_.size() ? pushing_[k] : 0;
  std::vector<Contact> solved = contacts_;
  deform();
  std::vector<Eigen::Vector3d> ua, ub;
  detect(ua, ub);
  bool unchanged = !remesh_;
  remesh_ = false;
  pushing_.assign(contacts_.size(), 0);
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const std::uint64_t key = contacts_[k].key();
    auto it = was_pushing.find(key);
    if (it != was_pushing.end()) pushing_[k] = it->second;
    if (known.count(key) == 0 &&
        detector_.geometry().overlap(contacts_[k], ua[k], ub[k]) > threshold_)
      unchanged = false;
  }
  // Nothing new overlaps: the answer is the one just solved, on the candidates it was solved with.
  if (unchanged) contacts_ = std::move(solved);
  return unchanged;
}

// A line after every outer iteration, for options_.progress.
void ReferenceSolver::report_progress(int outer) const {
  if (!options_.progress) return;
  std::size_t active = 0;
  for (const Contact& c : contacts_) active += c.force > 0.0 ? 1 : 0;
  options_.progress("outer iteration " + std::to_string(outer) + ": " + std::to_string(d0_.size()) +
                    " candidates, " + std::to_string(active) + " pushing, " +
                    std::to_string(active_set_iterations_) + " active-set passes so far");
}

int ReferenceSolver::station(int fibre, double s) const {
  const std::vector<double>& list = stations_[fibre];
  return static_cast<int>(std::lower_bound(list.begin(), list.end(), s - 1e-12) - list.begin());
}

// The forces on this process's fibres: the contact forces that push, on both sides.
std::vector<NodalForce> ReferenceSolver::nodal_forces() const {
  std::vector<NodalForce> forces;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& c = contacts_[k];
    if (!(c.force > 0.0)) continue;
    if (owned_[c.a]) forces.push_back({c.a, c.s_a, force_on_a_[k]});
    if (c.kind != ContactKind::wall && owned_[c.b]) forces.push_back({c.b, c.s_b, -force_on_a_[k]});
  }
  return forces;
}

// deform: the finite-element fibres under the scene's loads and the current contact forces, and
// their displacements at the detector's grid (every process ends with every fibre's).
void ReferenceSolver::deform() {
  gather_forces();
  const std::size_t m = detector_.grid().size();
  std::vector<double> packed(3 * m * fibres_.size(), 0.0);
  if (model_) {
    model_->run(nodal_forces(), true);
    for (std::size_t f = 0; f < fibres_.size(); ++f)
      if (owned_[f])
        for (std::size_t j = 0; j < m; ++j) {
          const Eigen::Vector3d u = model_->displacement(static_cast<int>(f), detector_.grid()[j]);
          for (int d = 0; d < 3; ++d) packed[3 * (f * m + j) + d] = u[d];
        }
  }
  sum_over_processes(packed, comm_);
  for (std::size_t f = 0; f < fibres_.size(); ++f)
    for (std::size_t j = 0; j < m; ++j)
      for (int d = 0; d < 3; ++d) {
        const double x = packed[3 * (f * m + j) + d];
        grid_u_[f][j][d] = std::isfinite(x) ? x : 0.0;
      }
}

// The last finite-element solution at both sides of every contact (mm), from the process that
// owns each fibre.
void ReferenceSolver::displacements_at_contacts(std::vector<Eigen::Vector3d>& u_a,
                                                std::vector<Eigen::Vector3d>& u_b) const {
  const std::size_t n = contacts_.size();
  std::vector<double> packed(6 * n, 0.0);
  for (std::size_t k = 0; model_ && k < n; ++k) {
    const Contact& c = contacts_[k];
    if (owned_[c.a]) {
      const Eigen::Vector3d u = model_->displacement(c.a, c.s_a);
      for (int d = 0; d < 3; ++d) packed[6 * k + d] = u[d];
    }
    if (c.kind != ContactKind::wall && owned_[c.b]) {
      const Eigen::Vector3d u = model_->displacement(c.b, c.s_b);
      for (int d = 0; d < 3; ++d) packed[6 * k + 3 + d] = u[d];
    }
  }
  sum_over_processes(packed, comm_);
  u_a.resize(n);
  u_b.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    u_a[k] = Eigen::Vector3d(packed[6 * k], packed[6 * k + 1], packed[6 * k + 2]);
    u_b[k] = Eigen::Vector3d(packed[6 * k + 3], packed[6 * k + 4], packed[6 * k + 5]);
  }
}

// Every fibre's contact stations (sorted, each once) and each contact's stations on A and B.
void ReferenceSolver::collect_stations() {
  stations_.assign(fibres_.size(), {});
  for (const Contact& c : contacts_) {
    stations_[c.a].push_back(c.s_a);
    if (c.kind != ContactKind::wall) stations_[c.b].push_back(c.s_b);
  }
  offset_.assign(fibres_.size() + 1, 0);
  g_offset_.assign(fibres_.size() + 1, 0);
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    std::vector<double>& list = stations_[f];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end(),
                           [](double x, double y) { return std::fabs(x - y) < 1e-12; }),
               list.end());
    offset_[f + 1] = offset_[f] + list.size();
    const bool held = owned_[f] || !compliance_shared();
    g_offset_[f + 1] = g_offset_[f] + (held ? list.size() * list.size() : 0);
  }
  station_a_.resize(contacts_.size());
  station_b_.resize(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    station_a_[k] = station(contacts_[k].a, contacts_[k].s_a);
    station_b_[k] =
        contacts_[k].kind == ContactKind::wall ? -1 : station(contacts_[k].b, contacts_[k].s_b);
  }
  check_memory_reach();
}

// The influence matrices are dense per fibre, and each process holds those of its own fibres
// (shared) or all of them and W; the finite elements of its own fibres grow with
// their unknowns. A problem that would not fit in the memory the machine has is not made: the step
// ends beyond reach, with what it would need on the process that needs most, rather than
// exhausting the machine in the middle of it. Where the contact problem alone is too much, the
// fibres under the scene's loads are still solved; where the finite elements are, nothing is
// meshed.
void ReferenceSolver::check_memory_reach() {
  std::vector<std::size_t> count(fibres_.size(), 0), sides(fibres_.size(), 0), frictional;
  if (mu_ > 0.0) frictional.assign(fibres_.size(), 0);
  // Shared, W is never formed: only the influence matrices of the process's own fibres.
  for (const Contact& c : contacts_)
    for (const int f : {c.a, c.kind == ContactKind::wall ? -1 : c.b}) {
      if (f < 0 || compliance_shared()) continue;
      ++sides[f];
      if (mu_ > 0.0) frictional[f] += 1 + c.tangents;
    }
  std::size_t widest = 0;
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    count[f] = compliance_shared() && !owned_[f] ? 0 : stations_[f].size();
    if (stations_[f].size() > stations_[widest].size()) widest = f;
  }
  MemoryNeed need =
      saddle_point() ? MemoryNeed() : contact_problem_memory(count, sides, frictional);
  need.finite_elements = finite_element_memory(own_unknowns());
  MPI_Allreduce(MPI_IN_PLACE, &need.influence, 1, MPI_DOUBLE, MPI_MAX, comm_);
  MPI_Allreduce(MPI_IN_PLACE, &need.compliance, 1, MPI_DOUBLE, MPI_MAX, comm_);
  MPI_Allreduce(MPI_IN_PLACE, &need.finite_elements, 1, MPI_DOUBLE, MPI_MAX, comm_);
  if (options_.progress && need.total() > (1 << 30))
    options_.progress(memory_line(need, within_reach_));
  if (need.total() <= within_reach_) return;
  trouble_.why = beyond_reach_message(need, within_reach_, fibres_[widest].id,
                                      stations_[widest].size(), saddle_point_possible());
  trouble_.beyond_reach = true;
  trouble_.fibres_beyond_reach = need.finite_elements > within_reach_;
}

// The unknowns of this process's fibres once meshed: four fields, each with a node per vertex and
// degree − 1 more per element.
double ReferenceSolver::own_unknowns() const {
  if (std::none_of(owned_.begin(), owned_.end(), [](char o) { return o != 0; })) return 0.0;
  MeshOptions mesh = mesh_options();
  mesh.fibres = owned_;
  const double elements = static_cast<double>(mesh_elements(scene_, mesh));
  double fibres = 0.0;
  for (char o : owned_) fibres += o ? 1.0 : 0.0;
  return 4.0 * (options_.degree * elements + fibres);
}

MeshOptions ReferenceSolver::mesh_options() const {
  MeshOptions mesh;
  mesh.size_per_slice = std::ldexp(1.0, -std::max(options_.refine, 0));
  mesh.contact_stations = stations_;
  mesh.sample_stations.assign(fibres_.size(), sample_s_);
  return mesh;
}

MeshOptions ReferenceSolver::first_mesh_options() {
  deform_under_scene_loads();
  detect();
  collect_stations();
  return mesh_options();
}

namespace {

/// Where a load step starts: the slip origins of the step before and its final contacts.
struct StepStart {
  SlipOrigins origins;
  std::vector<Contact> contacts;
};

/// One load step by its own ReferenceSolver, its slip measured from `from` and its active sets
/// started from `from`'s forces; `to` receives where the next step starts.
Result solve_step(const Scene& step, const ReferenceOptions& options, const StepStart& from,
                  StepStart& to) {
  ReferenceSolver solver(step, options);
  solver.start_from(from.origins);
  solver.guess_from(from.contacts);
  Result result = solver.run();
  to.origins = solver.end_state();
  to.contacts = solver.final_contacts();
  return result;
}

}  // namespace

// A load path step by step. Without friction each step's answer is that of its own geometry and
// loads, solved exactly; with friction each step's slip is measured from where the last one ended.
// Either way each step's active sets start from the forces the last step ended with. The
// continuous line contact, when it is to be refined until its line force settles, solves every
// refinement of a step from the same start.
Result solve_reference(const Scene& scene, const ReferenceOptions& options) {
  share_cores_with_blas(options.communicator);
  StepStart last;
  Result r = solve_load_path(scene, [&](const Scene& step, const Result*) {
    if (!options.refine_until_converged || options.line_contact != LineContact::continuous)
      return solve_step(step, options, last, last);
    const StepStart start = last;
    return solve_refined_until_settled(step, options, [&](const ReferenceOptions& once) {
      return solve_step(step, once, start, last);
    });
  });
  replace_non_finite(r);
  return r;
}

MeshOptions reference_mesh_options(const Scene& scene, const ReferenceOptions& options) {
  ReferenceOptions serial = options;
  serial.communicator = MPI_COMM_SELF;
  ReferenceSolver solver(scene, serial);
  return solver.first_mesh_options();
}

}  // namespace fibrecheck
