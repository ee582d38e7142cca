#include "reference_solver.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <mpi.h>
#include <unistd.h>

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "ambiguous_sides.h"
#include "beam_model.h"
#include "carry_over.h"
#include "contact.h"
#include "contact_detection.h"
#include "contact_problem.h"
#include "contact_results.h"
#include "fibre.h"
#include "fibre_mesh.h"
#include "frictional_contact.h"
#include "input_error.h"
#include "line_force_extrapolation.h"
#include "load_path_solve.h"
#include "nonnegative_active_set.h"
#include "process_sums.h"
#include "reference_result.h"
#include "result.h"
#include "scene.h"
#include "slip_origins.h"
#include "tresca_fixed_point.h"
#include "unresolvable_overlap.h"
#include "validity.h"

namespace fibrecheck {

/// One load step of the implicit reference (DESIGN §3), in the manner of
/// deal.II's step-41: `run()` meshes the fibres with a node at every contact
/// candidate, assembles the contact problem from finite-element solutions,
/// solves it exactly, and re-detects the candidates on the deformed
/// finite-element fibres, until they no longer change. The fibres are shared
/// out among the processes of `options.communicator`; every process ends with
/// the same result.
class ReferenceSolver {
 public:
  ReferenceSolver(const Scene& scene, const ReferenceOptions& options);
  ~ReferenceSolver();
  Result run();
  /// The mesh of the first outer iteration: the candidates on the fibres under
  /// the scene's loads.
  MeshOptions first_mesh_options();
  /// Friction: where this step's slip is measured from (the previous step's
  /// end).
  void start_from(SlipOrigins origins) { origins_ = std::move(origins); }
  /// After `run`: where the next step's slip is measured from.
  const SlipOrigins& end_state() const { return end_state_; }

 private:
  /// One side of a contact on a fibre: the contact, its station on that fibre,
  /// and the sign α of a unit normal force on it (−1 on fibre A, +1 on fibre B
  /// or a fibre against a wall).
  struct ContactSide {
    Eigen::Index contact;
    int station;
    double alpha;
    bool on_a;
  };
  /// The finite-element fields of the final state (mm and N·mm), every fibre's
  /// on every process.
  struct FinalFields {
    std::vector<double> stations;      ///< displacement at each contact station, packed
    std::vector<double> displacement;  ///< at each fibre's samples, 3 per sample
    std::vector<double> moment;        ///< bending moments at each fibre's samples, 2 per sample
  };

  // The phases of run(), in order.
  void deform_under_scene_loads();
  void detect();
  void make_grid();
  void setup_system();
  void assemble_system();
  void solve();
  bool update_active_set();
  void report_progress(int outer) const;
  void output_results(Result& r);
  void hand_over_contact_problem(Status status);
  void describe_run(Result& r, const std::vector<std::string>& ambiguous, int outer,
                    std::chrono::steady_clock::time_point start);

  // Meshing and detection.
  void collect_stations();
  MeshOptions mesh_options() const;
  void deform();
  void displacements_at_contacts(std::vector<Eigen::Vector3d>& u_a,
                                 std::vector<Eigen::Vector3d>& u_b) const;
  std::vector<NodalForce> nodal_forces() const;
  /// The force each contact's fibre A receives, from the contacts' forces.
  void gather_forces() {
    force_on_a_.resize(contacts_.size());
    for (std::size_t k = 0; k < contacts_.size(); ++k) force_on_a_[k] = contacts_[k].force_on_a();
  }
  int station(int fibre, double s) const;
  Eigen::Vector3d packed(const std::vector<double>& u, int fibre, int station) const {
    const double* v = &u[3 * (offset_[fibre] + station)];
    return {v[0], v[1], v[2]};
  }

  // The contact problem.
  std::vector<double> loads_and_influence();
  std::vector<std::vector<ContactSide>> assemble_compliance(const std::vector<double>& G);
  void assemble_frictional_problem(const std::vector<double>& G,
                                   const std::vector<std::vector<ContactSide>>& sides);
  Eigen::Vector3d reaction_direction(Eigen::Index k, int i, bool on_a) const;
  bool solve_frictionless(const std::vector<char>& excluded);
  void solve_friction(const std::vector<char>& excluded);
  /// The problem just solved, with its answer, for options_.contact_problem.
  void keep_contact_problem(const std::vector<char>& excluded);

