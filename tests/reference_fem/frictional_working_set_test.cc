// Coulomb's law on a working set of contacts gives the answer of the whole problem, including where
// friction closes a contact that was open at the start.
#include "frictional_working_set.h"

#include <gtest/gtest.h>

#include <Eigen/Sparse>

namespace fibrecheck {
namespace {

/// Two contacts with one tangent each, r = (P1, F1, P2, F2), μ = 0.5. Contact 1 overlaps by 1 and
/// is driven to slip (q_t = 10); its friction F1 closes contact 2 (open by 0.1) through W(P2, F1) =
/// −0.4. Contact 1 slips: P1 = 1 (w_n = 1 − P1), F1 = μP1 = 0.5; contact 2 then pushes with
/// P2 = −0.1 + 0.4·F1 = 0.1 and sticks at F2 = 0; contact 1's slip 10 − F1 + 0.4·P2 = 9.54 points
/// along F1, as slipping needs. W is positive definite (eigenvalues 1, 1, 0.6, 1.4).
FrictionalProblem friction_closing_a_contact() {
  FrictionalProblem p;
  Eigen::Matrix4d W;
  W << 1, 0, 0, 0,    //
      0, 1, -0.4, 0,  //
      0, -0.4, 1, 0,  //
      0, 0, 0, 1;
  p.W = W.sparseView();
  p.q = Eigen::Vector4d(1.0, 10.0, -0.1, 0.0);
  p.offset = {0, 2, 4};
  p.mu = 0.5;
  p.excluded = {0, 0};
  return p;
}

TEST(FrictionalWorkingSet, AContactFrictionClosesJoinsAndTheAnswerIsTheWholeProblems) {
  const FrictionalProblem problem = friction_closing_a_contact();
  TrescaOptions options;
  options.threshold = 1e-12;
  options.tolerance = 1e-9;
  // The frictionless answer: contact 1 alone pushes, so the working set starts without contact 2.
  Eigen::VectorXd r = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
  const AssembledCompliance W(problem.W);
  const TrescaSolve solved = tresca_on_working_set(W, problem, options, r);
  ASSERT_TRUE(solved.settled) << solved.trouble;
  EXPECT_NEAR(r[0], 1.0, 1e-9);
  EXPECT_NEAR(r[1], 0.5, 1e-9);
  EXPECT_NEAR(r[2], 0.1, 1e-9);
  EXPECT_NEAR(r[3], 0.0, 1e-12);
  // The fixed point on the whole problem gives the same.
  FrictionalProblem whole = problem;
  Eigen::VectorXd r_whole = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
  ASSERT_TRUE(tresca_fixed_point(whole, options, r_whole).settled);
  EXPECT_LE((r - r_whole).cwiseAbs().maxCoeff(), 1e-9);
}

// A contact nothing can move (excluded) never joins, however much the answer overlaps it.
TEST(FrictionalWorkingSet, AnExcludedContactNeverJoins) {
  FrictionalProblem problem = friction_closing_a_contact();
  problem.excluded = {0, 1};
  TrescaOptions options;
  options.threshold = 1e-12;
  options.tolerance = 1e-9;
  Eigen::VectorXd r = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
  const AssembledCompliance W(problem.W);
  ASSERT_TRUE(tresca_on_working_set(W, problem, options, r).settled);
  EXPECT_NEAR(r[0], 1.0, 1e-9);
  EXPECT_NEAR(r[1], 0.5, 1e-9);
  EXPECT_EQ(r[2], 0.0);
  EXPECT_EQ(r[3], 0.0);
}

}  // namespace
}  // namespace fibrecheck
