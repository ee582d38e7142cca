// The bounded-variable active set against the answer found by enumerating every set.
#include "bounded_active_set.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <random>

namespace fibrecheck {
namespace {

/// The KKT point of min ½rᵀWr − qᵀr on lo ≤ r ≤ hi found by trying every assignment of the
/// variables to lower bound, upper bound or free (3ⁿ of them).
Eigen::VectorXd enumerate(const Eigen::MatrixXd& W, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int n = static_cast<int>(q.size());
  int total = 1;
  for (int i = 0; i < n; ++i) total *= 3;
  for (int code = 0; code < total; ++code) {
    std::vector<int> state(n);
    bool possible = true;
    for (int i = 0, c = code; i < n; ++i, c /= 3) {
      state[i] = c % 3;  // 0 lo, 1 hi, 2 free
      possible &= !(state[i] == 1 && !std::isfinite(hi[i]));
    }
    if (!possible) continue;
    Eigen::VectorXd r(n);
    std::vector<int> free;
    for (int i = 0; i < n; ++i) {
      r[i] = state[i] == 0 ? lo[i] : hi[i];
      if (state[i] == 2) free.push_back(i);
    }
    if (!free.empty()) {
      const int m = static_cast<int>(free.size());
      Eigen::MatrixXd A(m, m);
      Eigen::VectorXd b(m);
      for (int a = 0; a < m; ++a) {
        b[a] = q[free[a]];
        for (int i = 0; i < n; ++i)
          if (state[i] != 2) b[a] -= W(free[a], i) * r[i];
        for (int c = 0; c < m; ++c) A(a, c) = W(free[a], free[c]);
      }
      const Eigen::VectorXd x = A.ldlt().solve(b);
      for (int a = 0; a < m; ++a) r[free[a]] = x[a];
    }
    const Eigen::VectorXd w = q - W * r;
    bool ok = true;
    for (int i = 0; i < n && ok; ++i) {
      if (r[i] < lo[i] - 1e-12 || r[i] > hi[i] + 1e-12) ok = false;
      if (state[i] == 0 && w[i] > 1e-12) ok = false;
      if (state[i] == 1 && w[i] < -1e-12) ok = false;
    }
    if (ok) return r;
  }
  return Eigen::VectorXd();
}

TEST(BoundedActiveSet, MatchesEnumerationOnRandomBoxes) {
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 6;
    Eigen::MatrixXd B(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) B(i, j) = gauss(random);
    const Eigen::MatrixXd W = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd q(n), lo(n), hi(n);
    for (int i = 0; i < n; ++i) {
      q[i] = gauss(random);
      // Normal-like (0, ∞), friction-like [−g, g], and fixed variables.
      const int kind = i % 3;
      lo[i] = kind == 0 ? 0.0 : (kind == 1 ? -uniform(random) : 0.0);
      hi[i] = kind == 0 ? INFINITY : (kind == 1 ? -lo[i] : (trial % 2 ? 0.0 : uniform(random)));
    }
    const Eigen::SparseMatrix<double> S = W.sparseView();
    Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
    const BoundedSolve solve = bounded_active_set(S, q, lo, hi, 1e-13, 1000, r);
    ASSERT_TRUE(solve.solved) << "trial " << trial;
    const Eigen::VectorXd exact = enumerate(W, q, lo, hi);
    ASSERT_EQ(exact.size(), n) << "trial " << trial;
    EXPECT_LT((r - exact).norm(), 1e-10 * (1.0 + exact.norm())) << "trial " << trial;
  }
}

// The slices of a line contact slipping as one: ten friction variables coupled alike (W = I +
// ½·11ᵀ, q = 10), all free at the start r = 0. The free solve puts each at 10/6, beyond its bound
// 1, and all reach the bound at the same point of the step (3/5 of the way): the answer r = 1
// (where w = q − W·r = 4 points outwards) comes from one factorisation and the check of the empty
// free set, not one factorisation per variable.
TEST(BoundedActiveSet, HoldsTheVariablesThatReachTheirBoundsTogether) {
  const int n = 10;
  const Eigen::MatrixXd W = Eigen::MatrixXd::Identity(n, n) + 0.5 * Eigen::MatrixXd::Ones(n, n);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(n, 10.0);
  const Eigen::VectorXd lo = Eigen::VectorXd::Constant(n, -1.0), hi = -lo;
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  const BoundedSolve solve = bounded_active_set(W.sparseView(), q, lo, hi, 1e-13, 1000, r);
  ASSERT_TRUE(solve.solved);
  EXPECT_EQ(r, hi);
  EXPECT_LE(solve.free_solves, 2);
}

}  // namespace
}  // namespace fibrecheck