  // The final state.
  FinalFields final_fields();
  void write_vtu() const;
  void measure_contacts(const std::vector<double>& u, Result& r, std::vector<Eigen::Vector3d>& u_a,
                        std::vector<Eigen::Vector3d>& u_b);
  void add_energies(Result& r);

  const Scene& scene_;
  ReferenceOptions options_;
  MPI_Comm comm_;
  unsigned int rank_ = 0, processes_ = 1;
  dealii::ConditionalOStream pcout_;
  dealii::TimerOutput timer_;
  std::vector<Fibre> fibres_;
  std::vector<char> owned_;  ///< fibres this process meshes and solves
  double tolerance_;
  double threshold_ = 0.0;  ///< overlaps the active set resolves: far below the tolerance
  ContactDetector detector_;
  /// Each fibre's finite-element displacements (mm) at the detector's grid, for
  /// detection.
  std::vector<std::vector<Eigen::Vector3d>> grid_u_;
  std::vector<double> sample_s_;

  std::vector<Contact> contacts_;
  std::vector<Eigen::Vector3d> force_on_a_;
  /// Per fibre, the sorted fractions where contacts act on it; per contact, its
  /// stations on A, B.
  std::vector<std::vector<double>> stations_;
  std::vector<int> station_a_, station_b_;
  std::vector<std::size_t> offset_,
      g_offset_;  ///< per fibre, into packed station data and G
  std::string mesh_file_;
  std::unique_ptr<BeamModel> model_;
  std::vector<double> u0_;  ///< displacements at every station under the scene's loads
  Eigen::VectorXd d0_, P_;
  /// W is sparse: two contacts interact only through a fibre they share.
  Eigen::SparseMatrix<double> W_;
  std::vector<char> pushing_;
  long active_set_iterations_ = 0;
  ReferenceTrouble trouble_;  ///< why the problem could not be solved, if it could not

