#include "frictional_contact.h"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

namespace fibrecheck {

namespace {

enum class State : unsigned char { open, stick, slip };

/// The natural map and what its generalised Jacobian needs.
struct NaturalMap {
  const FrictionalProblem* problem;
  std::vector<double> rho;   ///< per contact
  std::vector<char> frozen;  ///< per component: a tangent nothing moves along, F = 0
  std::vector<State> state;  ///< per contact
  Eigen::VectorXd phi, w;

  explicit NaturalMap(const FrictionalProblem& p) : problem(&p) {
    const std::size_t n = p.offset.size() - 1;
    rho.assign(n, 0.0);
    frozen.assign(p.q.size(), 0);
    for (std::size_t j = 0; j < n; ++j) {
      const Eigen::Index o = p.offset[j];
      const double diagonal = p.W.coeff(o, o);
      rho[j] = (diagonal > 0.0 && !p.excluded[j]) ? 1.0 / diagonal : 0.0;
      for (Eigen::Index i = o + 1; i < p.offset[j + 1]; ++i)
        frozen[i] = !(p.W.coeff(i, i) > 1e-12 * std::max(diagonal, 0.0));
    }
  }

  /// Φ(r) and the contacts' states; returns max_j ‖Φ_j‖/ρ_j (mm).
  double evaluate(const Eigen::VectorXd& r) {
    const FrictionalProblem& p = *problem;
    w = p.q - p.W * r;
    phi.resize(r.size());
    state.assign(rho.size(), State::open);
    double largest = 0.0;
    for (std::size_t j = 0; j < rho.size(); ++j) {
      const Eigen::Index o = p.offset[j], m = p.offset[j + 1] - o;
      if (rho[j] == 0.0) {
        phi.segment(o, m) = r.segment(o, m);
        // Nothing moves it: its force must vanish, whatever it overlaps (checked before).
        largest = std::max(largest, r.segment(o, m).cwiseAbs().maxCoeff() > 0.0 ? INFINITY : 0.0);
        continue;
      }
      const double zn = r[o] + rho[j] * w[o];
      if (zn <= 0.0) {
        phi.segment(o, m) = r.segment(o, m);
      } else {
        state[j] = State::stick;
        phi[o] = -rho[j] * w[o];
        Eigen::Vector2d zt = Eigen::Vector2d::Zero();
        for (Eigen::Index i = 1; i < m; ++i)
          zt[i - 1] = frozen[o + i] ? 0.0 : r[o + i] + rho[j] * w[o + i];
        const double radius = p.bounds.size() ? p.bounds[static_cast<Eigen::Index>(j)] : p.mu * zn;
        if (zt.norm() > radius) {
          state[j] = State::slip;
          const Eigen::Vector2d on = zt * (radius / zt.norm());
          for (Eigen::Index i = 1; i < m; ++i) phi[o + i] = r[o + i] - on[i - 1];
        } else {
          for (Eigen::Index i = 1; i < m; ++i)
            phi[o + i] = frozen[o + i] ? r[o + i] : -rho[j] * w[o + i];
        }
      }
      largest = std::max(largest, phi.segment(o, m).norm() / rho[j]);
    }
    return largest;
  }
};

/// ‖Φ‖² in mm²: Σ_j ‖Φ_j‖²/ρ_j² over the contacts something moves.
double merit(const FrictionalProblem& p, const NaturalMap& m) {
  const std::size_t n = p.offset.size() - 1;
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    if (m.rho[j] == 0.0) continue;
    const Eigen::Index o = p.offset[j], k = p.offset[j + 1] - o;
    sum += m.phi.segment(o, k).squaredNorm() / (m.rho[j] * m.rho[j]);
  }
  return sum;
}

/// One Newton system on the closed (sticking and slipping) contacts' components, in order:
/// J·Δr_C = rhs with J = A + B·W_CC block by block, the open contacts' step Δr_O = −r_O. J is as
/// sparse as W: contacts couple only through the fibres they share.
struct NewtonSystem {
  std::vector<Eigen::Index> closed;    ///< the closed components
  std::vector<Eigen::Index> position;  ///< per component, its place in `closed` (−1: open)
  Eigen::VectorXd open_part;           ///< r on the open components, zero on the closed
  Eigen::SparseMatrix<double> J;
  Eigen::VectorXd rhs;
  double largest_compliance = 0.0;  ///< W_CC's largest diagonal entry
};

/// The blocks A, B of one closed contact j with k components (see the header for Φ): rows that
/// read "the w of these components vanishes" are ρ·W rows (B), a tangent nothing moves along
/// keeps F = 0 (A). Slip: Φ_t = F − g ẑ; dΦ_t = (I − K)dF − μẑ dP + ρμẑ(W dr)_n + ρK(W dr)_t,
/// K = g/|z_t| (I − ẑẑᵀ), g = μ z_n for Coulomb (moving with the normal part) and the fixed
/// radius for Tresca.
void contact_blocks(const FrictionalProblem& p, const NaturalMap& map, const Eigen::VectorXd& r,
                    std::size_t j, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
  const Eigen::Index o = p.offset[j], k = p.offset[j + 1] - o;
  const double rho = map.rho[j];
  A = Eigen::MatrixXd::Zero(k, k);
  B = Eigen::MatrixXd::Zero(k, k);
  B(0, 0) = rho;
  if (map.state[j] == State::stick) {
    for (Eigen::Index i = 1; i < k; ++i) {
      if (map.frozen[o + i])
        A(i, i) = 1.0;
      else
        B(i, i) = rho;
    }
    return;
  }
  const double zn = r[o] + rho * map.w[o];
  Eigen::VectorXd zt = Eigen::VectorXd::Zero(k - 1);
  for (Eigen::Index i = 1; i < k; ++i)
    zt[i - 1] = map.frozen[o + i] ? 0.0 : r[o + i] + rho * map.w[o + i];
  const double size = zt.norm();
  const Eigen::VectorXd unit = zt / size;
  const bool tresca = p.bounds.size() > 0;
  const double radius = tresca ? p.bounds[static_cast<Eigen::Index>(j)] : p.mu * zn;
  const Eigen::MatrixXd K =
      (radius / size) * (Eigen::MatrixXd::Identity(k - 1, k - 1) - unit * unit.transpose());
  A.block(1, 1, k - 1, k - 1) = Eigen::MatrixXd::Identity(k - 1, k - 1) - K;
  const double coupling = tresca ? 0.0 : p.mu;
  A.block(1, 0, k - 1, 1) = -coupling * unit;
  B.block(1, 0, k - 1, 1) = rho * coupling * unit;
  B.block(1, 1, k - 1, k - 1) = rho * K;
  for (Eigen::Index i = 1; i < k; ++i)
    if (map.frozen[o + i]) {
      A.row(i).setZero();
      B.row(i).setZero();
      A(i, i) = 1.0;
    }
}

/// The Newton system at r: −Φ_C − J_CO·Δr_O = −Φ_C + B·(W_CO·r_O) on the right.
NewtonSystem newton_system(const FrictionalProblem& p, const NaturalMap& map,
                           const Eigen::VectorXd& r) {
  const std::size_t n = p.offset.size() - 1;
  NewtonSystem s;
  s.position.assign(r.size(), -1);
  for (std::size_t j = 0; j < n; ++j)
    if (map.state[j] != State::open)
      for (Eigen::Index i = p.offset[j]; i < p.offset[j + 1]; ++i) {
        s.position[i] = static_cast<Eigen::Index>(s.closed.size());
        s.closed.push_back(i);
      }
  const Eigen::Index m = static_cast<Eigen::Index>(s.closed.size());
  s.open_part = r;
  for (Eigen::Index i : s.closed) s.open_part[i] = 0.0;
  const Eigen::VectorXd W_open = p.W * s.open_part;
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index col = 0; col < m; ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.W, s.closed[col]); it; ++it)
      if (s.position[it.row()] >= 0) {
        entries.emplace_back(s.position[it.row()], col, it.value());
        if (s.position[it.row()] == col)
          s.largest_compliance = std::max(s.largest_compliance, std::fabs(it.value()));
      }
  Eigen::SparseMatrix<double> Wcc(m, m);
  Wcc.setFromTriplets(entries.begin(), entries.end());
  std::vector<Eigen::Triplet<double>> a_entries, b_entries;
  s.rhs.resize(m);
  Eigen::MatrixXd A, B;
  for (std::size_t j = 0; j < n; ++j) {
    if (map.state[j] == State::open) continue;
    const Eigen::Index o = p.offset[j], k = p.offset[j + 1] - o, b = s.position[o];
    contact_blocks(p, map, r, j, A, B);
    for (Eigen::Index row = 0; row < k; ++row)
      for (Eigen::Index col = 0; col < k; ++col) {
        if (A(row, col) != 0.0) a_entries.emplace_back(b + row, b + col, A(row, col));
        if (B(row, col) != 0.0) b_entries.emplace_back(b + row, b + col, B(row, col));
      }
    s.rhs.segment(b, k) = -map.phi.segment(o, k) + B * W_open.segment(o, k);
  }
  Eigen::SparseMatrix<double> Ab(m, m), Bb(m, m);
  Ab.setFromTriplets(a_entries.begin(), a_entries.end());
  Bb.setFromTriplets(b_entries.begin(), b_entries.end());
  s.J = Ab + Bb * Wcc;
  return s;
}

