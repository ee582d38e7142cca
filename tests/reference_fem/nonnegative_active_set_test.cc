// The frictionless active sets against the answer found by enumerating every set.
#include "nonnegative_active_set.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <random>

#include "primal_dual_active_set.h"

namespace fibrecheck {
namespace {

/// The solution of the LCP P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 (W positive definite, so it is unique)
/// found by trying every pushing set (2ⁿ of them); contacts in `excluded` never push.
Eigen::VectorXd enumerate(const Eigen::MatrixXd& W, const Eigen::VectorXd& d0,
                          const std::vector<char>& excluded) {
  const int n = static_cast<int>(d0.size());
  for (int code = 0; code < (1 << n); ++code) {
    std::vector<int> set;
    bool possible = true;
    for (int i = 0; i < n; ++i)
      if (code & (1 << i)) {
        set.push_back(i);
        possible &= !excluded[i];
      }
    if (!possible) continue;
    Eigen::VectorXd P = Eigen::VectorXd::Zero(n);
    const int m = static_cast<int>(set.size());
    if (m > 0) {
      Eigen::MatrixXd A(m, m);
      Eigen::VectorXd b(m);
      for (int a = 0; a < m; ++a) {
        b[a] = d0[set[a]];
        for (int c = 0; c < m; ++c) A(a, c) = W(set[a], set[c]);
      }
      const Eigen::VectorXd x = A.ldlt().solve(b);
      for (int a = 0; a < m; ++a) P[set[a]] = x[a];
    }
    const Eigen::VectorXd d = d0 - W * P;
    bool ok = true;
    for (int i = 0; i < n && ok; ++i) {
      if (P[i] < -1e-12) ok = false;
      if (!excluded[i] && d[i] > 1e-12) ok = false;
    }
    if (ok) return P;
  }
  return Eigen::VectorXd();
}

TEST(NonnegativeActiveSet, MatchesEnumerationOnRandomProblems) {
  std::mt19937 random(11);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 8;
    Eigen::MatrixXd B(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) B(i, j) = gauss(random);
    const Eigen::MatrixXd W = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd d0(n);
    std::vector<char> excluded(n, 0), pushing(n, 0);
    for (int i = 0; i < n; ++i) {
      d0[i] = gauss(random);
      excluded[i] = trial % 3 == 0 && i == 5;
      pushing[i] = trial % 2 == 0 && i % 3 == 0;  // a first guess, right or wrong
    }
    const Eigen::SparseMatrix<double> S = W.sparseView();
    Eigen::VectorXd P;
    const ActiveSetSolve solve = nonnegative_active_set(S, d0, 1e-13, excluded, 1000, P, pushing);
    ASSERT_TRUE(solve.solved) << "trial " << trial;
    EXPECT_FALSE(solve.singular) << "trial " << trial;
    const Eigen::VectorXd exact = enumerate(W, d0, excluded);
    ASSERT_EQ(exact.size(), n) << "trial " << trial;
    EXPECT_LT((P - exact).norm(), 1e-10 * (1.0 + exact.norm())) << "trial " << trial;
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(pushing[i] != 0, P[i] > 0.0) << "trial " << trial << ", contact " << i;
      if (excluded[i]) {
        EXPECT_EQ(P[i], 0.0) << "trial " << trial;
      }
    }
  }
}