  double mu_;
  SlipOrigins origins_, end_state_;
  /// The frictional problem of the candidates (μ > 0): W with the tangential
  /// blocks and q.
  FrictionalProblem friction_problem_;
  ContactProblem exported_;  ///< the problem last solved (only with
                             ///< options_.contact_problem)
  long newton_steps_ = 0;
  long tresca_updates_ = 0;
};

ReferenceSolver::ReferenceSolver(const Scene& scene, const ReferenceOptions& options)
    : scene_(scene),
      options_(options),
      comm_(options.communicator),
      rank_(dealii::Utilities::MPI::this_mpi_process(comm_)),
      processes_(dealii::Utilities::MPI::n_mpi_processes(comm_)),
      pcout_(std::cout, options.print_timing && rank_ == 0),
      // Timed on each process alone (no collective call per phase: a process
      // with nothing to mesh must not hold the others up); the statistics over
      // processes are gathered at the end.
      timer_(MPI_COMM_SELF, pcout_, dealii::TimerOutput::never, dealii::TimerOutput::wall_times),
      fibres_(make_fibres(scene)),
      tolerance_(scene.overlap_tolerance()),
      detector_(fibres_, scene, candidate_margin(fibres_),
                options.line_contact == LineContact::continuous
                    ? LineQuadrature::gauss(continuous_cells(scene, options.refine))
                    : LineQuadrature::slices(scene.contact.slices)),
      grid_u_(fibres_.size(),
              std::vector<Eigen::Vector3d>(detector_.grid().size(), Eigen::Vector3d::Zero())),
      mu_(scene.contact.friction) {
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

// run: like deal.II's step-41, the candidates on the fibres under the scene's
// loads first; then mesh them, assemble and solve the contact problem, and
// detect again on the deformed fibres, until nothing new overlaps.
Result ReferenceSolver::run() {
  const auto start = std::chrono::steady_clock::now();
  deform_under_scene_loads();
  detect();
  const std::vector<std::string> ambiguous =
      ambiguous_side_warnings(contacts_, fibres_, scene_.walls);
  OuterEnd end = OuterEnd::candidates_changing;
  int outer = 1;
  for (; outer <= options_.max_outer_iterations; ++outer) {
    make_grid();
    setup_system();
    assemble_system();
    solve();
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
  // The last solve used the candidates before the final detection: mesh them
  // again.
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

// The candidates of the first outer iteration are those of the fibres under the
// scene's loads: a mesh of the fibres alone (nodes at supports, slices, loads
// and the crossings of the undeformed fibres), solved once. Without loads the
// fibres stay straight.
void ReferenceSolver::deform_under_scene_loads() {
  if (scene_.loads.empty()) return;
  make_grid();
  setup_system();
  deform();
}

// Candidates on the finite-element fibres as last deformed (the shared
// detection); a contact found again keeps its force, and a pushing contact
// stays a candidate.
void ReferenceSolver::detect() {
  std::vector<Contact> found = detector_.detect(grid_u_);
  carry_over(contacts_, found);
  contacts_ = std::move(found);
  if (mu_ > 0.0) origins_.set(contacts_);
}

// make_grid: this process's fibres, with nodes at every contact station and
// sample position, meshed by Gmsh and read by deal.II.
void ReferenceSolver::make_grid() {
  dealii::TimerOutput::Scope scope(timer_, "make_grid");
  collect_stations();
  model_.reset();
  // A process with more processes than fibres may own none: it then only takes
  // part in the sums.
  const bool owns = std::any_of(owned_.begin(), owned_.end(), [](char o) { return o != 0; });
  MeshOptions mesh = mesh_options();
  mesh.fibres = owned_;
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

// solve: the complementarity problem, exactly, starting from the last pushing
// set; with friction then Coulomb's law from the frictionless answer. An
// overlap at a point neither fibre can move (both pinned there) has no answer;
// a contact there that does not overlap is left out.
void ReferenceSolver::solve() {
  dealii::TimerOutput::Scope scope(timer_, "solve");
  const Eigen::Index n = d0_.size();
  if (trouble_.non_finite) {
    trouble_.why = "the finite-element solutions are not finite (a singular beam system?)";
    for (Contact& c : contacts_) c.force = 0.0;
    return;
  }
  std::vector<double> overlap(d0_.data(), d0_.data() + n), compliance(n);
  for (Eigen::Index k = 0; k < n; ++k) compliance[k] = W_.coeff(k, k);
  if (auto why = find_unresolvable_overlap(contacts_, overlap, compliance, tolerance_, fibres_,
                                           scene_.walls)) {
    trouble_.why = *why;
    for (Contact& c : contacts_) c.force = 0.0;
    return;
  }
  const double immovable = immovable_compliance(fibres_);
  std::vector<char> excluded(n, 0);
  for (Eigen::Index k = 0; k < n; ++k) excluded[k] = compliance[k] <= immovable ? 1 : 0;
  // Overlaps are decided far below the scene's tolerance, but not below the
  // round-off of the finite-element data (about 1e-14 of the largest overlap
  // under the loads): a line force is barely determined by the overlaps (a
  // force near a pinned end moves nothing), so a coarser threshold leaves a
  // fine continuous line contact with too few points pushing.
  threshold_ =
      std::max(1e-6 * tolerance_, 1e-13 * (d0_.size() > 0 ? d0_.cwiseAbs().maxCoeff() : 0.0));
  if (solve_frictionless(excluded) && mu_ > 0.0) solve_friction(excluded);
  if (options_.contact_problem) keep_contact_problem(excluded);
}

// The frictionless problem P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 by the active set,
// from the pushing set of the last outer iteration; every contact's force is
// its answer (zero when there is none).
bool ReferenceSolver::solve_frictionless(const std::vector<char>& excluded) {
  const Eigen::Index n = d0_.size();
  pushing_.resize(n, 0);
  const ActiveSetSolve solved = nonnegative_active_set(
      W_, d0_, threshold_, excluded, options_.max_active_set_iterations, P_, pushing_);
  active_set_iterations_ += solved.passes;
  if (solved.singular)
    trouble_.why =
        "the pushing contacts' compliance matrix is singular "
        "(contacts that constrain the "
        "same motion twice)";
  else if (!solved.solved)
    trouble_.why = "the active-set method did not finish in " +
                   std::to_string(options_.max_active_set_iterations) + " passes";
  for (Eigen::Index k = 0; k < n; ++k) contacts_[k].force = solved.solved ? P_[k] : 0.0;
  return solved.solved;
}

// solve_friction: Coulomb's law at every candidate, exactly
// (tresca_fixed_point.h), from the frictionless answer just found and the
// friction forces the candidates carried over.
void ReferenceSolver::solve_friction(const std::vector<char>& excluded) {
  FrictionalProblem& problem = friction_problem_;
  problem.excluded = excluded;
  const Eigen::Index n = d0_.size();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(problem.offset[n]);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const Eigen::Index o = problem.offset[k];
    r[o] = P_[k];
    if (c.tangents >= 1) r[o + 1] = c.tangent.dot(c.friction);
    if (c.tangents == 2) r[o + 2] = c.normal.cross(c.tangent).dot(c.friction);
  }
  TrescaOptions options;
  options.threshold = threshold_;
  options.tolerance = tolerance_;
  options.max_active_set_passes = options_.max_active_set_iterations;
  const TrescaSolve solved = tresca_fixed_point(problem, options, r);
  active_set_iterations_ += solved.active_set_passes;
  newton_steps_ += solved.newton_steps;
  tresca_updates_ += solved.updates;
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
    if (c.tangents == 2) c.friction += r[o + 2] * c.normal.cross(c.tangent);
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
    if (p.contacts[k].tangents == 2) p.reaction[o + 2] = c.normal.cross(c.tangent).dot(c.friction);
  }
}

// The step's contact problem as last solved, with the step's status, to
// options_.contact_problem.
void ReferenceSolver::hand_over_contact_problem(Status status) {
  if (!options_.contact_problem) return;
  if (exported_.offset.empty()) set_offsets(exported_);
  exported_.status = to_string(status);
  options_.contact_problem(exported_);
}

// update_active_set: candidates again on the deformed fibres. Places and
// normals are those of the undeformed fibres, so the answer stands unless a new
// candidate overlaps.
bool ReferenceSolver::update_active_set() {
  dealii::TimerOutput::Scope scope(timer_, "update_active_set");
  std::set<std::uint64_t> known;
  for (const Contact& c : contacts_) known.insert(c.key());
  std::map<std::uint64_t, char> was_pushing;
  for (std::size_t k = 0; k < contacts_.size(); ++k)
    was_pushing[contacts_[k].key()] = k < pushing_.size() ? pushing_[k] : 0;
  std::vector<Contact> solved = contacts_;
  deform();
  detect();
  std::vector<Eigen::Vector3d> ua, ub;
  displacements_at_contacts(ua, ub);
  bool unchanged = true;
  pushing_.assign(contacts_.size(), 0);
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const std::uint64_t key = contacts_[k].key();
    auto it = was_pushing.find(key);
    if (it != was_pushing.end()) pushing_[k] = it->second;
    if (known.count(key) == 0 &&
        detector_.geometry().overlap_along_normal(contacts_[k], ua[k], ub[k]) > threshold_)
      unchanged = false;
  }
  // Nothing new overlaps: the answer is the one just solved, on the candidates
  // it was solved with.
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

// The forces on this process's fibres: the contact forces that push, on both
// sides.
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

// deform: the finite-element fibres under the scene's loads and the current
// contact forces, and their displacements at the detector's grid (every process
// ends with every fibre's).
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

// The last finite-element solution at both sides of every contact (mm), from
// the process that owns each fibre.
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

// Every fibre's contact stations (sorted, each once) and each contact's
// stations on A and B. The influence matrices are dense per fibre and every
// process holds all of them: what would not fit in 4 GiB is refused here rather
// than failing in the middle of the assembly.
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
    g_offset_[f + 1] = g_offset_[f] + list.size() * list.size();
  }
  constexpr double kMaxInfluenceBytes = 4.0 * (1 << 30);
  const double bytes = 8.0 * static_cast<double>(g_offset_.back());
  if (bytes > kMaxInfluenceBytes) {
    std::size_t widest = 0;
    for (std::size_t f = 0; f < fibres_.size(); ++f)
      if (stations_[f].size() > stations_[widest].size()) widest = f;
    std::ostringstream out;
    out.precision(3);
    out << "the reference's dense influence matrices would take " << bytes / (1 << 30)
        << " GiB (fibre " << fibres_[widest].id << " alone has " << stations_[widest].size()
        << " contact stations), above its limit of 4 GiB: give the reference "
           "fewer slices "
        << "(fibrecheck fem --slices) or a coarser continuous line contact";
    throw InputError(scene_.source, "contact.slices", out.str());
  }
  station_a_.resize(contacts_.size());
  station_b_.resize(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    station_a_[k] = station(contacts_[k].a, contacts_[k].s_a);
    station_b_[k] =
        contacts_[k].kind == ContactKind::wall ? -1 : station(contacts_[k].b, contacts_[k].s_b);
  }
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

// assemble_system: the overlaps d0 under the scene's loads and the compliance
// matrix W (and with friction its tangential blocks), from finite-element
// solutions.
void ReferenceSolver::assemble_system() {
  dealii::TimerOutput::Scope scope(timer_, "assemble_system");
  const std::vector<double> G = loads_and_influence();
  const std::vector<std::vector<ContactSide>> sides = assemble_compliance(G);
  if (mu_ > 0.0) assemble_frictional_problem(G, sides);
}

// The displacements u0_ at every station under the scene's loads, and the
// influence matrices G_f (mm/N, the same in both bending planes; packed by
// g_offset_), which the function returns. The fibres do not interact through
// the beams, so one solve can carry a unit load on every fibre at once: solve i
// loads the i-th station of each fibre and gives the i-th column of every G_f.
// Each process fills in its own fibres; the sums give every process all of
// them, so that every process takes the same branch after a non-finite
// solution.
std::vector<double> ReferenceSolver::loads_and_influence() {
  u0_.assign(3 * offset_.back(), 0.0);
  std::vector<double> G(g_offset_.back(), 0.0);
  if (model_) {
    model_->run({}, true);
    for (std::size_t f = 0; f < fibres_.size(); ++f)
      if (owned_[f]) {
        for (std::size_t i = 0; i < stations_[f].size(); ++i) {
          const Eigen::Vector3d u = model_->displacement(static_cast<int>(f), stations_[f][i]);
          for (int d = 0; d < 3; ++d) u0_[3 * (offset_[f] + i) + d] = u[d];
        }
      }
    // Long assemblies (fine continuous line contact) report how far they are,
    // every 5 s.
    auto last = std::chrono::steady_clock::now();
    const auto report = [&](std::size_t done, std::size_t total) {
      if (!options_.progress || done == total ||
          std::chrono::steady_clock::now() - last < std::chrono::seconds(5))
        return;
      last = std::chrono::steady_clock::now();
      options_.progress("assemble_system: " + std::to_string(done) + " of " +
                        std::to_string(total) + " unit-load right-hand sides");
    };
    const std::vector<Eigen::MatrixXd> influence = model_->influence_matrices(stations_, report);
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      const std::size_t m = stations_[f].size();
      if (!owned_[f]) continue;
      for (std::size_t j = 0; j < m; ++j)
        for (std::size_t i = 0; i < m; ++i) G[g_offset_[f] + j * m + i] = influence[f](j, i);
    }
  }
  sum_over_processes(u0_, comm_);
  sum_over_processes(G, comm_);
  if (!std::all_of(u0_.begin(), u0_.end(), [](double x) { return std::isfinite(x); }) ||
      !std::all_of(G.begin(), G.end(), [](double x) { return std::isfinite(x); }))
    trouble_.non_finite = true;
  return G;
}

// The overlaps d0_ under the scene's loads and W_jk = Σ_f α_j α_k G_f(j, k)
// n_j⊥·n_k⊥ over the fibres both contacts act on, ⊥ the part across the fibre
// (mm/N). Returns each fibre's contact sides, from which the frictional blocks
// are assembled alike.
std::vector<std::vector<ReferenceSolver::ContactSide>> ReferenceSolver::assemble_compliance(
    const std::vector<double>& G) {
  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  d0_.resize(n);
  std::vector<std::vector<ContactSide>> sides(fibres_.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const bool wall = c.kind == ContactKind::wall;
    d0_[k] = detector_.geometry().overlap_along_normal(
        c, packed(u0_, c.a, station_a_[k]),
        wall ? Eigen::Vector3d::Zero().eval() : packed(u0_, c.b, station_b_[k]));
    sides[c.a].push_back({k, station_a_[k], wall ? 1.0 : -1.0, true});
    if (!wall) sides[c.b].push_back({k, station_b_[k], 1.0, false});
  }
  std::vector<Eigen::Triplet<double>> entries;
  std::size_t count = 0;
  for (const auto& list : sides) count += list.size() * list.size();
  entries.reserve(count);
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    const std::size_t m = stations_[f].size();
    const Eigen::Vector3d t = fibres_[f].t;
    for (const ContactSide& j : sides[f]) {
      const Eigen::Vector3d nj = contacts_[j.contact].normal;
      const Eigen::Vector3d nj_across = nj - nj.dot(t) * t;
      for (const ContactSide& k : sides[f]) {
        const Eigen::Vector3d nk = contacts_[k.contact].normal;
        entries.emplace_back(j.contact, k.contact,
                             j.alpha * k.alpha * G[g_offset_[f] + j.station * m + k.station] *
                                 nj_across.dot(nk - nk.dot(t) * t));
      }
    }
  }
  W_.resize(n, n);
  W_.setFromTriplets(entries.begin(),
                     entries.end());  // sums the two fibres' parts
  return sides;
}

