// Coulomb friction through the iterative solver: the closed forms of DESIGN §7 (written once in
// friction_ground_truths.h), every update rule, and the seed's own friction rule beside it.
#include <gtest/gtest.h>

#include "friction_ground_truths.h"
#include "iterative_solver.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

Result solve_with(const Scene& scene, UpdateRule rule) {
  Scene s = scene;
  s.solver.rule = rule;
  if (rule == UpdateRule::seed) s.solver.c = 0.01;  // below 2/λmax of these scenes
  validate_scene(s);
  return solve_iteratively(s, SolverOptions::from_scene(s));
}

Result solve(const Scene& scene) {
  return solve_with(scene, UpdateRule::accelerated);
}

// The overlap tolerance is 1e-9 mm on the crossings (1e-12 on the parallel fibres): forces and
// shifts within 1e-4 of the closed form.
constexpr double kTolerance = 1e-4;

TEST(CoulombFriction, CrossingSticksBelowMuNAndSlipsAbove) {
  testing::check_crossing_stick_and_slip(solve, kTolerance);
}

TEST(CoulombFriction, EveryRuleProjectsOntoTheCoulombDisk) {
  for (UpdateRule rule : {UpdateRule::seed, UpdateRule::automatic}) {
    SCOPED_TRACE(to_string(rule));
    testing::check_crossing_stick_and_slip([&](const Scene& s) { return solve_with(s, rule); },
                                           kTolerance);
  }
}

TEST(CoulombFriction, ZeroMuIsFrictionless) {
  testing::check_zero_friction(solve, kTolerance);
}

TEST(CoulombFriction, HugeMuIsBonded) {
  testing::check_bonded_limit(solve, kTolerance);
}

TEST(CoulombFriction, ParallelFibresMoveTogetherOrSlipWithMuTimesTheLineForce) {
  testing::check_parallel_shear(solve, kTolerance);
}

TEST(CoulombFriction, UnloadingLeavesTheHysteresisWidthTwoMuN) {
  testing::check_hysteresis(solve, kTolerance);
}

TEST(CoulombFriction, TheOrderOfLoadsMatters) {
  testing::check_path_dependence(solve, kTolerance);
}

// A 19-fibre tow with μ = 0.2 compacted in twelve steps, from F = 0.95 to 0.7.
TowOptions compacted_tow_19() {
  TowOptions tow;
  tow.fibres = 19;
  tow.slices = 20;
  tow.seed = 2;
  tow.volume_fraction = 0.35;
  tow.steps = 12;
  tow.first_compaction = 0.95;
  tow.compaction = 0.7;
  tow.friction = 0.2;
  return tow;
}

// A tow compacted with friction in twelve steps, from first wall contact to Vf ≈ 0.59, in both
// contact geometries: every step converges and its answer satisfies Coulomb's law as the result
// reports it — slips at sticking contacts and slips against the friction of slipping ones below
// t_d, no friction beyond μP — and the contact criterion. Under the deformed geometry this needs
// the friction to turn with its tangent at full size, and the Tresca radii to be judged against
// the disks the inner problem had: otherwise contacts slipping on their circle are taken for
// sticking ones with all their slip, and the run ends without progress. Each step keeps its own
// count of the updates of the Tresca radii and of the normals.
TEST(CoulombFriction, CompactedTowConvergesEveryStepInBothGeometries) {
  const TowOptions tow = compacted_tow_19();
  for (ContactGeometryModel geometry :
       {ContactGeometryModel::deformed, ContactGeometryModel::linearised}) {
    SCOPED_TRACE(to_string(geometry));
    Scene s = generate_tow(tow);
    s.contact.geometry = geometry;
    const Result r = solve(s);
    ASSERT_EQ(r.status, Status::converged) << r.message;
    ASSERT_EQ(r.steps.size(), 12u);
    ASSERT_TRUE(r.friction.has_value());
    const double t = s.overlap_tolerance();
    for (const StepResult& step : r.steps) {
      EXPECT_EQ(step.status, Status::converged);
      EXPECT_LT(step.stick_residual, t) << step.compaction;
      EXPECT_LT(step.slip_residual, t) << step.compaction;
      // A step whose fibres push has set its radii at least once, and under the deformed
      // geometry updated its normals; linearised normals never follow.
      const bool loaded = step.strain_energy > 0.0;
      const bool linearised = geometry == ContactGeometryModel::linearised;
      EXPECT_TRUE(!loaded || step.fixed_point_updates > 0) << step.compaction;
      EXPECT_TRUE(!linearised || step.geometric_updates == 0) << step.compaction;
      EXPECT_TRUE(linearised || !loaded || step.geometric_updates > 0) << step.compaction;
    }
    EXPECT_EQ(r.steps.back().fixed_point_updates, r.friction->fixed_point_updates);
    EXPECT_EQ(r.steps.back().stick_residual, r.friction->stick_residual);
    EXPECT_EQ(r.steps.back().slip_residual, r.friction->slip_residual);
    EXPECT_EQ(r.steps.back().geometric_updates, r.geometric_updates);
    EXPECT_LT(r.max_overlap, t);
    EXPECT_LT(r.gap_force_residual, t);
    EXPECT_LT(r.friction->stick_residual, t);
    EXPECT_LT(r.friction->slip_residual, t);
    double largest = 0.0;
    for (const ContactResult& c : r.contacts) largest = std::max(largest, c.normal_force);
    ASSERT_GT(largest, 0.0);
    EXPECT_GT(r.friction->slipping, 0);
    EXPECT_GT(r.friction->sticking, 0);
    EXPECT_LE(r.friction->cone_residual, 1e-12 * tow.friction * largest);
  }
}