// The primal-dual active set: on an M-matrix W (a positive diagonal, non-positive entries off it,
// diagonally dominant) it converges from any set, to the enumerated answer; on general positive
// definite W it may cycle, and then says so and leaves a set of pushing contacts from which the
// other method finishes with the enumerated answer.
TEST(PrimalDualActiveSet, MatchesEnumerationOrHandsOver) {
  std::mt19937 random(12);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  int unsolved_general = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 8;
    const bool m_matrix = trial % 2 == 0;
    Eigen::MatrixXd W(n, n);
    if (m_matrix) {
      W.setZero();
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < i; ++j) W(i, j) = W(j, i) = -uniform(random);
      for (int i = 0; i < n; ++i) W(i, i) = 0.1 - (W.row(i).sum() - W(i, i));
    } else {
      Eigen::MatrixXd B(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) B(i, j) = gauss(random);
      W = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    }
    Eigen::VectorXd d0(n);
    std::vector<char> excluded(n, 0), pushing(n, 0);
    for (int i = 0; i < n; ++i) {
      d0[i] = gauss(random);
      excluded[i] = trial % 3 == 0 && i == 5;
      pushing[i] = trial % 4 < 2 && i % 3 == 0;
    }
    const Eigen::SparseMatrix<double> S = W.sparseView();
    const AssembledCompliance compliance(S);
    Eigen::VectorXd P;
    ActiveSetSolve solve = primal_dual_active_set(compliance, d0, 1e-13, excluded, 50, P, pushing);
    if (m_matrix) {
      EXPECT_TRUE(solve.solved) << "trial " << trial;
    }
    if (!solve.solved) {
      ++unsolved_general;
      solve = nonnegative_active_set(compliance, d0, 1e-13, excluded, 1000, P, pushing);
      ASSERT_TRUE(solve.solved) << "trial " << trial;
    }
    const Eigen::VectorXd exact = enumerate(W, d0, excluded);
    ASSERT_EQ(exact.size(), n) << "trial " << trial;
    EXPECT_LT((P - exact).norm(), 1e-10 * (1.0 + exact.norm())) << "trial " << trial;
    for (int i = 0; i < n; ++i) {
      if (excluded[i]) {
        EXPECT_EQ(P[i], 0.0) << "trial " << trial;
      }
    }
  }
  RecordProperty("general_problems_handed_over", unsolved_general);
}

// No contacts: nothing to solve, and solved at once.
TEST(NonnegativeActiveSet, NoContactsIsSolved) {
  const Eigen::SparseMatrix<double> W(0, 0);
  Eigen::VectorXd P;
  std::vector<char> pushing;
  const ActiveSetSolve solve =
      nonnegative_active_set(W, Eigen::VectorXd(), 1e-13, {}, 10, P, pushing);
  EXPECT_TRUE(solve.solved);
  EXPECT_EQ(solve.passes, 0);
  EXPECT_EQ(P.size(), 0);
}


// Pairs of contacts coupled as two slices of one line contact: each pair's first contact pushes,
// and its second, which overlaps as well under the loads alone, would pull once the first pushes.
// The block that adds them together must keep the first: the set then roughly doubles a pass, and
// the method ends in about log2 of the pushing set's size of passes. Dropping a whole block for
// one contact that would pull falls back to one contact a pass (two passes a contact).
TEST(NonnegativeActiveSet, BlockKeepsItsPushingContactsWhenOneWouldPull) {
  const int pairs = 200, n = 2 * pairs;
  const double coupling = 0.9;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd d0(n), exact = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < pairs; ++i) {
    const double scale = std::pow(0.95, i);  // interleaves the pairs in the order of overlaps
    d0[2 * i] = scale;
    d0[2 * i + 1] = 0.85 * scale;  // below coupling × the first's: it would pull
    exact[2 * i] = scale;
    entries.emplace_back(2 * i, 2 * i, 1.0);
    entries.emplace_back(2 * i + 1, 2 * i + 1, 1.0);
    entries.emplace_back(2 * i, 2 * i + 1, coupling);
    entries.emplace_back(2 * i + 1, 2 * i, coupling);
  }
  Eigen::SparseMatrix<double> W(n, n);
  W.setFromTriplets(entries.begin(), entries.end());
  std::vector<char> excluded(n, 0), pushing(n, 0);
  Eigen::VectorXd P;
  const ActiveSetSolve solve = nonnegative_active_set(W, d0, 1e-13, excluded, 10 * n, P, pushing);
  ASSERT_TRUE(solve.solved);
  EXPECT_LT((P - exact).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE(solve.passes, 20) << "log2(" << pairs << ") ≈ 8 doublings";
}

}  // namespace
}  // namespace fibrecheck