/// Solves J·x = rhs by a sparse LU; false when it fails, the answer is not finite or, where
/// `judged`, it leaves a residual above 1e-6 of the right-hand side.
bool sparse_solve(const Eigen::SparseMatrix<double>& J, const Eigen::VectorXd& rhs, bool judged,
                  Eigen::VectorXd& x) {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(J);
  if (lu.info() != Eigen::Success) return false;
  x = lu.solve(rhs);
  return lu.info() == Eigen::Success && x.allFinite() &&
         (!judged || (J * x - rhs).norm() <= 1e-6 * (rhs.norm() + 1e-300));
}

/// The full Newton step (closed components from the system, open ones to zero); false when the
/// system cannot be solved even regularised. Closed contacts that constrain the same motion make
/// J singular: it is then regularised by 1e-10 of W's diagonal.
bool newton_step(const FrictionalProblem& p, const NaturalMap& map, const NewtonSystem& s,
                 Eigen::VectorXd& step) {
  const std::size_t n = p.offset.size() - 1;
  Eigen::VectorXd step_c;
  if (!sparse_solve(s.J, s.rhs, true, step_c)) {
    Eigen::SparseMatrix<double> Jr = s.J;
    const double epsilon = 1e-10 * s.largest_compliance;
    for (std::size_t j = 0; j < n; ++j) {
      if (map.state[j] == State::open) continue;
      const Eigen::Index b = s.position[p.offset[j]];
      Jr.coeffRef(b, b) += map.rho[j] * epsilon;
    }
    if (!sparse_solve(Jr, s.rhs, false, step_c)) return false;
  }
  step = -s.open_part;
  for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(s.closed.size()); ++c)
    step[s.closed[c]] = step_c[c];
  return true;
}

