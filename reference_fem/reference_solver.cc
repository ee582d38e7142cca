#include "reference_solver.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>

#include "ambiguous_sides.h"
#include "beam_model.h"
#include "blas_threads.h"
#include "bounded_active_set.h"
#include "carry_over.h"
#include "contact_detection.h"
#include "contact_results.h"
#include "fibre.h"
#include "fibre_mesh.h"
#include "frictional_contact.h"
#include "input_error.h"
#include "load_path_solve.h"
#include "slip_origins.h"
#include "subset_solve.h"
#include "unresolvable_overlap.h"
#include "validity.h"

namespace fibrecheck {

namespace {

/// The contact problem P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 is the quadratic programme
/// min ½PᵀWP − Pᵀd0 over P ≥ 0, solved exactly by an active-set method in the manner of
/// Lawson–Hanson's non-negative least squares: add the contacts that overlap most (by more than
/// `tolerance`) to the set of pushing contacts, solve W_SS·P_S = d0_S, step back to feasibility
/// when a force would turn negative (dropping the contact that blocks), and repeat. A pass that
/// adds one contact lowers the objective strictly, so no set comes back and the method ends in a
/// finite number of passes (the plain primal–dual active set cycles on a dense W).
///  - Passes add blocks of the most overlapping contacts (at most max(8, |set|)); when a block
///    gains nothing or makes the set singular (two walls in one plane), the next pass adds one.
///  - A single contact that gains nothing (round-off decides it) is set aside until P changes.
///  - Contacts marked in `excluded` (nothing can move them) are never added.
/// `pushing` holds a first guess of the set (the last outer iteration's) on entry and the final
/// set on return. Returns false on a singular single addition (`singular` set) or when
/// `max_iterations` passes were not enough.
bool active_set_solve(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& d0,
                      double tolerance, const std::vector<char>& excluded, int max_iterations,
                      Eigen::VectorXd& P, std::vector<char>& pushing, int& iterations,
                      bool& singular) {
  const Eigen::Index n = d0.size();
  P = Eigen::VectorXd::Zero(n);
  pushing.resize(n, 0);
  iterations = 0;
  singular = false;
  if (n == 0) return true;
  for (Eigen::Index k = 0; k < n; ++k)
    if (excluded[k]) pushing[k] = 0;
  auto solve_on_set = [&](Eigen::VectorXd& z) {
    std::vector<Eigen::Index> index;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k]) index.push_back(k);
    z = Eigen::VectorXd::Zero(n);
    const Eigen::Index m = static_cast<Eigen::Index>(index.size());
    if (m == 0) return true;
    Eigen::VectorXd ds(m), zs;
    for (Eigen::Index i = 0; i < m; ++i) ds[i] = d0[index[i]];
    if (!solve_on_subset(W, index, ds, zs)) return false;
    for (Eigen::Index i = 0; i < m; ++i) z[index[i]] = zs[i];
    return true;
  };
  Eigen::VectorXd z;
  // Warm start: the guessed set, less the contacts that would pull, until all push.
  for (;;) {
    if (!solve_on_set(z)) {
      std::fill(pushing.begin(), pushing.end(), 0);  // start afresh instead
      z.setZero();
      break;
    }
    bool pulled = false;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k] && z[k] <= 0.0) pushing[k] = 0, pulled = true;
    if (!pulled) break;
  }
  P = z;
  bool one_at_a_time = false;
  std::vector<char> set_aside(n, 0);
  // W·P over the pushing contacts only: P is zero elsewhere, and few of the candidates push.
  auto W_times = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
    for (Eigen::Index k = 0; k < n; ++k)
      if (x[k] != 0.0)
        for (Eigen::SparseMatrix<double>::InnerIterator it(W, k); it; ++it)
          y[it.row()] += x[k] * it.value();
    return y;
  };
  auto objective = [&](const Eigen::VectorXd& x) { return 0.5 * x.dot(W_times(x)) - x.dot(d0); };
  for (iterations = 1; iterations <= max_iterations; ++iterations) {
    const Eigen::VectorXd d = d0 - W_times(P);
    std::vector<Eigen::Index> overlapping;
    std::size_t set_size = 0;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!pushing[k] && !excluded[k] && !set_aside[k] && d[k] > tolerance)
        overlapping.push_back(k);
      set_size += pushing[k] ? 1 : 0;
    }
    if (overlapping.empty()) return true;
    // The most overlapping first, at most as many as already push (at least 8): a big block of
    // contacts that mostly will not push costs one dense solve per contact dropped again.
    const std::size_t add =
        one_at_a_time ? 1 : std::min(overlapping.size(), std::max<std::size_t>(8, set_size));
    std::partial_sort(overlapping.begin(), overlapping.begin() + static_cast<long>(add),
                      overlapping.end(),
                      [&](Eigen::Index x, Eigen::Index y) { return d[x] > d[y]; });
    for (std::size_t i = 0; i < add; ++i) pushing[overlapping[i]] = 1;
    // ½PᵀWP − Pᵀd0 with W·P = d0 − d, from the product just made.
    const double objective_before = -0.5 * P.dot(d0 + d);
    if (!solve_on_set(z)) {
      for (std::size_t i = 0; i < add; ++i) pushing[overlapping[i]] = 0;
      if (add > 1) {
        // Contacts added together may constrain the same motion (two walls in one plane): the
        // set is singular, though the problem is not. Take them one at a time instead.
        one_at_a_time = true;
        continue;
      }
      singular = true;
      return false;
    }
    for (int inner = 0; inner < n + 1; ++inner) {
      double alpha = 1.0;
      Eigen::Index blocking = -1;
      for (Eigen::Index k = 0; k < n; ++k)
        if (pushing[k] && z[k] <= 0.0) {
          const double a = P[k] / (P[k] - z[k]);
          if (blocking < 0 || a < alpha) alpha = a, blocking = k;
        }
      if (blocking < 0) break;
      P += alpha * (z - P);
      P[blocking] = 0.0;  // the contact that blocks leaves, whatever round-off left of it
      for (Eigen::Index k = 0; k < n; ++k)
        if (pushing[k] && P[k] <= 0.0) pushing[k] = 0, P[k] = 0.0;
      if (!solve_on_set(z)) {
        singular = true;
        return false;
      }
    }
    P = z.cwiseMax(0.0);
    const bool progress = objective(P) < objective_before - 1e-14 * std::fabs(objective_before);
    if (progress) {
      std::fill(set_aside.begin(), set_aside.end(), 0);
    } else if (one_at_a_time) {
      set_aside[overlapping[0]] = 1;
    }
    one_at_a_time = !progress;
  }
  return false;
}

