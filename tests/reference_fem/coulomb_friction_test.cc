// Coulomb friction through the reference: the same closed forms as the iterative solver
// (friction_ground_truths.h), solved exactly per load step.
#include <gtest/gtest.h>

#include "friction_ground_truths.h"
#include "reference_solver.h"

namespace fibrecheck {
namespace {

Result solve(const Scene& scene) {
  validate_scene(scene);
  return solve_reference(scene);
}

// Exact to the round-off of the finite elements.
constexpr double kTolerance = 1e-9;

TEST(ReferenceFriction, CrossingSticksBelowMuNAndSlipsAbove) {
  testing::check_crossing_stick_and_slip(solve, kTolerance);
}

TEST(ReferenceFriction, ZeroMuIsFrictionless) {
  testing::check_zero_friction(solve, kTolerance);
}

TEST(ReferenceFriction, HugeMuIsBonded) {
  testing::check_bonded_limit(solve, kTolerance);
}

TEST(ReferenceFriction, ParallelFibresMoveTogetherOrSlipWithMuTimesTheLineForce) {
  testing::check_parallel_shear(solve, kTolerance);
}

TEST(ReferenceFriction, UnloadingLeavesTheHysteresisWidthTwoMuN) {
  testing::check_hysteresis(solve, kTolerance);
}

TEST(ReferenceFriction, TheOrderOfLoadsMatters) {
  testing::check_path_dependence(solve, kTolerance);
}

// Coulomb's law holds at every point to round-off, and the residuals say so.
TEST(ReferenceFriction, ReportsStickSlipAndConeResiduals) {
  const testing::CrossingFigures x = testing::crossing_figures();
  for (double ratio : {0.5, 2.0}) {
    const Result r = solve(testing::sheared_crossing(ratio * 0.3 * x.N, 0.3));
    ASSERT_TRUE(r.friction.has_value());
    EXPECT_LT(r.friction->stick_residual, 1e-15);
    EXPECT_LT(r.friction->slip_residual, 1e-15);
    EXPECT_LT(r.friction->cone_residual, 1e-18);
    EXPECT_EQ(r.friction->sticking + r.friction->slipping, 1);
  }
}

}  // namespace
}  // namespace fibrecheck