/// The iterate of the Newton method: r, its natural map, ‖Φ‖'s largest part and ‖Φ‖².
struct Iterate {
  NaturalMap map;
  double residual;
  double merit;
};

/// Backtracking on ‖Φ‖² along `step`. A whole step that changes the sets (a contact closes or
/// opens, one starts or stops slipping) is taken, as a primal–dual active-set method would,
/// within a budget of `nonmonotone` such steps; otherwise the search walks towards the kink and
/// stalls there. When no fraction lowers ‖Φ‖ — a set change the Newton model cannot see — a small
/// step (1/1000 of it) lets the sets change without a large one; returns false then.
bool line_search(const FrictionalProblem& p, double tolerance, const Eigen::VectorXd& step,
                 int& nonmonotone, Eigen::VectorXd& r, Iterate& at) {
  double alpha = 1.0;
  Eigen::VectorXd trial;
  for (int halving = 0; halving < 30; ++halving, alpha *= 0.5) {
    trial = r + alpha * step;
    NaturalMap next = at.map;
    const double res = next.evaluate(trial);
    const double value = merit(p, next);
    const bool set_change =
        halving == 0 && next.state != at.map.state && value < 10.0 * at.merit && nonmonotone > 0;
    if (set_change) --nonmonotone;
    if (value <= (1.0 - 1e-4 * alpha) * at.merit || res <= tolerance || set_change) {
      r = trial;
      at.map = std::move(next);
      at.residual = res;
      at.merit = value;
      return true;
    }
  }
  trial = r + 1e-3 * step;
  NaturalMap next = at.map;
  at.residual = next.evaluate(trial);
  r = trial;
  at.map = std::move(next);
  at.merit = merit(p, at.map);
  return false;
}

}  // namespace

FrictionalSolve solve_frictional(const FrictionalProblem& p, double tolerance, int max_steps,
                                 Eigen::VectorXd& r) {
  FrictionalSolve result;
  Iterate at{NaturalMap(p), 0.0, 0.0};
  at.residual = at.map.evaluate(r);
  at.merit = merit(p, at.map);
  Eigen::VectorXd best = r;
  double best_merit = at.merit, best_residual = at.residual;
  int nonmonotone = 20;
  for (result.newton_steps = 0; result.newton_steps < max_steps; ++result.newton_steps) {
    if (at.residual <= tolerance) break;
    Eigen::VectorXd step;
    if (!newton_step(p, at.map, newton_system(p, at.map, r), step)) {
      result.singular = true;
      break;
    }
    if (!line_search(p, tolerance, step, nonmonotone, r, at)) ++result.stalled_steps;
    if (at.merit < best_merit) {
      best_merit = at.merit;
      best = r;
      best_residual = at.residual;
    }
  }
  // Not settled: the best state seen, never a wild last one.
  if (at.residual > tolerance && best.size() == r.size()) {
    r = best;
    at.residual = best_residual;
  }
  result.residual = at.residual;
  result.settled = at.residual <= tolerance;
  return result;
}

}  // namespace fibrecheck
