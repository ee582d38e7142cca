// The Tresca fixed point where it crawls: Newton's method on Coulomb's law finishes it.
#include "tresca_fixed_point.h"

#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <cmath>

namespace fibrecheck {
namespace {

/// One contact whose friction presses it on: w = q − W·r with r = (P, F), W = [1 b; b 5],
/// b = −0.95/μ, q = (1, 20), μ = 0.5. It slips with F = μP, so the normal equation reads
/// 1 − P − bμP = 0: P = 1/(1 − 0.95) = 20, F = 10, and the slip w_t = 20 + 1.9·20 − 5·10 = 8 ≥ 0
/// along F. (Sticking would need |F| ≤ μP at w_t = 0: F = 15.76 > μP = 15.47, so it slips.) The
/// radius map is g ← μP(g) = 0.5 + 0.95·g: the plain fixed point gains a factor 0.95 an update,
/// some 500 updates to the reference's tolerance.
FrictionalProblem self_loading_contact() {
  const double mu = 0.5, b = -0.95 / mu;
  FrictionalProblem p;
  Eigen::MatrixXd W(2, 2);
  W << 1.0, b, b, 5.0;
  p.W = W.sparseView();
  p.q = Eigen::Vector2d(1.0, 20.0);
  p.offset = {0, 2};
  p.mu = mu;
  p.excluded = {0};
  return p;
}

/// The contact's fixed point from the frictionless answer (P = 1, F = 0) within `updates` updates.
TrescaSolve solve_within(double tolerance, int updates, Eigen::VectorXd& r) {
  FrictionalProblem problem = self_loading_contact();
  TrescaOptions options;
  options.threshold = 1e-12;
  options.tolerance = tolerance;
  options.max_updates = updates;
  r = Eigen::Vector2d(1.0, 0.0);
  return tresca_fixed_point(problem, options, r);
}

TEST(TrescaFixedPoint, ACrawlingFixedPointIsFinishedByNewtonOnCoulombsLaw) {
  Eigen::VectorXd r;
  const TrescaSolve solved = solve_within(1e-9, 30, r);
  EXPECT_TRUE(solved.settled) << solved.trouble;
  EXPECT_TRUE(solved.finished_by_newton);
  EXPECT_EQ(solved.updates, 30);
  EXPECT_GT(solved.newton_steps, 0);
  EXPECT_NEAR(r[0], 20.0, 1e-9);
  EXPECT_NEAR(r[1], 10.0, 1e-9);
}

// With updates enough, the fixed point gets there by itself and Newton has nothing to do.
TEST(TrescaFixedPoint, ItsOwnUpdatesSettleWhereTheyHaveTheTime) {
  Eigen::VectorXd r;
  const TrescaSolve solved = solve_within(1e-6, 2000, r);
  EXPECT_TRUE(solved.settled) << solved.trouble;
  EXPECT_FALSE(solved.finished_by_newton);
  EXPECT_GT(solved.updates, 100);
  EXPECT_NEAR(r[0], 20.0, 1e-6);
  EXPECT_NEAR(r[1], 10.0, 1e-6);
}

}  // namespace
}  // namespace fibrecheck

namespace fibrecheck {
namespace {

// One contact entered twice, as two contacts that constrain the same motion (a singular W, solved
// regularised): only the sums are determined, P1 + P2 = 1 and, slipping (slip 10 − (F1 + F2) > 0),
// F1 + F2 = μ(P1 + P2) = 0.5. The radii settle to the floor the regularised solves leave, which
// the answer reports, above the 1e-12 mm aimed at, and each contact keeps its friction in its
// disk.
TEST(TrescaFixedPoint, ASingularStickingSetSettlesToItsRoundOffFloorAndSaysSo) {
  FrictionalProblem problem;
  Eigen::Matrix4d W;
  W << 1, 0, 1, 0,  //
      0, 1, 0, 1,  //
      1, 0, 1, 0,  //
      0, 1, 0, 1;
  problem.W = W.sparseView();
  problem.q = Eigen::Vector4d(1.0, 10.0, 1.0, 10.0);
  problem.offset = {0, 2, 4};
  problem.mu = 0.5;
  problem.excluded = {0, 0};
  TrescaOptions options;
  options.threshold = 1e-12;
  options.tolerance = 1e-9;
  Eigen::VectorXd r = Eigen::Vector4d(0.5, 0.0, 0.5, 0.0);
  const TrescaSolve solved = tresca_fixed_point(problem, options, r);
  ASSERT_TRUE(solved.settled) << solved.trouble;
  EXPECT_NEAR(r[0] + r[2], 1.0, 1e-6);
  EXPECT_NEAR(r[1] + r[3], 0.5, 1e-6);
  EXPECT_LE(std::fabs(r[1]), problem.mu * r[0] + 1e-6);
  EXPECT_LE(std::fabs(r[3]), problem.mu * r[2] + 1e-6);
  EXPECT_GT(solved.settled_to, solved.aimed);
  EXPECT_LE(solved.settled_to, 1e-5);
}

}  // namespace
}  // namespace fibrecheck