// The direction φ along which component i of contact k's reaction acts on one
// of its sides (the force on that fibre per unit reaction): the normal −n on A
// and +n on B (+n on a walled fibre), a tangent +t on A and −t on B (the second
// tangent n × t).
Eigen::Vector3d ReferenceSolver::reaction_direction(Eigen::Index k, int i, bool on_a) const {
  const Contact& c = contacts_[k];
  if (i == 0) return (c.kind == ContactKind::wall || !on_a) ? c.normal : Eigen::Vector3d(-c.normal);
  const Eigen::Vector3d t = i == 1 ? c.tangent : Eigen::Vector3d(c.normal.cross(c.tangent));
  return on_a ? t : Eigen::Vector3d(-t);
}

// Friction: W with the tangential blocks, W_(j,a)(k,b) = Σ_f G_f(j, k)
// φ⊥_ja·φ⊥_kb, and q the overlaps d0 and the slips under the scene's loads
// alone (measured from the step's start).
void ReferenceSolver::assemble_frictional_problem(
    const std::vector<double>& G, const std::vector<std::vector<ContactSide>>& sides) {
  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  FrictionalProblem& problem = friction_problem_;
  problem.mu = mu_;
  problem.offset.assign(n + 1, 0);
  for (Eigen::Index k = 0; k < n; ++k)
    problem.offset[k + 1] = problem.offset[k] + 1 + contacts_[k].tangents;
  const Eigen::Index unknowns = problem.offset[n];
  problem.q.resize(unknowns);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const bool wall = c.kind == ContactKind::wall;
    const Eigen::Vector3d slip =
        c.relative(packed(u0_, c.a, station_a_[k]),
                   wall ? Eigen::Vector3d::Zero().eval() : packed(u0_, c.b, station_b_[k])) -
        c.origin;
    problem.q[problem.offset[k]] = d0_[k];
    for (int i = 1; i <= c.tangents; ++i)
      problem.q[problem.offset[k] + i] = reaction_direction(k, i, true).dot(slip);
  }
  std::size_t count = 0;
  for (const auto& list : sides) count += list.size() * list.size();
  std::vector<Eigen::Triplet<double>> frictional;
  frictional.reserve(4 * count);
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    const std::size_t m = stations_[f].size();
    const Eigen::Vector3d t = fibres_[f].t;
    auto across = [&](const Eigen::Vector3d& v) { return Eigen::Vector3d(v - v.dot(t) * t); };
    for (const ContactSide& j : sides[f])
      for (int a = 0; a <= contacts_[j.contact].tangents; ++a) {
        const Eigen::Vector3d pj = across(reaction_direction(j.contact, a, j.on_a));
        for (const ContactSide& k : sides[f]) {
          const double g = G[g_offset_[f] + j.station * m + k.station];
          for (int b = 0; b <= contacts_[k.contact].tangents; ++b)
            frictional.emplace_back(problem.offset[j.contact] + a, problem.offset[k.contact] + b,
                                    g * pj.dot(across(reaction_direction(k.contact, b, k.on_a))));
        }
      }
  }
  problem.W.resize(unknowns, unknowns);
  problem.W.setFromTriplets(frictional.begin(), frictional.end());
  problem.excluded.assign(n, 0);
}

