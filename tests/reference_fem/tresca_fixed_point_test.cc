// The Tresca fixed point where it crawls: Newton's method on Coulomb's law finishes it.
#include "tresca_fixed_point.h"

#include <gtest/gtest.h>

#include <Eigen/Sparse>

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
