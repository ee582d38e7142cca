// The implicit reference meets the closed forms of DESIGN §7 exactly where its elements are
// nodally exact (point contacts), and agrees with the converged iterative solver on the same
// slices.
#include "reference_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "iterative_solver.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

using testing::bending_stiffness;
using testing::compliance;

double force_between(const Result& r, const std::string& a, const std::string& b) {
  for (const ContactResult& c : r.contacts)
    if ((c.fibres[0] == a && c.fibres[1] == b) || (c.fibres[0] == b && c.fibres[1] == a))
      return c.total_force;
  return 0.0;
}

TEST(ReferenceSolver, CrossingForceIsOverlapOverSummedCompliances) {
  struct Case {
    double sa, sb, ra, rb, ea, eb;
  };
  for (const Case& k :
       {Case{0.5, 0.5, 0.01, 0.01, 80000, 80000}, Case{0.3, 0.7, 0.01, 0.01, 80000, 80000},
        Case{0.15, 0.42, 0.012, 0.008, 230000, 72000}}) {
    const double overlap = 1e-3;
    const Scene s = testing::crossing(k.sa, k.sb, overlap, k.ra, k.rb, k.ea, k.eb);
    const double C = compliance(k.sa, 1.0, bending_stiffness(k.ra, k.ea)) +
                     compliance(k.sb, 1.0, bending_stiffness(k.rb, k.eb));
    const Result r = solve_reference(s);
    ASSERT_EQ(r.status, "converged") << r.message;
    EXPECT_EQ(r.solver, "fem");
    EXPECT_NEAR(force_between(r, "A", "B"), overlap / C, 1e-8 * overlap / C)
        << k.sa << ", " << k.sb;
    EXPECT_LT(std::fabs(r.max_overlap), 1e-12);
  }
}

TEST(ReferenceSolver, CompactionTestCaseIsExact) {
  const Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/compaction_test.json");
  const Result r = solve_reference(s);
  ASSERT_EQ(r.status, "converged") << r.message;
  const double EI = bending_stiffness(0.01, 80000);
  const double v = 2 * 0.01 - 0.0195;
  EXPECT_NEAR(force_between(r, "A1", "S1"), v / compliance(0.5, 1.0, EI),
              1e-8 * v / compliance(0.5, 1.0, EI));
  EXPECT_NEAR(force_between(r, "B2", "S2"), v / compliance(1.0 / 6, 1.0, EI),
              1e-8 * v / compliance(1.0 / 6, 1.0, EI));
  EXPECT_EQ(r.walls.size(), 4u);
}

// Four fibres across one: the exact active set by enumeration, as for the iterative solver.
TEST(ReferenceSolver, SmallLcpMatchesEnumeration) {
  using testing::fibre;
  Scene s;
  const double r = 0.01, E = 80000, xs[3] = {0.2, 0.45, 0.8}, overlaps[3] = {2e-3, -1e-4, 1.5e-3};
  s.fibres.push_back(fibre("M", {0, 0, 0}, {1, 0, 0}, r, E));
  for (int i = 0; i < 3; ++i)
    s.fibres.push_back(fibre("C" + std::to_string(i), {xs[i], -0.5, 2 * r - overlaps[i]},
                             {xs[i], 0.5, 2 * r - overlaps[i]}, r, E * (1 + i)));
  const Result res = solve_reference(s);
  ASSERT_EQ(res.status, "converged") << res.message;
  const double EI = bending_stiffness(r, E);
  Eigen::Matrix3d W;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W(i, j) = testing::unit_load_deflection(xs[i], xs[j], EI);
      if (i == j) W(i, j) += compliance(0.5, 1.0, bending_stiffness(r, E * (1 + i)));
    }
  // C1 stays clear; C0 and C2 push: solve the 2×2 system of the active pair.
  Eigen::Matrix2d Waa;
  Waa << W(0, 0), W(0, 2), W(2, 0), W(2, 2);
  const Eigen::Vector2d P = Waa.ldlt().solve(Eigen::Vector2d(overlaps[0], overlaps[2]));
  EXPECT_NEAR(force_between(res, "M", "C0"), P[0], 1e-8 * P[0]);
  EXPECT_NEAR(force_between(res, "M", "C2"), P[1], 1e-8 * P[1]);
  EXPECT_EQ(force_between(res, "M", "C1"), 0.0);
  EXPECT_LT(overlaps[1] - (W(1, 0) * P[0] + W(1, 2) * P[1]), 0.0);  // C1 really stays clear
}

// Same slices, same line contact: the reference and the converged iterative solver give the same
// deflections; the line force is the closed form within the slices' discretisation error.
TEST(ReferenceSolver, ParallelFibresOnSlicesAgreeWithTheIterativeSolver) {
  const double q = 1e-4;
  const Scene s = testing::parallel(q, 40);
  const Result fem = solve_reference(s);
  ASSERT_EQ(fem.status, "converged") << fem.message;
  const Result it = solve_iteratively(s, SolverOptions::from_scene(s));
  ASSERT_EQ(it.status, "converged");
  double largest = 0.0, difference = 0.0;
  for (std::size_t f = 0; f < 2; ++f)
    for (std::size_t j = 0; j < fem.fibres[f].displacement.size(); ++j) {
      largest = std::max(largest, fem.fibres[f].displacement[j].norm());
      difference = std::max(difference,
                            (fem.fibres[f].displacement[j] - it.fibres[f].displacement[j]).norm());
    }
  EXPECT_LT(difference, 1e-6 * largest);
  const double EIa = bending_stiffness(0.01, 80000), EIb = bending_stiffness(0.008, 70000);
  EXPECT_NEAR(force_between(fem, "A", "B"), q * EIb / (EIa + EIb), 0.02 * q * EIb / (EIa + EIb));
}

}  // namespace
}  // namespace fibrecheck