// output_results: the beams solved once more under the final contact forces;
// from that solution the displacements and moments at the samples, each
// contact's overlap and slip, the contacts' and walls' forces, and the
// energies.
void ReferenceSolver::output_results(Result& r) {
  dealii::TimerOutput::Scope scope(timer_, "output_results");
  gather_forces();
  const FinalFields fields = final_fields();
  r.finite_elements.emplace();
  std::vector<Eigen::Vector3d> u_a, u_b;
  measure_contacts(fields.stations, r, u_a, u_b);
  const std::size_t samples = sample_s_.size();
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    FibreResult fr;
    fr.id = fibres_[f].id;
    for (std::size_t j = 0; j < samples; ++j) {
      const std::size_t at = f * samples + j;
      fr.displacement.emplace_back(fields.displacement[3 * at], fields.displacement[3 * at + 1],
                                   fields.displacement[3 * at + 2]);
      fr.moment.emplace_back(fields.moment[2 * at], fields.moment[2 * at + 1]);
    }
    r.fibres.push_back(std::move(fr));
  }
  r.contacts = contact_results(contacts_, fibres_, scene_.walls, force_on_a_, u_a, u_b, mu_);
  if (mu_ > 0.0) {
    r.friction = friction_figures(contacts_, mu_, FrictionModel::coulomb);
    r.friction->fixed_point_updates = tresca_updates_;
    end_state_ = SlipOrigins(contacts_, u_a, u_b, r);
  }
  r.walls = wall_results(contacts_, fibres_, scene_.walls);
  add_energies(r);
}

