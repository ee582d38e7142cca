// The slicing estimate against closed forms: two parallel fibres touching along their length
// under a uniform load q on A (fibres of length L = 1 bend together as one beam of stiffness
// EI_A + EI_B): contact line load q·EI_B/(EI_A + EI_B), deflection w(x) = q(x⁴ − 2Lx³ + L³x) /
// (24(EI_A + EI_B)) of both fibres, strain energy ½∫q·w = q²L⁵/(240(EI_A + EI_B)). The estimate of
// the 100-slice run from the 50-slice run must lie within a factor 0.5–3 of its true slicing error
// in every metric (the errors are 2.4e-3 in force and below 1e-8 in deflection and energy, far
// above the runs' iteration errors at an overlap tolerance of 1e-12 mm).
#include "slicing_estimate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "iterative_solver.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

Result solve(const Scene& s) {
  return solve_iteratively(s, SolverOptions::from_scene(s));
}

TEST(SlicingEstimate, ParallelFibresEstimateTheirSlicingErrorWithinAFactorOfThree) {
  const double q = 1e-4;
  const Scene fine_scene = testing::parallel(q, 100), coarse_scene = testing::parallel(q, 50);
  const Result fine = solve(fine_scene), coarse = solve(coarse_scene);
  ASSERT_EQ(fine.status, Status::converged) << fine.message;
  ASSERT_EQ(coarse.status, Status::converged) << coarse.message;
  const SlicingEstimate e = estimate_slicing_error(fine, coarse, 100, 50);

  const double EI =
      testing::bending_stiffness(0.01, 80000) + testing::bending_stiffness(0.008, 70000);
  const double line_force = q * testing::bending_stiffness(0.008, 70000) / EI;
  const double force_error = std::fabs(fine.contacts.at(0).total_force - line_force) / line_force;
  double deflection = 0.0, largest = 0.0;
  for (const FibreResult& f : fine.fibres)
    for (std::size_t j = 0; j < f.displacement.size(); ++j) {
      const double x = static_cast<double>(j) / (f.displacement.size() - 1);
      const double w = q * (std::pow(x, 4) - 2 * std::pow(x, 3) + x) / (24 * EI);
      deflection = std::max(deflection, (f.displacement[j] - Eigen::Vector3d(0, 0, -w)).norm());
      largest = std::max(largest, w);
    }
  const double deflection_error = deflection / largest;
  const double U = q * q / (240 * EI);
  const double energy_error = std::fabs(fine.strain_energy_exact - U) / U;

  for (auto [name, estimate, truth] : {std::tuple{"force", e.force, force_error},
                                       std::tuple{"deflection", e.deflection, deflection_error},
                                       std::tuple{"energy", e.energy, energy_error}}) {
    SCOPED_TRACE(name);
    ASSERT_GT(truth, 1e-10);
    EXPECT_GT(estimate / truth, 0.5) << estimate << " against " << truth;
    EXPECT_LT(estimate / truth, 3.0) << estimate << " against " << truth;
  }
  EXPECT_EQ(e.slices, 100);
  EXPECT_EQ(e.coarse_slices, 50);
  EXPECT_EQ(e.force_order, 1.0);
}

// The check of the orders: 25, 50 and 100 slices of the parallel fibres show the line force's
// first order and the fourth of deflection and energy, within 10 % (the runs are in the asymptotic
// range from 25 slices on: the slice study observes 0.94 and 4.08 between 2 and 128). A check
// that observes other orders says so.
TEST(SlicingEstimate, ThreeRunsOfTheParallelFibresObserveTheAssumedOrders) {
  const double q = 1e-4;
  const Result fine = solve(testing::parallel(q, 100)), coarse = solve(testing::parallel(q, 50)),
               coarser = solve(testing::parallel(q, 25));
  SlicingEstimate e = estimate_slicing_error(fine, coarse, 100, 50);
  observe_slicing_orders(e, fine, coarse, coarser, 25);
  EXPECT_EQ(e.coarser_slices, 25);
  EXPECT_NEAR(e.observed_force_order, 1.0, 0.1);
  EXPECT_NEAR(e.observed_deflection_order, 4.0, 0.4);
  EXPECT_NEAR(e.observed_energy_order, 4.0, 0.4);
  EXPECT_TRUE(slicing_orders_hold(e));
  e.observed_deflection_order = 0.45;  // as on a tow whose touching stretches move with the slices
  EXPECT_FALSE(slicing_orders_hold(e));
}

}  // namespace
}  // namespace fibrecheck
