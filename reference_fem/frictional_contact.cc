#include "frictional_contact.h"

#include <Eigen/Dense>
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

}  // namespace

FrictionalSolve solve_frictional(const FrictionalProblem& p, double tolerance, int max_steps,
                                 Eigen::VectorXd& r) {
  FrictionalSolve result;
  const std::size_t n = p.offset.size() - 1;
  NaturalMap map(p);
  double residual = map.evaluate(r);
  auto merit = [&](const NaturalMap& m) {
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      if (m.rho[j] == 0.0) continue;
      const Eigen::Index o = p.offset[j], k = p.offset[j + 1] - o;
      sum += m.phi.segment(o, k).squaredNorm() / (m.rho[j] * m.rho[j]);
    }
    return sum;
  };
  double current = merit(map);
  Eigen::VectorXd best = r;
  double best_merit = current, best_residual = residual;
  int nonmonotone = 20;
  for (result.newton_steps = 0; result.newton_steps < max_steps; ++result.newton_steps) {
    if (residual <= tolerance) break;
    // The closed contacts' components, in order.
    std::vector<Eigen::Index> closed, position(r.size(), -1);
    for (std::size_t j = 0; j < n; ++j)
      if (map.state[j] != State::open)
        for (Eigen::Index i = p.offset[j]; i < p.offset[j + 1]; ++i) {
          position[i] = static_cast<Eigen::Index>(closed.size());
          closed.push_back(i);
        }
    const Eigen::Index m = static_cast<Eigen::Index>(closed.size());
    // Open contacts go to zero: Δr_O = −r_O; its effect on the closed rows is −W_CO·r_O.
    Eigen::VectorXd open_part = r;
    for (Eigen::Index i : closed) open_part[i] = 0.0;
    const Eigen::VectorXd W_open = p.W * open_part;
    Eigen::MatrixXd Wcc = Eigen::MatrixXd::Zero(m, m);
    for (Eigen::Index col = 0; col < m; ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(p.W, closed[col]); it; ++it)
        if (position[it.row()] >= 0) Wcc(position[it.row()], col) = it.value();
    // J = A + B·W on the closed blocks, block by block (see the header for Φ).
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, m);
    Eigen::VectorXd rhs(m);
    for (std::size_t j = 0; j < n; ++j) {
      if (map.state[j] == State::open) continue;
      const Eigen::Index o = p.offset[j], k = p.offset[j + 1] - o, b = position[o];
      const double rho = map.rho[j];
      // Rows that read "the w of these components vanishes": ρ·W rows.
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(k, k), B = Eigen::MatrixXd::Zero(k, k);
      B(0, 0) = rho;
      if (map.state[j] == State::stick) {
        for (Eigen::Index i = 1; i < k; ++i) {
          if (map.frozen[o + i])
            A(i, i) = 1.0;
          else
            B(i, i) = rho;
        }
      } else {
        // Slip: Φ_t = F − μ z_n ẑ; dΦ_t = (I − K)dF − μẑ dP + ρμẑ(W dr)_n + ρK(W dr)_t,
        // K = μ z_n/|z_t| (I − ẑẑᵀ).
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
        // Coulomb's radius μ·z_n moves with the normal part; Tresca's is fixed.
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
      J.block(b, b, k, k) += A;
      J.middleRows(b, k) += B * Wcc.middleRows(b, k);
      // −Φ_C − J_CO·Δr_O = −Φ_C + B·(W_CO·r_O).
      rhs.segment(b, k) = -map.phi.segment(o, k) + B * W_open.segment(o, k);
    }
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
    Eigen::VectorXd step_c = lu.solve(rhs);
    if (!step_c.allFinite() || (J * step_c - rhs).norm() > 1e-6 * (rhs.norm() + 1e-300)) {
      // Closed contacts that constrain the same motion: regularise by 1e-10 of W's diagonal.
      Eigen::MatrixXd Jr = J;
      const double epsilon = 1e-10 * Wcc.diagonal().cwiseAbs().maxCoeff();
      for (std::size_t j = 0; j < n; ++j) {
        if (map.state[j] == State::open) continue;
        const Eigen::Index o = p.offset[j], b = position[o];
        Jr(b, b) += map.rho[j] * epsilon;
      }
      step_c = Eigen::PartialPivLU<Eigen::MatrixXd>(Jr).solve(rhs);
      if (!step_c.allFinite()) {
        result.singular = true;
        break;
      }
    }
    Eigen::VectorXd step = -open_part;
    for (Eigen::Index c = 0; c < m; ++c) step[closed[c]] = step_c[c];
    // Backtracking on ‖Φ‖²; if no fraction lowers it, the full step is taken anyway (the map is
    // only piecewise smooth and a set change may need to pass a ridge).
    double alpha = 1.0;
    Eigen::VectorXd trial;
    bool accepted = false;
    for (int halving = 0; halving < 30; ++halving, alpha *= 0.5) {
      trial = r + alpha * step;
      NaturalMap next = map;
      const double res = next.evaluate(trial);
      const double value = merit(next);
      // The whole step changes the sets (a contact closes or opens, one starts or stops
      // slipping): taken, as a primal–dual active-set method would, within a budget of
      // non-monotone steps; otherwise the search walks towards the kink and stalls there.
      const bool set_change =
          halving == 0 && next.state != map.state && value < 10.0 * current && nonmonotone > 0;
      if (set_change) --nonmonotone;
      if (value <= (1.0 - 1e-4 * alpha) * current || res <= tolerance || set_change) {
        r = trial;
        map = std::move(next);
        residual = res;
        current = value;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // No fraction of the step lowers ‖Φ‖: a set change the Newton model cannot see. Take a
      // small step (1/1000 of it) so that the sets may change, but never a large one.
      trial = r + 1e-3 * step;
      NaturalMap next = map;
      residual = next.evaluate(trial);
      r = trial;
      map = std::move(next);
      current = merit(map);
      ++result.stalled_steps;
    }
    if (current < best_merit) {
      best_merit = current;
      best = r;
      best_residual = residual;
    }
  }
  if (residual > tolerance && best.size() == r.size()) {
    // Not settled: return the best state seen, never a wild last one.
    r = best;
    residual = best_residual;
  }
  result.residual = residual;
  result.settled = residual <= tolerance;
  return result;
}

}  // namespace fibrecheck