// The beams under the scene's loads and the final contact forces, and their
// displacements at every contact station and sample and their moments at the
// samples, summed over the processes. A non-finite number left here becomes a
// zero and the status `diverged` in solve_reference (replace_non_finite), as
// for the iterative solver.
ReferenceSolver::FinalFields ReferenceSolver::final_fields() {
  const std::size_t samples = sample_s_.size();
  FinalFields fields;
  fields.stations.assign(3 * offset_.back(), 0.0);
  fields.displacement.assign(3 * samples * fibres_.size(), 0.0);
  fields.moment.assign(2 * samples * fibres_.size(), 0.0);
  if (model_) {
    model_->run(nodal_forces(), true);
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      for (std::size_t i = 0; i < stations_[f].size(); ++i) {
        const Eigen::Vector3d x = model_->displacement(static_cast<int>(f), stations_[f][i]);
        for (int d = 0; d < 3; ++d) fields.stations[3 * (offset_[f] + i) + d] = x[d];
      }
      for (std::size_t j = 0; j < samples; ++j) {
        const Eigen::Vector3d x = model_->displacement(static_cast<int>(f), sample_s_[j]);
        for (int d = 0; d < 3; ++d) fields.displacement[3 * (f * samples + j) + d] = x[d];
        const Eigen::Vector2d M = model_->moment(static_cast<int>(f), sample_s_[j]);
        for (int d = 0; d < 2; ++d) fields.moment[2 * (f * samples + j) + d] = M[d];
      }
    }
    if (!options_.vtu.empty()) write_vtu();
  }
  sum_over_processes(fields.stations, comm_);
  sum_over_processes(fields.displacement, comm_);
  sum_over_processes(fields.moment, comm_);
  return fields;
}

