// assemble_system: the contact problem of the current candidates from finite-element solutions.

#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "process_sums.h"
#include "reference_solver_class.h"

namespace fibrecheck {

namespace {

/// Entries summed into a sparse matrix: from triplets, which make its pattern, or, where the matrix
/// already has the pattern of these entries (the same candidates about new normals), into it in
/// place: a geometric update then neither holds the triplets nor sorts them again.
class SparseSum {
 public:
  SparseSum(Eigen::SparseMatrix<double>& W, Eigen::Index size, bool in_place, std::size_t count)
      : W_(W), size_(size), in_place_(in_place && W.rows() == size && W.isCompressed()) {
    if (in_place_)
      W_.coeffs().setZero();
    else
      entries_.reserve(count);
  }
  void add(Eigen::Index row, Eigen::Index column, double value) {
    if (in_place_)
      W_.coeffRef(row, column) += value;  // found in the pattern: nothing inserted
    else
      entries_.emplace_back(row, column, value);
  }
  void finish() {
    if (in_place_) return;
    W_.resize(size_, size_);
    W_.setFromTriplets(entries_.begin(), entries_.end());  // sums duplicates
  }

 private:
  Eigen::SparseMatrix<double>& W_;
  Eigen::Index size_;
  bool in_place_;
  std::vector<Eigen::Triplet<double>> entries_;
};

}  // namespace

// assemble_system: the overlaps d0 under the scene's loads and the compliance matrix W (and with
// friction its tangential blocks), from finite-element solutions.
void ReferenceSolver::assemble_system() {
  dealii::TimerOutput::Scope scope(timer_, "assemble_system");
  G_ = loads_and_influence();
  const std::vector<std::vector<ContactSide>> sides = assemble_compliance(G_, false);
  if (mu_ > 0.0) assemble_frictional_problem(G_, sides, false);
  // Shared, W is applied through them; the deformed contact assembles again about new normals on
  // the same mesh.
  if (!compliance_shared() && !detector_.geometry().deformed()) G_ = {};
}

// The displacements u0_ at every station under the scene's loads, and the influence matrices G_f
// (mm/N, the same in both bending planes; packed by g_offset_), which the function returns. Each
// process fills in its own fibres; where the compliance is not shared, the sums give every process
// all of them. Every process takes the same branch after a non-finite solution.
std::vector<double> ReferenceSolver::loads_and_influence() {
  u0_.assign(3 * offset_.back(), 0.0);
  std::vector<double> G(saddle_point() ? 0 : g_offset_.back(), 0.0);
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
    const std::vector<Eigen::MatrixXd> influence =
        saddle_point() ? std::vector<Eigen::MatrixXd>(fibres_.size())
                       : model_->influence_matrices(stations_, report);
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      const std::size_t m = stations_[f].size();
      if (!owned_[f] || influence[f].size() == 0) continue;
      for (std::size_t j = 0; j < m; ++j)
        for (std::size_t i = 0; i < m; ++i) G[g_offset_[f] + j * m + i] = influence[f](j, i);
    }
  }
  sum_over_processes(u0_, comm_);
  if (!compliance_shared()) sum_over_processes(G, comm_);
  const auto finite = [](double x) { return std::isfinite(x); };
  const bool all_finite =
      std::all_of(u0_.begin(), u0_.end(), finite) && std::all_of(G.begin(), G.end(), finite);
  if (!all_over_processes(all_finite, comm_)) trouble_.non_finite = true;
  return G;
}

// The overlaps d0_ under the scene's loads and W_jk = Σ_f α_j α_k G_f(j, k) n_j⊥·n_k⊥ over the
// fibres both contacts act on, ⊥ the part across the fibre (mm/N); shared, W applied through this
// process's fibres' influence matrices (influence_compliance.h), never formed. Returns each fibre's
// contact sides, from which the frictional blocks are assembled alike. `in_place`: W has the
// pattern of these candidates already (new normals only).
std::vector<std::vector<ReferenceSolver::ContactSide>> ReferenceSolver::assemble_compliance(
    const std::vector<double>& G, bool in_place) {
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
  if (saddle_point()) {
    make_saddle_point(sides);
    return sides;
  }
  const auto across = [&](std::size_t f, const ContactSide& side) {
    const Eigen::Vector3d t = fibres_[f].t, n = contacts_[side.contact].normal;
    return Eigen::Vector3d(side.alpha * (n - n.dot(t) * t));
  };
  if (compliance_shared()) {
    std::vector<InfluenceCompliance::Fibre> held;
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      InfluenceCompliance::Fibre fibre{&G[g_offset_[f]], static_cast<int>(stations_[f].size()), {}};
      for (const ContactSide& side : sides[f])
        fibre.sides.push_back({side.contact, side.station, across(f, side)});
      held.push_back(std::move(fibre));
    }
    influence_ = std::make_unique<InfluenceCompliance>(std::move(held), n, comm_);
    return sides;
  }
  std::size_t count = 0;
  for (const auto& list : sides) count += list.size() * list.size();
  SparseSum W(W_, n, in_place, count);
  std::vector<Eigen::Vector3d> phi;
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    const std::size_t m = stations_[f].size();
    phi.clear();
    for (const ContactSide& side : sides[f]) phi.push_back(across(f, side));
    for (std::size_t j = 0; j < sides[f].size(); ++j)
      for (std::size_t k = 0; k < sides[f].size(); ++k)
        W.add(sides[f][j].contact, sides[f][k].contact,
              G[g_offset_[f] + sides[f][j].station * m + sides[f][k].station] * phi[j].dot(phi[k]));
  }
  W.finish();  // the two fibres' parts summed
  return sides;
}