void sum_over_processes(std::vector<double>& values, MPI_Comm comm) {
  if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1) return;
  // In pieces: MPI counts are ints.
  constexpr std::size_t piece = std::size_t(1) << 28;
  for (std::size_t start = 0; start < values.size(); start += piece)
    MPI_Allreduce(MPI_IN_PLACE, values.data() + start,
                  static_cast<int>(std::min(piece, values.size() - start)), MPI_DOUBLE, MPI_SUM,
                  comm);
}

/// The reference solver's state; like deal.II's tutorial programs, `run()` calls the phases.
class ReferenceSolver {
 public:
  ReferenceSolver(const Scene& scene, const ReferenceOptions& options);
  ~ReferenceSolver();
  Result run();
  /// The mesh of the first outer iteration: the candidates on the fibres under the scene's loads.
  MeshOptions first_mesh_options();
  /// Friction: where this step's slip is measured from (the previous step's end).
  void start_from(SlipOrigins origins) { origins_ = std::move(origins); }
  /// After `run`: where the next step's slip is measured from.
  const SlipOrigins& end_state() const { return end_state_; }

 private:
  void collect_stations();
  MeshOptions mesh_options() const;
  void make_grid();
  void setup_system();
  void assemble_system();
  void solve();
  void solve_friction(const std::vector<char>& excluded);
  /// The problem just solved, with its answer, for options_.contact_problem.
  void keep_contact_problem(const std::vector<char>& excluded);
  bool update_active_set();
  void output_results(Result& r);

  void deform_under_scene_loads();
  void deform();
  void detect();
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
  /// Each fibre's finite-element displacements (mm) at the detector's grid, for detection.
  std::vector<std::vector<Eigen::Vector3d>> grid_u_;
  std::vector<double> sample_s_;

  std::vector<Contact> contacts_;
  std::vector<Eigen::Vector3d> force_on_a_;
  /// Per fibre, the sorted fractions where contacts act on it; per contact, its stations on A, B.
  std::vector<std::vector<double>> stations_;
  std::vector<int> station_a_, station_b_;
  std::vector<std::size_t> offset_, g_offset_;  ///< per fibre, into packed station data and G
  std::string mesh_file_;
  std::unique_ptr<BeamModel> model_;
  std::vector<double> u0_;  ///< displacements at every station under the scene's loads
  Eigen::VectorXd d0_, P_;
  /// W is sparse: two contacts interact only through a fibre they share.
  Eigen::SparseMatrix<double> W_;
  std::vector<char> pushing_;
  long active_set_iterations_ = 0;
  std::string trouble_;              ///< why the problem could not be solved, if it could not
  bool non_finite_ = false;          ///< the finite-element solutions were not finite
  bool friction_unsettled_ = false;  ///< the frictional problem's Newton method did not settle