// The beams' solution as a ParaView file: with several processes one piece per
// process, and a record that collects them (written by the first).
void ReferenceSolver::write_vtu() const {
  if (processes_ == 1) {
    model_->write_vtu(options_.vtu);
    return;
  }
  const std::filesystem::path path(options_.vtu);
  const auto piece = [&](unsigned int p) {
    return path.stem().string() + "." + std::to_string(p) + ".vtu";
  };
  std::vector<std::string> pieces;
  for (unsigned int p = 0; p < processes_ && p < fibres_.size(); ++p) pieces.push_back(piece(p));
  const std::string record =
      rank_ == 0 ? (path.parent_path() / (path.stem().string() + ".pvtu")).string() : "";
  model_->write_vtu((path.parent_path() / piece(rank_)).string(), record, pieces);
}

// Each contact's overlap (and with friction its slip) in the final state, from
// the displacements `u` at the stations; the sides' displacements go to `u_a`,
// `u_b`. Sets the largest overlap, the largest gap that carries a force and the
// complementarity residual max |P·d|.
void ReferenceSolver::measure_contacts(const std::vector<double>& u, Result& r,
                                       std::vector<Eigen::Vector3d>& u_a,
                                       std::vector<Eigen::Vector3d>& u_b) {
  FiniteElementFigures& figures = *r.finite_elements;
  u_a.assign(contacts_.size(), Eigen::Vector3d::Zero());
  u_b.assign(contacts_.size(), Eigen::Vector3d::Zero());
  r.max_overlap = contacts_.empty() ? 0.0 : -INFINITY;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    Contact& c = contacts_[k];
    u_a[k] = packed(u, c.a, station_a_[k]);
    if (c.kind != ContactKind::wall) u_b[k] = packed(u, c.b, station_b_[k]);
    c.overlap = detector_.geometry().overlap_along_normal(c, u_a[k], u_b[k]);
    if (mu_ > 0.0) c.slip = c.tangential(c.relative(u_a[k], u_b[k]) - c.origin);
    r.max_overlap = std::max(r.max_overlap, c.overlap);
    if (c.force > 0.0) r.gap_force_residual = std::max(r.gap_force_residual, -c.overlap);
    figures.complementarity_residual =
        std::max(figures.complementarity_residual, std::fabs(c.force * c.overlap));
  }
}

