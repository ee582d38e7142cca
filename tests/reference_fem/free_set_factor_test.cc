// The free set's factor, modified a variable at a time, against dense solves of W_FF.
#include "free_set_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace fibrecheck {
namespace {

/// A sparse symmetric positive definite W: a banded B·Bᵀ plus a little of the identity, as
/// contacts couple only through the fibres they share.
Eigen::SparseMatrix<double> banded_compliance(int n, std::mt19937& random) {
  std::normal_distribution<double> gauss;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - 3); j <= i; ++j) B(i, j) = gauss(random);
  const Eigen::MatrixXd W = B * B.transpose() + 0.05 * Eigen::MatrixXd::Identity(n, n);
  return W.sparseView();
}

Eigen::VectorXd dense_answer(const Eigen::MatrixXd& W, const std::vector<char>& free,
                             const Eigen::VectorXd& b) {
  std::vector<int> index;
  for (int i = 0; i < static_cast<int>(free.size()); ++i)
    if (free[i]) index.push_back(i);
  const int m = static_cast<int>(index.size());
  Eigen::MatrixXd A(m, m);
  Eigen::VectorXd c(m);
  for (int a = 0; a < m; ++a) {
    c[a] = b[index[a]];
    for (int k = 0; k < m; ++k) A(a, k) = W(index[a], index[k]);
  }
  const Eigen::VectorXd y = A.llt().solve(c);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  for (int a = 0; a < m; ++a) x[index[a]] = y[a];
  return x;
}

// A walk of free sets, each one or two variables away from the last (as an active set's), solved
// with one factorisation and modifications after it: every answer as the dense solve's, within
// round-off times W_FF's condition (at most 1e4 here), and zero outside the set.
TEST(FreeSetFactor, ModifiedFactorSolvesEveryFreeSetOfAWalk) {
  std::mt19937 random(11);
  std::normal_distribution<double> gauss;
  const int n = 60;
  const Eigen::SparseMatrix<double> W = banded_compliance(n, random);
  const Eigen::MatrixXd dense(W);
  FreeSetFactor factor(W);
  std::vector<char> free(n, 0);
  for (int i = 0; i < n; i += 2) free[i] = 1;
  std::uniform_int_distribution<int> pick(0, n - 1);
  for (int walk = 0; walk < 200; ++walk) {
    if (walk > 0)
      for (int change = 0; change < 1 + walk % 2; ++change) {
        const int i = pick(random);
        free[i] = !free[i];
      }
    Eigen::VectorXd b(n), x;
    for (int i = 0; i < n; ++i) b[i] = gauss(random);
    ASSERT_TRUE(factor.solve(free, b, x)) << "walk " << walk;
    const Eigen::VectorXd exact = dense_answer(dense, free, b);
    EXPECT_LT((x - exact).norm(), 1e-10 * (1.0 + exact.norm())) << "walk " << walk;
  }
  EXPECT_EQ(factor.factorisations(), 1);
  EXPECT_GE(factor.modifications(), 200);
}

// An unjudged answer is the factor's as it stands; `answers` judges it afterwards: the answer of a
// walk's set meets its equations, and the same answer moved by a part in a million does not.
TEST(FreeSetFactor, JudgesAnUnjudgedAnswerByItsResidual) {
  std::mt19937 random(5);
  std::normal_distribution<double> gauss;
  const int n = 40;
  const Eigen::SparseMatrix<double> W = banded_compliance(n, random);
  FreeSetFactor factor(W);
  std::vector<char> free(n, 0);
  for (int i = 0; i < n; i += 3) free[i] = 1;
  Eigen::VectorXd b(n), x;
  for (int i = 0; i < n; ++i) b[i] = gauss(random);
  ASSERT_TRUE(factor.solve(free, b, x));
  free[1] = 1;
  ASSERT_TRUE(factor.solve(free, b, x, false));
  EXPECT_TRUE(factor.answers(free, b, x));
  EXPECT_LT((x - dense_answer(Eigen::MatrixXd(W), free, b)).norm(), 1e-10 * (1.0 + x.norm()));
  x[1] *= 1.0 + 1e-6;
  EXPECT_FALSE(factor.answers(free, b, x));
}

// Two free variables that constrain the same motion (equal rows of W): W_FF is singular, and the
// regularised answer closes the consistent equations all the same, the two sharing alike; with one
// of them held the other two are solved exactly.
TEST(FreeSetFactor, ClosesASingularFreeSetByItsRegularisation) {
  Eigen::MatrixXd dense(3, 3);
  dense << 2.0, 2.0, 0.5, 2.0, 2.0, 0.5, 0.5, 0.5, 1.0;
  const Eigen::SparseMatrix<double> W = dense.sparseView();
  FreeSetFactor factor(W);
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, 1.0, 1.0);
  Eigen::VectorXd x;
  ASSERT_TRUE(factor.solve({1, 1, 1}, b, x));
  EXPECT_LT((dense * x - b).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(x[0], x[1], 1e-9);
  ASSERT_TRUE(factor.solve({1, 0, 1}, b, x));
  EXPECT_NEAR(x[0], 1.0 / 3.5, 1e-14);
  EXPECT_EQ(x[1], 0.0);
  EXPECT_NEAR(x[2], 1.5 / 1.75, 1e-14);
}

}  // namespace
}  // namespace fibrecheck