  double mu_;
  SlipOrigins origins_, end_state_;
  /// The frictional problem of the candidates (μ > 0): W with the tangential blocks and q.
  FrictionalProblem friction_problem_;
  Eigen::VectorXd reaction_;  ///< its last answer (warm start of the next outer iteration)
  ContactProblem exported_;   ///< the problem last solved (only with options_.contact_problem)
  long newton_steps_ = 0;
  long tresca_updates_ = 0;
  static constexpr int kMaxTrescaUpdates = 500;
};

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
// again keeps its force, and a pushing contact stays a candidate.
void ReferenceSolver::detect() {
  std::vector<Contact> found = detector_.detect(grid_u_);
  carry_over(contacts_, found);
  contacts_ = std::move(found);
  if (mu_ > 0.0) origins_.set(contacts_);
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
    g_offset_[f + 1] = g_offset_[f] + list.size() * list.size();
  }
  // The influence matrices are dense per fibre and every process holds all of them: refuse what
  // would not fit rather than fail in the middle of the assembly.
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
        << " contact stations), above its limit of 4 GiB: give the reference fewer slices "
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

// make_grid: this process's fibres, with nodes at every contact station and sample position,
// meshed by Gmsh and read by deal.II.
void ReferenceSolver::make_grid() {
  dealii::TimerOutput::Scope scope(timer_, "make_grid");
  collect_stations();
  model_.reset();
  // A process with more processes than fibres may own none: it then only takes part in the sums.
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

// assemble_system: the overlaps d0 under the scene's loads and the compliance matrix W, from
// finite-element solutions. The fibres do not interact through the beams, so one solve can carry a
// unit load on every fibre at once: solve i loads the i-th station of each fibre and gives the
// i-th column of every fibre's influence matrix G_f (mm/N, the same in both bending planes).
// Then W_jk = Σ_f α_j α_k G_f(j, k) n_j⊥·n_k⊥ over the fibres both contacts act on, α = ∓1 on
// fibre A and B (+1 for a wall) and ⊥ the part across the fibre.
void ReferenceSolver::assemble_system() {
  dealii::TimerOutput::Scope scope(timer_, "assemble_system");
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
    // Long assemblies (fine continuous line contact) report how far they are, every 5 s.
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
  // The same numbers on every process after the sums, so every process takes the same branch.
  if (!std::all_of(u0_.begin(), u0_.end(), [](double x) { return std::isfinite(x); }) ||
      !std::all_of(G.begin(), G.end(), [](double x) { return std::isfinite(x); }))
    non_finite_ = true;

  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  d0_.resize(n);
  struct Side {
    Eigen::Index contact;
    int station;
    double alpha;
    bool on_a;
  };
  std::vector<std::vector<Side>> sides(fibres_.size());
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
    for (const Side& j : sides[f]) {
      const Eigen::Vector3d nj = contacts_[j.contact].normal;
      const Eigen::Vector3d nj_across = nj - nj.dot(t) * t;
      for (const Side& k : sides[f]) {
        const Eigen::Vector3d nk = contacts_[k.contact].normal;
        entries.emplace_back(j.contact, k.contact,
                             j.alpha * k.alpha * G[g_offset_[f] + j.station * m + k.station] *
                                 nj_across.dot(nk - nk.dot(t) * t));
      }
    }
  }
  W_.resize(n, n);
  W_.setFromTriplets(entries.begin(), entries.end());  // sums the two fibres' parts
  if (!(mu_ > 0.0)) return;

  // Friction: W with the tangential blocks. Component i of contact k acts on a side of it along
  // φ (force on that fibre per unit reaction): the normal −n on A and +n on B (+n on a walled
  // fibre), a tangent +t on A and −t on B; then W_(j,a)(k,b) = Σ_f G_f(j, k) φ⊥_ja·φ⊥_kb, and q
  // holds the overlaps d0 and the slips under the scene's loads alone.
  FrictionalProblem& problem = friction_problem_;
  problem.mu = mu_;
  problem.offset.assign(n + 1, 0);
  for (Eigen::Index k = 0; k < n; ++k)
    problem.offset[k + 1] = problem.offset[k] + 1 + contacts_[k].tangents;
  const Eigen::Index unknowns = problem.offset[n];
  auto direction = [&](Eigen::Index k, int i, bool on_a) -> Eigen::Vector3d {
    const Contact& c = contacts_[k];
    if (i == 0)
      return (c.kind == ContactKind::wall || !on_a) ? c.normal : Eigen::Vector3d(-c.normal);
    const Eigen::Vector3d t = i == 1 ? c.tangent : Eigen::Vector3d(c.normal.cross(c.tangent));
    return on_a ? t : Eigen::Vector3d(-t);
  };
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
      problem.q[problem.offset[k] + i] = direction(k, i, true).dot(slip);
  }
  std::vector<Eigen::Triplet<double>> frictional;
  frictional.reserve(4 * count);
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    const std::size_t m = stations_[f].size();
    const Eigen::Vector3d t = fibres_[f].t;
    auto across = [&](const Eigen::Vector3d& v) { return Eigen::Vector3d(v - v.dot(t) * t); };
    for (const Side& j : sides[f])
      for (int a = 0; a <= contacts_[j.contact].tangents; ++a) {
        const Eigen::Vector3d pj = across(direction(j.contact, a, j.on_a));
        for (const Side& k : sides[f]) {
          const double g = G[g_offset_[f] + j.station * m + k.station];
          for (int b = 0; b <= contacts_[k.contact].tangents; ++b)
            frictional.emplace_back(problem.offset[j.contact] + a, problem.offset[k.contact] + b,
                                    g * pj.dot(across(direction(k.contact, b, k.on_a))));
        }
      }
  }
  problem.W.resize(unknowns, unknowns);
  problem.W.setFromTriplets(frictional.begin(), frictional.end());
  problem.excluded.assign(n, 0);
}

