#include "nonnegative_active_set.h"

#include <algorithm>
#include <cmath>

namespace fibrecheck {

namespace {

/// z: the forces that close every pushing contact's overlap, W_SS·z_S = d0_S, zero elsewhere;
/// false when the set's system cannot be solved.
bool solve_on_set(const ContactCompliance& W, const Eigen::VectorXd& d0,
                  const std::vector<char>& pushing, Eigen::VectorXd& z) {
  const Eigen::Index n = d0.size();
  std::vector<Eigen::Index> index;
  for (Eigen::Index k = 0; k < n; ++k)
    if (pushing[k]) index.push_back(k);
  z = Eigen::VectorXd::Zero(n);
  const Eigen::Index m = static_cast<Eigen::Index>(index.size());
  if (m == 0) return true;
  Eigen::VectorXd ds(m), zs;
  for (Eigen::Index i = 0; i < m; ++i) ds[i] = d0[index[i]];
  if (!W.solve_on_subset(index, ds, zs)) return false;
  for (Eigen::Index i = 0; i < m; ++i) z[index[i]] = zs[i];
  return true;
}

/// The warm start: the guessed set, less the contacts that would pull, until all push (an empty
/// set when the guess cannot be solved). Returns the forces of that set.
Eigen::VectorXd start_from_guess(const ContactCompliance& W, const Eigen::VectorXd& d0,
                                 std::vector<char>& pushing) {
  Eigen::VectorXd z;
  for (;;) {
    if (!solve_on_set(W, d0, pushing, z)) {
      std::fill(pushing.begin(), pushing.end(), 0);
      z.setZero();
      return z;
    }
    bool pulled = false;
    for (Eigen::Index k = 0; k < d0.size(); ++k)
      if (pushing[k] && z[k] <= 0.0) pushing[k] = 0, pulled = true;
    if (!pulled) return z;
  }
}

/// From the forces P towards the set's answer z, stopping where the first force reaches zero: that
/// contact leaves the set (whatever round-off left of its force), and so does any other at zero;
/// then z is solved again, until every force of the set's answer is positive. False when a set
/// cannot be solved.
bool step_back(const ContactCompliance& W, const Eigen::VectorXd& d0, std::vector<char>& pushing,
               Eigen::VectorXd& P, Eigen::VectorXd& z) {
  const Eigen::Index n = d0.size();
  for (int inner = 0; inner < n + 1; ++inner) {
    // A contact just added that the set's answer would make pull leaves before any step: it would
    // block the step at its start and take every other contact just added with it.
    bool left = false;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k] && z[k] <= 0.0 && P[k] <= 0.0) pushing[k] = 0, left = true;
    if (left) {
      if (!solve_on_set(W, d0, pushing, z)) return false;
      continue;
    }
    double alpha = 1.0;
    Eigen::Index blocking = -1;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k] && z[k] <= 0.0) {
        const double a = P[k] / (P[k] - z[k]);
        if (blocking < 0 || a < alpha) alpha = a, blocking = k;
      }
    if (blocking < 0) return true;
    P += alpha * (z - P);
    P[blocking] = 0.0;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k] && P[k] <= 0.0) pushing[k] = 0, P[k] = 0.0;
    if (!solve_on_set(W, d0, pushing, z)) return false;
  }
  return true;
}

}  // namespace

// The assembled W, through the same method.
ActiveSetSolve nonnegative_active_set(const Eigen::SparseMatrix<double>& W,
                                      const Eigen::VectorXd& d0, double tolerance,
                                      const std::vector<char>& excluded, int max_passes,
                                      Eigen::VectorXd& P, std::vector<char>& pushing) {
  return nonnegative_active_set(AssembledCompliance(W), d0, tolerance, excluded, max_passes, P,
                                pushing);
}

ActiveSetSolve nonnegative_active_set(const ContactCompliance& W, const Eigen::VectorXd& d0,
                                      double tolerance, const std::vector<char>& excluded,
                                      int max_passes, Eigen::VectorXd& P,
                                      std::vector<char>& pushing) {
  ActiveSetSolve result;
  const Eigen::Index n = d0.size();
  P = Eigen::VectorXd::Zero(n);
  pushing.resize(n, 0);
  if (n == 0) {
    result.solved = true;
    return result;
  }
  for (Eigen::Index k = 0; k < n; ++k)
    if (excluded[k]) pushing[k] = 0;
  P = start_from_guess(W, d0, pushing);
  bool one_at_a_time = false;
  std::vector<char> set_aside(n, 0);
  Eigen::VectorXd z;
  for (result.passes = 1; result.passes <= max_passes; ++result.passes) {
    const Eigen::VectorXd d = d0 - W.times(P);
    std::vector<Eigen::Index> overlapping;
    std::size_t set_size = 0;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!pushing[k] && !excluded[k] && !set_aside[k] && d[k] > tolerance)
        overlapping.push_back(k);
      set_size += pushing[k] ? 1 : 0;
    }
    if (overlapping.empty()) {
      result.solved = true;
      return result;
    }
    const std::size_t add =
        one_at_a_time ? 1 : std::min(overlapping.size(), std::max<std::size_t>(8, set_size));
    std::partial_sort(overlapping.begin(), overlapping.begin() + static_cast<long>(add),
                      overlapping.end(),
                      [&](Eigen::Index x, Eigen::Index y) { return d[x] > d[y]; });
    for (std::size_t i = 0; i < add; ++i) pushing[overlapping[i]] = 1;
    // ½PᵀWP − Pᵀd0 with W·P = d0 − d, from the product just made.
    const double objective_before = -0.5 * P.dot(d0 + d);
    if (!solve_on_set(W, d0, pushing, z)) {
      for (std::size_t i = 0; i < add; ++i) pushing[overlapping[i]] = 0;
      // Contacts added together may constrain the same motion (two walls in one plane): the set is
      // singular, though the problem is not. Take them one at a time instead.
      if (add > 1) {
        one_at_a_time = true;
        continue;
      }
      result.singular = true;
      return result;
    }
    if (!step_back(W, d0, pushing, P, z)) {
      result.singular = true;
      return result;
    }
    P = z.cwiseMax(0.0);
    const double objective = 0.5 * P.dot(W.times(P)) - P.dot(d0);
    const bool progress = objective < objective_before - 1e-14 * std::fabs(objective_before);
    if (progress)
      std::fill(set_aside.begin(), set_aside.end(), 0);
    else if (one_at_a_time)
      set_aside[overlapping[0]] = 1;
    one_at_a_time = !progress;
  }
  return result;
}

}  // namespace fibrecheck