// The energies and the dropped axial load, from this process's elements,
// summed: Eq. 4.34 by the trapezium rule on the finite-element moments at the
// slice spacing (as the iterative solver), ½ΣP·v from the finite-element
// displacements, and ∫M²/2EI over the elements (N·mm; N).
void ReferenceSolver::add_energies(Result& r) {
  std::vector<double> sums(4, 0.0);
  if (model_) {
    const int n = scene_.contact.slices;
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      double sum = 0.0;
      for (int j = 0; j <= n; ++j) {
        const double weight = (j == 0 || j == n) ? 0.5 : 1.0;
        sum +=
            weight * model_->moment(static_cast<int>(f), static_cast<double>(j) / n).squaredNorm();
      }
      sums[0] += sum * (fibres_[f].length / n) / (2.0 * fibres_[f].EI);
    }
    sums[1] = model_->load_work();
    sums[2] = model_->strain_energy();
    sums[3] = model_->axial_load_dropped();
  }
  sum_over_processes(sums, comm_);
  r.strain_energy = sums[0];
  r.strain_energy_exact = sums[1];
  r.finite_elements->strain_energy_elements = sums[2];
  r.axial_load_dropped = sums[3];
  r.candidates = static_cast<long>(contacts_.size());
}

// describe_run: what the result says besides the solution — warnings, outer
// iterations, the finite elements' figures, the stages, the wall time and the
// run's cost in its message.
void ReferenceSolver::describe_run(Result& r, const std::vector<std::string>& ambiguous, int outer,
                                   std::chrono::steady_clock::time_point start) {
  add_reference_warnings(r, ambiguous, fibres_, scene_, tolerance_);
  r.iterations = outer;
  r.finite_elements->active_set_iterations = active_set_iterations_;
  r.finite_elements->unknowns = static_cast<long>(
      dealii::Utilities::MPI::sum(model_ ? model_->unknowns() : std::size_t(0), comm_));
  r.stages = reference_stages(detector_, options_, mu_ > 0.0, processes_);
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ReferenceCounts counts;
  counts.unknowns = r.finite_elements->unknowns;
  counts.active_set_passes = active_set_iterations_;
  counts.friction = mu_ > 0.0;
  counts.tresca_updates = tresca_updates_;
  counts.newton_steps = newton_steps_;
  counts.cg = options_.beam_solver == BeamSolver::cg_amg;
  counts.cg_iterations = model_ ? model_->cg_iterations() : 0;
  if (!r.message.empty()) r.message += "; ";
  r.message += reference_summary(counts, timer_);
  if (options_.print_timing) {
    if (processes_ == 1)
      timer_.print_summary();
    else
      timer_.print_wall_time_statistics(comm_);
  }
}

namespace {

/// One load step by its own ReferenceSolver, its slip measured from `from`;
/// `to` receives where the next step's slip is measured from.
Result solve_step(const Scene& step, const ReferenceOptions& options, const SlipOrigins& from,
                  SlipOrigins& to) {
  ReferenceSolver solver(step, options);
  solver.start_from(from);
  Result result = solver.run();
  to = solver.end_state();
  return result;
}

}  // namespace

// A load path step by step. Without friction each step's answer is that of its
// own geometry and loads, so each is solved afresh, exactly; with friction each
// step starts where the last one ended (its slip is measured from there). The
// continuous line contact, when it is to be refined until its line force
// settles, solves every refinement of a step from the same start.
Result solve_reference(const Scene& scene, const ReferenceOptions& options) {
  share_cores_with_blas(options.communicator);
  SlipOrigins origins;
  Result r = solve_load_path(scene, [&](const Scene& step, const Result*) {
    if (!options.refine_until_converged || options.line_contact != LineContact::continuous)
      return solve_step(step, options, origins, origins);
    const SlipOrigins start = origins;
    return solve_refined_until_settled(step, options, [&](const ReferenceOptions& once) {
      return solve_step(step, once, start, origins);
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