// solve: the complementarity problem, exactly, starting from the last pushing set.
void ReferenceSolver::solve() {
  dealii::TimerOutput::Scope scope(timer_, "solve");
  const Eigen::Index n = d0_.size();
  if (non_finite_) {
    trouble_ = "the finite-element solutions are not finite (a singular beam system?)";
    for (Contact& c : contacts_) c.force = 0.0;
    return;
  }
  // An overlap at a point neither fibre can move (both pinned there) has no answer; a contact
  // there that does not overlap is left out of the problem.
  std::vector<double> overlap(d0_.data(), d0_.data() + n), compliance(n);
  for (Eigen::Index k = 0; k < n; ++k) compliance[k] = W_.coeff(k, k);
  if (auto why = find_unresolvable_overlap(contacts_, overlap, compliance, tolerance_, fibres_,
                                           scene_.walls)) {
    trouble_ = *why;
    for (Contact& c : contacts_) c.force = 0.0;
    return;
  }
  const double immovable = immovable_compliance(fibres_);
  std::vector<char> excluded(n, 0);
  for (Eigen::Index k = 0; k < n; ++k) excluded[k] = compliance[k] <= immovable ? 1 : 0;
  // Overlaps are decided far below the scene's tolerance, but not below the round-off of the
  // finite-element data (about 1e-14 of the largest overlap under the loads, with MUMPS's
  // iterative refinement). A coarser threshold ruins a fine continuous line contact: a line force
  // is barely determined by the overlaps (a force near a pinned end moves nothing), so the
  // active set would end with only every other Gauss point pushing and the line force 3e-3 low.
  threshold_ =
      std::max(1e-6 * tolerance_, 1e-13 * (d0_.size() > 0 ? d0_.cwiseAbs().maxCoeff() : 0.0));
  pushing_.resize(n, 0);
  int iterations = 0;
  bool singular = false;
  const bool solved =
      active_set_solve(W_, d0_, threshold_, excluded, options_.max_active_set_iterations, P_,
                       pushing_, iterations, singular);
  active_set_iterations_ += iterations;
  if (singular)
    trouble_ =
        "the pushing contacts' compliance matrix is singular (contacts that constrain the "
        "same motion twice)";
  else if (!solved)
    trouble_ = "the active-set method did not finish in " +
               std::to_string(options_.max_active_set_iterations) + " passes";
  for (Eigen::Index k = 0; k < n; ++k) contacts_[k].force = solved ? P_[k] : 0.0;
  if (solved && !singular && mu_ > 0.0) solve_friction(excluded);
  if (options_.contact_problem) keep_contact_problem(excluded);
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

// solve_friction: Coulomb's law at every candidate, exactly (semismooth Newton on its natural
// map, frictional_contact.h), from the frictionless answer just found and the friction forces the
// candidates carried over.
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
  // A Tresca fixed point: the disk radii fixed at μ times the normal forces, the convex problem
  // solved exactly, the radii updated, until they produce the normal forces they assumed (to the
  // slip they could still cause, W_tt·Δg, below the threshold). A Newton method on Coulomb's law
  // itself cycled between sticking and slipping sets on compacted tows.
  problem.bounds.resize(n);
  for (Eigen::Index k = 0; k < n; ++k)
    problem.bounds[k] = mu_ * std::max(r[problem.offset[k]], 0.0);
  // The radii settle to the round-off of the normal forces (W's condition times machine epsilon),
  // far below the slips the loads cause, or to 1e-3 of the scene's tolerance t_d (the fixed point
  // converges linearly, slowly where it must be relaxed): a thousand times tighter than the
  // iterative solver's stopping criterion.
  double slip_scale = 0.0;
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index i = problem.offset[k] + 1; i < problem.offset[k + 1]; ++i)
      slip_scale = std::max(slip_scale, std::fabs(problem.q[i]));
  const double settled = std::max({threshold_, 1e-9 * slip_scale, 1e-3 * tolerance_});
  bool one_tangent = true;
  for (const Contact& c : contacts_) one_tangent &= c.tangents <= 1;
  // Each contact's tangential compliance (the slip per unit of friction), and for one tangent
  // whether anything moves along it: fixed for the whole fixed point.
  std::vector<double> tangential_compliance(n, 0.0);
  std::vector<char> movable(n, 0);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index o = problem.offset[k];
    for (Eigen::Index i = o + 1; i < problem.offset[k + 1]; ++i)
      tangential_compliance[k] = std::max(tangential_compliance[k], problem.W.coeff(i, i));
    movable[k] = !excluded[k] && tangential_compliance[k] > 1e-12 * problem.W.coeff(o, o);
  }
  FrictionalSolve solved;
  double change = INFINITY, last_change = INFINITY, relaxation = 1.0;
  int falling = 0;
  int updates = 0;
  for (updates = 1; updates <= kMaxTrescaUpdates; ++updates) {
    if (one_tangent) {
      // Slices and walls only: the Tresca problem is a box-constrained QP, solved exactly by the
      // bounded active set (a Newton method stalled on compacted tows, see frictional_contact.h).
      Eigen::VectorXd lo = Eigen::VectorXd::Zero(r.size());
      Eigen::VectorXd hi = Eigen::VectorXd::Constant(r.size(), INFINITY);
      for (Eigen::Index k = 0; k < n; ++k) {
        const Eigen::Index o = problem.offset[k];
        if (excluded[k]) hi[o] = 0.0;
        for (Eigen::Index i = o + 1; i < problem.offset[k + 1]; ++i) {
          lo[i] = movable[k] ? -problem.bounds[k] : 0.0;
          hi[i] = movable[k] ? problem.bounds[k] : 0.0;
        }
      }
      const BoundedSolve box = bounded_active_set(problem.W, problem.q, lo, hi, threshold_,
                                                  options_.max_active_set_iterations, r);
      active_set_iterations_ += box.passes;
      solved.settled = box.solved;
      solved.newton_steps = 0;
      solved.residual = box.solved ? 0.0 : INFINITY;
    } else {
      solved = solve_frictional(problem, threshold_, 100, r);
      newton_steps_ += solved.newton_steps;
    }
    if (!solved.settled) break;
    // Coulomb's law for this answer: a slipping contact's radius must be μP, a sticking one's
    // friction within μP — each violation times the contact's tangential compliance, the slip it
    // stands for. (A sticking contact's radius may differ from μP without harm.)
    change = 0.0;
    for (Eigen::Index k = 0; k < n; ++k) {
      const Eigen::Index o = problem.offset[k];
      const double g = mu_ * std::max(r[o], 0.0);
      const Eigen::Index t = problem.offset[k + 1] - o - 1;
      const double size = r.segment(o + 1, t).norm();
      const double compliance = tangential_compliance[k];
      // A zero radius lets the contact slip freely: its radius must become μP too.
      const bool slipping = !(problem.bounds[k] > 0.0) || size >= (1.0 - 1e-9) * problem.bounds[k];
      change =
          std::max(change, (slipping ? std::fabs(g - problem.bounds[k]) : std::max(0.0, size - g)) *
                               compliance);
      // A contact that slipped on its old circle slips on the new one.
      if (slipping && size > 0.0) r.segment(o + 1, t) *= g / size;
      // Relaxed when the violation stops falling: the plain map g ← μP settles into cycles on
      // compacted tows (a radius whose own normal force falls faster than it grows).
      problem.bounds[k] += relaxation * (g - problem.bounds[k]);
    }
    // Halved when the violation grows, grown again while it falls steadily.
    if (change > last_change)
      relaxation = std::max(relaxation * 0.5, 1.0 / 64.0), falling = 0;
    else if (++falling >= 3)
      relaxation = std::min(relaxation * 1.5, 1.0), falling = 0;
    last_change = change;
    if (change <= settled) break;
  }
  tresca_updates_ += std::min(updates, kMaxTrescaUpdates);
  if (!solved.settled || change > settled) {
    std::ostringstream out;
    out.precision(3);
    if (!solved.settled && one_tangent)
      out << "the frictional contact problem's Tresca problem was not solved in "
          << options_.max_active_set_iterations << " active-set passes";
    else if (!solved.settled)
      out << "the frictional contact problem did not settle: after " << solved.newton_steps
          << " Newton steps on its Tresca problem Coulomb's law is still violated by "
          << solved.residual << " mm";
    else
      out << "the Tresca fixed point of the frictional contact problem did not settle: after "
          << kMaxTrescaUpdates << " updates the disk radii still move the slips by " << change
          << " mm";
    out << " (mu = " << mu_ << "; the solution is unique only for small mu)";
    trouble_ = out.str();
    friction_unsettled_ = true;
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

// update_active_set: candidates again on the deformed fibres. Places and normals are those of the
// undeformed fibres, so the answer stands unless a new candidate overlaps.
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
  // Nothing new overlaps: the answer is the one just solved, on the candidates it was solved with.
  if (unchanged) contacts_ = std::move(solved);
  return unchanged;
}

