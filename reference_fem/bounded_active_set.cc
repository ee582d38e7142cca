#include "bounded_active_set.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "subset_solve.h"

namespace fibrecheck {

BoundedSolve bounded_active_set(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                double tolerance, int max_passes, Eigen::VectorXd& r) {
  BoundedSolve result;
  const Eigen::Index n = q.size();
  if (r.size() != n) r = Eigen::VectorXd::Zero(n);
  r = r.cwiseMax(lo).cwiseMin(hi);
  // −1 held at lo, +1 held at hi, 0 free.
  std::vector<signed char> state(n, 0);
  for (Eigen::Index i = 0; i < n; ++i) state[i] = r[i] <= lo[i] ? -1 : (r[i] >= hi[i] ? 1 : 0);
  auto free_solve = [&](Eigen::VectorXd& z) {
    std::vector<Eigen::Index> index;
    for (Eigen::Index i = 0; i < n; ++i)
      if (state[i] == 0) index.push_back(i);
    z = r;
    const Eigen::Index m = static_cast<Eigen::Index>(index.size());
    if (m == 0) return true;
    Eigen::VectorXd held = r;
    for (Eigen::Index i : index) held[i] = 0.0;
    const Eigen::VectorXd load = q - W * held;
    Eigen::VectorXd b(m), x;
    for (Eigen::Index k = 0; k < m; ++k) b[k] = load[index[k]];
    if (!solve_on_subset(W, index, b, x)) return false;
    for (Eigen::Index k = 0; k < m; ++k) z[index[k]] = x[k];
    return true;
  };
  // Solve on the free set, stepping back to the box: the first variable to reach a bound is held
  // there, and the free set solved again.
  auto settle = [&]() {
    Eigen::VectorXd z;
    for (Eigen::Index guard = 0; guard <= n; ++guard) {
      if (!free_solve(z)) return false;
      double alpha = 1.0;
      Eigen::Index blocking = -1;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (state[i] != 0 || (z[i] >= lo[i] && z[i] <= hi[i])) continue;
        const double bound = z[i] < lo[i] ? lo[i] : hi[i];
        const double a = (bound - r[i]) / (z[i] - r[i]);
        if (blocking < 0 || a < alpha) alpha = a, blocking = i;
      }
      if (blocking < 0) {
        r = z;
        return true;
      }
      r += std::clamp(alpha, 0.0, 1.0) * (z - r);
      state[blocking] = z[blocking] < lo[blocking] ? -1 : 1;
      r[blocking] = state[blocking] < 0 ? lo[blocking] : hi[blocking];
      r = r.cwiseMax(lo).cwiseMin(hi);
    }
    return true;
  };
  auto objective = [&]() { return 0.5 * r.dot(W * r) - q.dot(r); };
  bool one_at_a_time = false;
  std::vector<char> set_aside(n, 0);
  std::vector<Eigen::Index> added;
  double before = INFINITY;
  for (result.passes = 0; result.passes < max_passes; ++result.passes) {
    if (!settle()) {
      if (!one_at_a_time) {
        one_at_a_time = true;
        continue;
      }
      result.singular = true;
      return result;
    }
    // A pass that gained nothing (round-off decides it): one variable at a time, and a single one
    // that gains nothing is set aside until something changes.
    const double now = objective();
    const bool progress = now < before - 1e-14 * std::fabs(before);
    if (progress) {
      std::fill(set_aside.begin(), set_aside.end(), 0);
      one_at_a_time = false;
    } else if (std::isfinite(before)) {
      if (one_at_a_time && added.size() == 1) set_aside[added[0]] = 1;
      one_at_a_time = true;
    }
    before = std::min(before, now);
    const Eigen::VectorXd w = q - W * r;
    std::vector<std::pair<double, Eigen::Index>> leaving;
    std::size_t free_count = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (state[i] == 0) {
        ++free_count;
        continue;
      }
      if (lo[i] >= hi[i] || set_aside[i]) continue;
      if (state[i] < 0 && w[i] > tolerance) leaving.push_back({w[i], i});
      if (state[i] > 0 && w[i] < -tolerance) leaving.push_back({-w[i], i});
    }
    if (leaving.empty()) {
      result.solved = true;
      return result;
    }
    const std::size_t add =
        one_at_a_time ? 1 : std::min(leaving.size(), std::max<std::size_t>(8, free_count));
    std::partial_sort(leaving.begin(), leaving.begin() + static_cast<long>(add), leaving.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
    added.clear();
    for (std::size_t k = 0; k < add; ++k) {
      state[leaving[k].second] = 0;
      added.push_back(leaving[k].second);
    }
  }
  return result;
}

}  // namespace fibrecheck