// A frictional run that runs out of iterations says how far Coulomb's law had got — how often
// the Tresca radii were set and the inner problem's residuals — and its progress reports count the
// updates of the radii and of the normals as they happen.
TEST(CoulombFriction, RunningOutSaysWhereTheTrescaRadiiStood) {
  TowOptions tow = compacted_tow_19();
  tow.steps = 0;
  tow.compaction = 0.75;
  const Scene s = generate_tow(tow);
  SolverOptions options = SolverOptions::from_scene(s);
  const Result full = solve_iteratively(s, options);
  ASSERT_EQ(full.status, Status::converged) << full.message;
  ASSERT_GT(full.friction->fixed_point_updates, 2);
  options.max_iterations = full.iterations / 2;
  options.progress_interval_s = 0.0;
  std::vector<IterationProgress> seen;
  options.progress = [&](const IterationProgress& p) { seen.push_back(p); };
  const Result capped = solve_iteratively(s, options);
  ASSERT_EQ(capped.status, Status::max_iterations);
  const std::string set = "the Tresca radii had been set " +
                          std::to_string(capped.friction->fixed_point_updates) + " times";
  EXPECT_NE(capped.message.find(set), std::string::npos) << capped.message;
  EXPECT_NE(capped.message.find("stick residual"), std::string::npos) << capped.message;
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(seen.back().coulomb);
  EXPECT_EQ(seen.front().radius_updates, 0);
  EXPECT_GT(seen.back().radius_updates, 0);
  EXPECT_LE(seen.back().radius_updates, capped.friction->fixed_point_updates);
  EXPECT_LE(seen.back().normal_updates, capped.geometric_updates);
  for (std::size_t k = 1; k < seen.size(); ++k)
    EXPECT_GE(seen[k].radius_updates, seen[k - 1].radius_updates);
}

// A run whose force tolerance made t_d smaller and that then runs out of iterations ends
// `converged`, with a warning, only where its state meets Coulomb's law itself at the scene's t_d.
// Its inner problem, judged against the Tresca radii it was last given, can be settled to 1e-12 mm
// while those radii are still far from μN and contacts inside their disks slip: the 19-fibre tow at
// F = 0.7, 100 slices, linearised, whose estimate asks for t_d = 1e-10 mm, is such a run at 100 000
// iterations, with slips of 7e-3 mm at contacts whose friction is below μN.
TEST(CoulombFriction, RunningOutIsConvergedOnlyWhereCoulombsLawHolds) {
  TowOptions tow = compacted_tow_19();
  tow.steps = 0;
  tow.slices = 100;
  tow.compaction = 0.7;
  Scene s = generate_tow(tow);
  s.contact.geometry = ContactGeometryModel::linearised;
  SolverOptions options = SolverOptions::from_scene(s);
  options.max_iterations = 100000;
  const Result r = solve_iteratively(s, options);
  ASSERT_TRUE(r.friction.has_value());
  const double t = s.overlap_tolerance();
  if (r.status == Status::converged) {
    EXPECT_LT(r.friction->stick_residual, t);
    EXPECT_LT(r.friction->slip_residual, t);
  } else {
    EXPECT_EQ(r.status, Status::max_iterations);
    EXPECT_NE(r.message.find("against muN the stick residual"), std::string::npos) << r.message;
  }
}

// The seed's rule (§4.3.4, Eqs. 4.29–4.33): the previous resultant split on the deformed centres'
// normal, capped. Under a side load below μN the centres' normal turns as B moves, so the rule
// drives the friction to the cap: it never lets the contact stick as Coulomb's law does, and B
// ends where the capped friction leaves it, not at rest.
TEST(SeedFrictionRule, CapsTheKeptResultantButDoesNotStick) {
  const testing::CrossingFigures x = testing::crossing_figures();
  const double mu = 0.3, H = 0.5 * mu * x.N;
  Scene s = testing::sheared_crossing(H, mu);
  s.contact.friction_model = FrictionModel::seed;
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_TRUE(r.friction.has_value());
  EXPECT_EQ(r.friction->model, "seed");
  const ContactResult& c = testing::only_contact(r);
  EXPECT_LE(c.friction_force, mu * c.normal_force * (1 + 1e-12));
  EXPECT_GT(std::fabs(testing::crossing_shift(r)), 1e-3 * H * x.C);
  EXPECT_NE(std::find(r.stages.begin(), r.stages.end(), "friction_seed"), r.stages.end());
}

}  // namespace
}  // namespace fibrecheck