// output_results: the final state from the finite elements.
void ReferenceSolver::output_results(Result& r) {
  dealii::TimerOutput::Scope scope(timer_, "output_results");
  gather_forces();
  const std::vector<NodalForce> forces = nodal_forces();
  const std::size_t samples = sample_s_.size();
  std::vector<double> u(3 * offset_.back(), 0.0), field(3 * samples * fibres_.size(), 0.0);
  std::vector<double> moments(2 * samples * fibres_.size(), 0.0);
  if (model_) {
    model_->run(forces, true);
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      for (std::size_t i = 0; i < stations_[f].size(); ++i) {
        const Eigen::Vector3d x = model_->displacement(static_cast<int>(f), stations_[f][i]);
        for (int d = 0; d < 3; ++d) u[3 * (offset_[f] + i) + d] = x[d];
      }
      for (std::size_t j = 0; j < samples; ++j) {
        const Eigen::Vector3d x = model_->displacement(static_cast<int>(f), sample_s_[j]);
        for (int d = 0; d < 3; ++d) field[3 * (f * samples + j) + d] = x[d];
        const Eigen::Vector2d M = model_->moment(static_cast<int>(f), sample_s_[j]);
        for (int d = 0; d < 2; ++d) moments[2 * (f * samples + j) + d] = M[d];
      }
    }
    if (!options_.vtu.empty()) {
      if (processes_ == 1) {
        model_->write_vtu(options_.vtu);
      } else {
        // One piece per process, and a record that collects them (written by the first).
        const std::filesystem::path path(options_.vtu);
        const auto piece = [&](unsigned int p) {
          return path.stem().string() + "." + std::to_string(p) + ".vtu";
        };
        std::vector<std::string> pieces;
        for (unsigned int p = 0; p < processes_ && p < fibres_.size(); ++p)
          pieces.push_back(piece(p));
        const std::string record =
            rank_ == 0 ? (path.parent_path() / (path.stem().string() + ".pvtu")).string() : "";
        model_->write_vtu((path.parent_path() / piece(rank_)).string(), record, pieces);
      }
    }
  }
  sum_over_processes(u, comm_);
  sum_over_processes(field, comm_);
  sum_over_processes(moments, comm_);
  // A non-finite number left here becomes a zero and the status `diverged` in solve_reference
  // (replace_non_finite), as for the iterative solver.

  FiniteElementFigures& figures = r.finite_elements.emplace();
  std::vector<Eigen::Vector3d> u_a(contacts_.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> u_b(contacts_.size(), Eigen::Vector3d::Zero());
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
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    FibreResult fr;
    fr.id = fibres_[f].id;
    for (std::size_t j = 0; j < samples; ++j) {
      fr.displacement.emplace_back(field[3 * (f * samples + j)], field[3 * (f * samples + j) + 1],
                                   field[3 * (f * samples + j) + 2]);
      fr.moment.emplace_back(moments[2 * (f * samples + j)], moments[2 * (f * samples + j) + 1]);
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
  // The energies and the dropped axial load, from this process's elements, summed: Eq. 4.34 by
  // the trapezium rule on the FE moments at the slice spacing (as the iterative solver), ½ΣP·v
  // from the FE displacements, and ∫M²/2EI over the elements.
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
  figures.strain_energy_elements = sums[2];
  r.axial_load_dropped = sums[3];
  r.candidates = static_cast<long>(contacts_.size());
}

Result ReferenceSolver::run() {
  const auto start = std::chrono::steady_clock::now();
  Result r;
  r.scene = scene_.name;
  r.solver = "fem";
  r.rule = "active_set";
  r.status = Status::max_iterations;
  r.criterion = Criterion::max_iterations;
  deform_under_scene_loads();
  detect();
  const std::vector<std::string> ambiguous =
      ambiguous_side_warnings(contacts_, fibres_, scene_.walls);
  int outer = 0;
  for (outer = 1; outer <= options_.max_outer_iterations; ++outer) {
    make_grid();
    setup_system();
    assemble_system();
    solve();
    if (!trouble_.empty()) {
      r.status = non_finite_           ? Status::diverged
                 : friction_unsettled_ ? Status::max_iterations
                                       : Status::unresolvable;
      r.criterion = non_finite_           ? Criterion::non_finite
                    : friction_unsettled_ ? Criterion::max_iterations
                                          : Criterion::unresolvable;
      r.message = trouble_;
      break;
    }
    const bool unchanged = update_active_set();
    if (options_.progress) {
      std::size_t active = 0;
      for (const Contact& c : contacts_) active += c.force > 0.0 ? 1 : 0;
      options_.progress("outer iteration " + std::to_string(outer) + ": " +
                        std::to_string(d0_.size()) + " candidates, " + std::to_string(active) +
                        " pushing, " + std::to_string(active_set_iterations_) +
                        " active-set passes so far");
    }
    if (unchanged) {
      r.status = Status::converged;
      r.criterion = Criterion::active_set;
      break;
    }
  }
  if (r.status == Status::max_iterations && !friction_unsettled_) {
    r.message = "the candidates still changed after " +
                std::to_string(options_.max_outer_iterations) + " outer iterations";
    // The last solve used the candidates before the final detection: mesh them again.
    make_grid();
    setup_system();
  }
  output_results(r);
  if (options_.contact_problem) {
    if (exported_.offset.empty()) set_offsets(exported_);
    exported_.status = to_string(r.status);
    options_.contact_problem(exported_);
  }
  r.warnings.insert(r.warnings.begin(), ambiguous.begin(), ambiguous.end());
  assess_validity(r, fibres_);
  r.iterations = std::min(outer, options_.max_outer_iterations);
  r.finite_elements->active_set_iterations = active_set_iterations_;
  r.finite_elements->unknowns = static_cast<long>(
      dealii::Utilities::MPI::sum(model_ ? model_->unknowns() : std::size_t(0), comm_));
  r.stages = {"gmsh_mesh", "fem_beams", "active_set"};
  if (detector_.point_search()) r.stages.push_back("point_contacts");
  if (detector_.slicing()) r.stages.push_back("slices");
  if (detector_.walls()) r.stages.push_back("walls");
  if (options_.line_contact == LineContact::continuous)
    r.stages.push_back("continuous_line_contact");
  r.stages.push_back(options_.beam_solver == BeamSolver::direct ? "mumps" : "cg_boomeramg");
  if (mu_ > 0.0) {
    r.stages.push_back("friction_coulomb");
    if (scene_.contact.friction_model == FrictionModel::seed)
      r.warnings.push_back(
          "the reference solves Coulomb's law exactly; friction_model \"seed\" names the "
          "iterative solver's approximation of it (Eqs. 4.29-4.33), which it is compared with");
  }
  if (r.status == Status::converged && r.max_overlap > tolerance_) {
    std::ostringstream out;
    out.precision(3);
    out << "an overlap of " << r.max_overlap << " mm remains, above the scene's tolerance of "
        << tolerance_ << " mm: the round-off of the finite-element solves and of the contact "
        << "compliance matrix (close contact points make it ill-conditioned)";
    r.warnings.push_back(out.str());
  }
  if (processes_ > 1) r.stages.push_back("mpi_" + std::to_string(processes_) + "_processes");
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream timing;
  timing.precision(3);
  timing << "unknowns " << r.finite_elements->unknowns << ", active-set passes "
         << active_set_iterations_;
  if (mu_ > 0.0)
    timing << ", friction: Tresca updates " << tresca_updates_ << ", Newton steps "
           << newton_steps_;
  if (options_.beam_solver == BeamSolver::cg_amg)
    timing << ", CG iterations " << (model_ ? model_->cg_iterations() : 0) << " (last mesh)";
  timing << "; wall time per phase (s):";
  for (const auto& [phase, seconds] : timer_.get_summary_data(dealii::TimerOutput::total_wall_time))
    timing << " " << phase << " " << seconds;
  if (!r.message.empty()) r.message += "; ";
  r.message += timing.str();
  if (options_.print_timing) {
    if (processes_ == 1)
      timer_.print_summary();
    else
      timer_.print_wall_time_statistics(comm_);
  }
  return r;
}

}  // namespace