// W as saddle points: each contact's sides (A first, whose process holds its constraint row) with
// the force a unit reaction puts on them.
void ReferenceSolver::make_saddle_point(const std::vector<std::vector<ContactSide>>& sides) {
  std::vector<std::vector<ContactSideForce>> forces(contacts_.size());
  for (std::size_t f = 0; f < fibres_.size(); ++f)
    for (const ContactSide& side : sides[f]) {
      const Eigen::Vector3d direction = reaction_direction(side.contact, 0, side.on_a);
      const ContactSideForce force{static_cast<int>(f), stations_[f][side.station], direction};
      auto& list = forces[side.contact];
      if (side.on_a)
        list.insert(list.begin(), force);
      else
        list.push_back(force);
    }
  std::vector<int> owner(fibres_.size());
  for (std::size_t f = 0; f < fibres_.size(); ++f) owner[f] = static_cast<int>(f % processes_);
  saddle_ = std::make_unique<SaddlePointCompliance>(comm_, model_.get(), fibres_, std::move(owner),
                                                    std::move(forces));
  if (options_.progress && rank_ == 0) saddle_->report_to(options_.progress);
}

// The direction φ along which component i of contact k's reaction acts on one of its sides (the
// force on that fibre per unit reaction): the normal −n on A and +n on B (+n on a walled fibre),
// a tangent +t on A and −t on B (the second tangent n × t).
Eigen::Vector3d ReferenceSolver::reaction_direction(Eigen::Index k, int i, bool on_a) const {
  const Contact& c = contacts_[k];
  if (i == 0) return (c.kind == ContactKind::wall || !on_a) ? c.normal : Eigen::Vector3d(-c.normal);
  const Eigen::Vector3d t = i == 1 ? c.tangent : c.second_tangent();
  return on_a ? t : Eigen::Vector3d(-t);
}

// Friction: W with the tangential blocks, W_(j,a)(k,b) = Σ_f G_f(j, k) φ⊥_ja·φ⊥_kb, and q the
// overlaps d0 and the slips under the scene's loads alone (measured from the step's start);
// shared, W applied through this process's fibres' influence matrices like the frictionless one.
void ReferenceSolver::assemble_frictional_problem(
    const std::vector<double>& G, const std::vector<std::vector<ContactSide>>& sides,
    bool in_place) {
  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  FrictionalProblem& problem = friction_problem_;
  problem.mu = mu_;
  const std::vector<Eigen::Index> offset_before = problem.offset;
  problem.offset.assign(n + 1, 0);
  for (Eigen::Index k = 0; k < n; ++k)
    problem.offset[k + 1] = problem.offset[k] + 1 + contacts_[k].tangents;
  // A normal turned along the tow axis takes its slice's tangent away: a new pattern then.
  in_place = in_place && problem.offset == offset_before;
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
  problem.excluded.assign(n, 0);
  if (compliance_shared()) {
    std::vector<InfluenceCompliance::Fibre> held;
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      const Eigen::Vector3d t = fibres_[f].t;
      InfluenceCompliance::Fibre fibre{&G[g_offset_[f]], static_cast<int>(stations_[f].size()), {}};
      for (const ContactSide& j : sides[f])
        for (int a = 0; a <= contacts_[j.contact].tangents; ++a) {
          const Eigen::Vector3d phi = reaction_direction(j.contact, a, j.on_a);
          fibre.sides.push_back({problem.offset[j.contact] + a, j.station, phi - phi.dot(t) * t});
        }
      held.push_back(std::move(fibre));
    }
    frictional_influence_ = std::make_unique<InfluenceCompliance>(std::move(held), unknowns, comm_);
    return;
  }
  std::size_t count = 0;
  for (const auto& list : sides) count += list.size() * list.size();
  SparseSum frictional(problem.W, problem.offset[n], in_place, 4 * count);
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
            frictional.add(problem.offset[j.contact] + a, problem.offset[k.contact] + b,
                           g * pj.dot(across(reaction_direction(k.contact, b, k.on_a))));
        }
      }
  }
  frictional.finish();
}

}  // namespace fibrecheck