int continuous_cells(const Scene& scene, int K) {
  const int n = scene.contact.slices;
  if (K >= 0) return n << K;
  if (K < coarsest_refinement(scene))
    throw std::invalid_argument("continuous_cells: refinement " + std::to_string(K) +
                                " below the coarsest for " + std::to_string(n) + " slices");
  return n >> -K;
}

int coarsest_refinement(const Scene& scene) {
  int K = 0;
  for (int n = scene.contact.slices; K > -2 && n % 2 == 0 && n / 2 >= 4; n /= 2) --K;
  return K;
}

int finest_refinement(const Scene& scene, long points) {
  int K = 0;
  while ((2L * scene.contact.slices << (K + 1)) <= points) ++K;
  return K;
}

MeshOptions reference_mesh_options(const Scene& scene, const ReferenceOptions& options) {
  ReferenceOptions serial = options;
  serial.communicator = MPI_COMM_SELF;
  ReferenceSolver solver(scene, serial);
  return solver.first_mesh_options();
}

// Continuous line contact, refined until its line force is known to `refinement_tolerance`. The
// line force converges at first order (a force next to a pinned end moves nothing), so the change
// from one refinement to the next says little about what is left; instead each refinement K ≥ 2
// extrapolates (Richardson) with the order observed on the last three, and the refinement stops
// when two successive extrapolations agree. Every line and wall pair gets its extrapolated force.
namespace {
Result solve_refined_until_settled(const Scene& scene, const ReferenceOptions& options,
                                   SlipOrigins& origins);
}  // namespace

Result solve_reference(const Scene& scene, const ReferenceOptions& options) {
  share_cores_with_blas(options.communicator);
  // A load path step by step; without friction each step's answer is that of its own geometry
  // and loads, so each is solved afresh, exactly.
  // With friction each step starts where the last one ended (its slip is measured from there).
  SlipOrigins origins;
  Result r = solve_load_path(scene, [&](const Scene& step, const Result*) {
    if (!options.refine_until_converged || options.line_contact != LineContact::continuous) {
      ReferenceSolver solver(step, options);
      solver.start_from(origins);
      Result result = solver.run();
      origins = solver.end_state();
      return result;
    }
    return solve_refined_until_settled(step, options, origins);
  });
  replace_non_finite(r);
  return r;
}

void share_cores_with_blas(MPI_Comm communicator) {
  MPI_Comm node;
  MPI_Comm_split_type(communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int here = 1;
  MPI_Comm_size(node, &here);
  MPI_Comm_free(&node);
  if (here <= 1) return;
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int share = std::max(1, cores / here);
  if (blas_threads() > share) set_blas_threads(share);
}

namespace {
Result solve_refined_until_settled(const Scene& scene, const ReferenceOptions& options,
                                   SlipOrigins& origins) {
  const SlipOrigins start = origins;
  auto line_force = [](const Result& r) {
    double total = 0.0;
    for (const ContactResult& c : r.contacts)
      if (c.kind != "point") total += c.total_force;
    return total;
  };
  using PairKey = std::tuple<std::string, std::string, std::string>;
  auto pair_forces = [](const Result& r) {
    std::map<PairKey, double> forces;
    for (const ContactResult& c : r.contacts)
      if (c.kind != "point") forces[{c.kind, c.fibres[0], c.fibres[1]}] = c.total_force;
    return forces;
  };
  ReferenceOptions once = options;
  once.refine_until_converged = false;
  std::vector<double> force, extrapolated;
  std::map<PairKey, double> previous_pairs;
  Result r;
  double order = NAN, estimate = NAN;
  for (int K = std::min(options.refine, coarsest_refinement(scene)); K <= options.max_refine; ++K) {
    once.refine = K;
    ReferenceSolver solver(scene, once);
    solver.start_from(start);
    r = solver.run();
    origins = solver.end_state();
    if (r.status != Status::converged) return r;
    force.push_back(line_force(r));
    const std::size_t m = force.size();
    if (force.back() == 0.0) return r;  // no line contact: nothing to refine
    double E = NAN;
    if (m >= 3) {
      const double d1 = force[m - 2] - force[m - 3], d2 = force[m - 1] - force[m - 2];
      // Monotone convergence at an order between 1/2 and 4, or the data are not asymptotic yet.
      const double p = d1 * d2 > 0.0 ? std::log2(d1 / d2) : NAN;
      if (p >= 0.5 && p <= 4.0) {
        order = p;
        E = force[m - 1] + d2 / (std::exp2(p) - 1.0);
      } else if (d2 == 0.0) {
        E = force[m - 1];
      }
    }
    extrapolated.push_back(E);
    if (m >= 4 && std::isfinite(E) && std::isfinite(extrapolated[m - 2]))
      estimate = std::fabs(E - extrapolated[m - 2]) / std::fabs(E);
    else if (m >= 2)
      // Not (yet) in the asymptotic range: the last change is all that is known.
      estimate = std::fabs(force[m - 1] - force[m - 2]) / std::fabs(force[m - 1]);
    if (options.progress) {
      std::ostringstream line;
      line.precision(8);
      line << "refinement K = " << K << ": line and wall force " << force.back() << " N";
      if (std::isfinite(E)) line << ", extrapolated " << E << " N (order " << order << ")";
      if (std::isfinite(estimate)) line << ", estimated error " << estimate;
      options.progress(line.str());
    }
    const std::map<PairKey, double> pairs = pair_forces(r);
    if (m >= 2) {
      FiniteElementFigures& figures = *r.finite_elements;
      figures.refinement = K;
      figures.line_force_order = std::isfinite(E) ? order : 0.0;
      figures.line_force_error_estimate = estimate;
    }
    if (std::isfinite(E)) {
      for (ContactResult& c : r.contacts) {
        if (c.kind == "point") continue;
        auto it = previous_pairs.find({c.kind, c.fibres[0], c.fibres[1]});
        const double before = it == previous_pairs.end() ? c.total_force : it->second;
        c.extrapolated_force = c.total_force + (c.total_force - before) / (std::exp2(order) - 1.0);
      }
    }
    previous_pairs = pairs;
    if (m >= 4 && std::isfinite(E) && estimate <= options.refinement_tolerance) {
      std::ostringstream out;
      out.precision(3);
      out << "continuous line contact extrapolated at refinement " << K << " ("
          << r.finite_elements->unknowns << " unknowns): line force converging at order " << order
          << ", extrapolated line force within an estimated " << estimate << " (relative); "
          << r.message;
      r.message = out.str();
      return r;
    }
  }
  std::ostringstream out;
  out.precision(3);
  out << "the continuous line contact's extrapolated line force did not settle to "
      << options.refinement_tolerance << " by refinement " << options.max_refine;
  if (std::isfinite(estimate)) out << " (estimated error " << estimate << ")";
  r.warnings.push_back(out.str());
  return r;
}

}  // namespace

}  // namespace fibrecheck
