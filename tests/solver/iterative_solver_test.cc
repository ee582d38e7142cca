// Behaviour of the iterative solver beyond the closed forms: statuses for trouble, the stages a
// scene runs, determinism, the update rules and friction.
#include "iterative_solver.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <string>

#include "test_scenes.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

Result solve(const Scene& scene) {
  return solve_iteratively(scene, SolverOptions::from_scene(scene));
}

bool has_stage(const Result& r, const std::string& stage) {
  return std::find(r.stages.begin(), r.stages.end(), stage) != r.stages.end();
}

/// A generated tow of 19 fibres, 40 slices, compacted in one step.
Scene compacted_tow_19() {
  TowOptions tow;
  tow.fibres = 19;
  tow.slices = 40;
  tow.seed = 5;
  return generate_tow(tow);
}

void expect_finite(const Result& r) {
  EXPECT_TRUE(std::isfinite(r.strain_energy) && std::isfinite(r.strain_energy_exact) &&
              std::isfinite(r.max_overlap));
  for (const FibreResult& f : r.fibres)
    for (const Eigen::Vector3d& u : f.displacement) EXPECT_TRUE(u.allFinite());
  for (const ContactResult& c : r.contacts) EXPECT_TRUE(std::isfinite(c.total_force));
}

// Two fibres whose pinned supports overlap: no force can separate them there.
TEST(IterativeSolver, OverlapAtTwoPinnedSupportsIsUnresolvable) {
  const Result r = solve(testing::overlapping_supports());
  EXPECT_EQ(r.status, Status::unresolvable);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_NE(r.message.find("A and B"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("s = 0"), std::string::npos) << r.message;
  expect_finite(r);
}

// Rule seed with c three times the stability limit 2/λmax(W): P' = P + c·d oscillates (§4.3.2,
// "if c is too large the system will become unstable"); the run must end as diverged, finite.
TEST(IterativeSolver, SeedRuleBeyondTheStabilityLimitIsReportedDiverged) {
  Scene s = testing::crossing(0.5, 0.5, 1e-3);
  const double C = 2 * testing::compliance(0.5, 1.0, testing::bending_stiffness(0.01, 80000));
  s.solver.rule = UpdateRule::seed;
  s.solver.c = 3.0 * 2.0 / C;
  const Result r = solve(s);
  EXPECT_EQ(r.status, Status::diverged);
  // From P = 0 the projected update alternates between P = c·δ (overlap δ(1 − cC) = −5δ, a gap)
  // and P = 0 (overlap δ): a bounded two-cycle, so the monitor sees no progress, not growth.
  EXPECT_EQ(r.criterion, Criterion::oscillation);
  EXPECT_NE(r.message.find("lambda_max"), std::string::npos) << r.message;
  EXPECT_LT(r.iterations, s.solver.max_iterations);
  expect_finite(r);
  // Just below the limit the same rule converges.
  s.solver.c = 0.95 * 2.0 / C;
  EXPECT_EQ(solve(s).status, Status::converged);
}

TEST(IterativeSolver, IterationCapIsReportedAsMaxIterations) {
  Scene s = testing::parallel(1e-4, 50);
  s.solver.max_iterations = 5;
  const Result r = solve(s);
  EXPECT_EQ(r.status, Status::max_iterations);
  EXPECT_EQ(r.criterion, Criterion::max_iterations);
  EXPECT_EQ(r.iterations, 5);
  EXPECT_GT(r.max_overlap, s.overlap_tolerance());
  EXPECT_NE(r.message.find("5 iterations"), std::string::npos);
  expect_finite(r);
}

// Under the deformed contact a run that runs out of iterations says whether its normals had
// settled: the residuals it reports are those along the normals its last problem was solved
// with, and can lie within t_d while every update of the normals left more.
TEST(IterativeSolver, RunningOutOnTheDeformedFibresSaysTheNormalsHadNotSettled) {
  Scene s = compacted_tow_19();
  s.solver.max_iterations = 300;
  const Result deformed = solve(s);
  ASSERT_EQ(deformed.status, Status::max_iterations);
  ASSERT_GT(deformed.geometric_updates, 0);
  EXPECT_NE(deformed.message.find("the normals had not settled: each of the " +
                                  std::to_string(deformed.geometric_updates) + " updates"),
            std::string::npos)
      << deformed.message;
  s.contact.geometry = ContactGeometryModel::linearised;
  const Result linearised = solve(s);
  ASSERT_EQ(linearised.status, Status::max_iterations);
  EXPECT_EQ(linearised.message.find("normals"), std::string::npos) << linearised.message;
}

// A run that meets the scene's t_d but runs out of iterations while t_d was made smaller for a
// force tolerance it cannot reach (1e-13: below what the round-off of a 100-slice line contact
// lets any state have) is converged by the scene's own criterion, and says which tolerance it
// missed; one that runs out before the scene's t_d stays max_iterations.
TEST(IterativeSolver, RunningOutWithinTheScenesToleranceIsConvergedWithAWarning) {
  Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/parallel_fibres.json");
  s.solver.force_tolerance = 0.0;
  const long within = solve(s).iterations;  // the seed's criterion met
  s.solver.force_tolerance = 1e-13;
  s.solver.max_iterations = within + 1000;
  const Result r = solve(s);
  EXPECT_EQ(r.status, Status::converged);
  EXPECT_EQ(r.criterion, Criterion::contact);
  EXPECT_LT(r.max_overlap, s.overlap_tolerance());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("force_tolerance 1e-13 not reached: the iteration ran out"),
            std::string::npos)
      << r.warnings[0];
  s.solver.max_iterations = 100;
  EXPECT_EQ(solve(s).status, Status::max_iterations);
}

// On the deformed fibres a run whose update of the normals once left a state within the scene's
// t_d, and that then runs out of iterations (here right after the force tolerance, 1e-13, sent it
// on from there), ends in the better of that state and its last one judged as an update would
// judge it: converged by the scene's own criterion, with a warning, not max_iterations.
TEST(IterativeSolver, RunningOutOnTheDeformedFibresReturnsToTheBestUpdate) {
  Scene s = compacted_tow_19();
  s.solver.force_tolerance = 0.0;
  const Result met = solve(s);
  ASSERT_EQ(met.status, Status::converged) << met.message;
  s.solver.force_tolerance = 1e-13;
  s.solver.max_iterations = met.iterations + 1;
  const Result r = solve(s);
  EXPECT_EQ(r.status, Status::converged) << r.message;
  EXPECT_EQ(r.criterion, Criterion::contact);
  const double t = s.overlap_tolerance();
  EXPECT_LT(r.max_overlap, t);
  EXPECT_LT(r.gap_force_residual, t);
  EXPECT_LT(r.deformed_test.gap_where_pushing, t);
  EXPECT_LT(r.deformed_test.overlap_where_free, t);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("force_tolerance 1e-13 not shown to be reached"), std::string::npos)
      << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("ends in the best state an update of the normals left"),
            std::string::npos)
      << r.warnings[0];
  expect_finite(r);
}

// The energy criterion of §4.3.6 ends a slow run when the last n_i energies agree within t_U.
TEST(IterativeSolver, EnergyCriterionStopsWhenEnergySettles) {
  Scene s = testing::parallel(1e-4, 50);
  s.solver.rule = UpdateRule::automatic;
  s.solver.energy_tolerance = 1e-15;
  s.solver.energy_window = 20;
  const Result r = solve(s);
  EXPECT_EQ(r.status, Status::converged);
  EXPECT_EQ(r.criterion, Criterion::energy);
  EXPECT_TRUE(has_stage(r, "energy_criterion"));
  ASSERT_GE(r.history.size(), 2u);
  // The answer it stops at. The energy is stationary at the solution, so it settles long before
  // the forces do: within 1e-5 of the exact U = q²L⁵/(240(EI_A + EI_B)) (DESIGN §7) while the line
  // force is still a few per cent from q·EI_B/(EI_A + EI_B) (measured: 5.6 % at t_U = 1e-15 N·mm
  // after 1 760 iterations).
  const double EIa = testing::bending_stiffness(0.01, 80000);
  const double EIb = testing::bending_stiffness(0.008, 70000);
  const double q = 1e-4, line_force = q * EIb / (EIa + EIb);
  const double energy = q * q / (240.0 * (EIa + EIb));
  EXPECT_NEAR(r.strain_energy_exact, energy, 1e-5 * energy);
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_NEAR(r.contacts[0].total_force, line_force, 0.1 * line_force);
  EXPECT_GT(std::fabs(r.contacts[0].total_force - line_force), 1e-2 * line_force);
}

// Each scene runs only the stages it needs (DESIGN §2).
TEST(IterativeSolver, ScenesRunOnlyTheStagesTheyNeed) {
  const Result crossing = solve(testing::crossing(0.5, 0.5, 1e-3));
  EXPECT_TRUE(has_stage(crossing, "point_contacts"));
  EXPECT_FALSE(has_stage(crossing, "slices"));
  EXPECT_FALSE(has_stage(crossing, "broad_phase"));
  EXPECT_FALSE(has_stage(crossing, "walls"));
  EXPECT_FALSE(has_stage(crossing, "friction_coulomb"));
  const Result parallel = solve(testing::parallel(1e-4, 20));
  EXPECT_TRUE(has_stage(parallel, "slices"));
  EXPECT_FALSE(has_stage(parallel, "point_contacts"));
  Scene with_friction = testing::crossing(0.5, 0.5, 1e-3);
  with_friction.contact.friction = 0.3;
  EXPECT_TRUE(has_stage(solve(with_friction), "friction_coulomb"));
  TowOptions tow;
  tow.fibres = 7;
  tow.slices = 20;
  const Result t = solve(generate_tow(tow));
  EXPECT_TRUE(has_stage(t, "broad_phase"));
  EXPECT_TRUE(has_stage(t, "walls"));
  EXPECT_TRUE(has_stage(t, "slices"));
  EXPECT_FALSE(has_stage(t, "point_contacts"));
}

TEST(IterativeSolver, RunsAreDeterministic) {
  TowOptions tow;
  tow.fibres = 19;
  tow.slices = 30;
  tow.seed = 4;
  Scene s = generate_tow(tow);
  s.solver.rule = UpdateRule::accelerated;
  const Result first = solve(s), second = solve(s);
  ASSERT_EQ(first.status, Status::converged);
  EXPECT_EQ(first.iterations, second.iterations);
  EXPECT_EQ(first.strain_energy_exact, second.strain_energy_exact);
  ASSERT_EQ(first.contacts.size(), second.contacts.size());
  for (std::size_t i = 0; i < first.contacts.size(); ++i)
    EXPECT_EQ(first.contacts[i].total_force, second.contacts[i].total_force);
}

// A compacted tow ends with every contact just touching: no overlap above t_d, no force across a
// gap above t_d, forces balanced against the walls (no external load: the walls' reactions and the
// supports carry the compaction).
TEST(IterativeSolver, CompactedTowEndsJustTouching) {
  Scene s = compacted_tow_19();
  s.solver.rule = UpdateRule::accelerated;
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  EXPECT_LT(r.max_overlap, s.overlap_tolerance());
  EXPECT_LT(r.gap_force_residual, s.overlap_tolerance());
  EXPECT_GT(r.contacts.size(), 3u);
  for (const ContactResult& c : r.contacts) EXPECT_GT(c.total_force, 0.0);
  expect_finite(r);
  // The accelerated and the plain rule reach the same equilibrium of the linearised contact (one
  // fixed quadratic programme, one answer).
  s.contact.geometry = ContactGeometryModel::linearised;
  const Result linearised = solve(s);
  ASSERT_EQ(linearised.status, Status::converged) << linearised.message;
  s.solver.rule = UpdateRule::automatic;
  s.solver.max_iterations = 400000;
  const Result plain = solve(s);
  ASSERT_EQ(plain.status, Status::converged) << plain.message;
  EXPECT_NEAR(plain.strain_energy_exact, linearised.strain_energy_exact,
              1e-3 * linearised.strain_energy_exact);
}

/// Each pair's resultant, by its fibres and kind.
std::map<std::string, double> pair_forces(const Result& r) {
  std::map<std::string, double> forces;
  for (const ContactResult& c : r.contacts)
    forces[c.fibres[0] + "|" + c.fibres[1] + "|" + c.kind] = c.total_force;
  return forces;
}

// Under the deformed contact an update of the normals that leaves the sequence of linearised
// problems within a hundred t_d hands the state to the error estimate's answer, the linearised
// problem solved exactly with its normals followed. It must be the answer the sequence alone
// reaches: both runs pass the seed's test in the deformed configuration, and their pair forces
// differ by no more than the two runs' own estimated force errors together (each the largest
// |ΔF|/F of a pair against the exact answer, so the difference of two answers is within their sum).
TEST(IterativeSolver, SettlingTheNormalsExactlyReachesTheSequencesAnswer) {
  TowOptions tow;
  tow.fibres = 30;
  tow.slices = 40;
  tow.seed = 2;
  tow.compaction = 0.8;
  Scene s = generate_tow(tow);
  s.solver.force_tolerance = 0.0;  // the estimate's answers then only settle the normals
  SolverOptions options = SolverOptions::from_scene(s);
  const Result settled = solve_iteratively(s, options);
  options.exact_answer_below = 0.0;
  const Result sequence = solve_iteratively(s, options);
  ASSERT_EQ(settled.status, Status::converged) << settled.message;
  ASSERT_EQ(sequence.status, Status::converged) << sequence.message;
  EXPECT_GT(settled.exact_answers, 0);
  EXPECT_EQ(sequence.exact_answers, 0);
  const double t = s.overlap_tolerance();
  for (const Result* r : {&settled, &sequence}) {
    EXPECT_LT(r->deformed_test.gap_where_pushing, t);
    EXPECT_LT(r->deformed_test.overlap_where_free, t);
  }
  ASSERT_TRUE(settled.error_estimate && sequence.error_estimate);
  const double allowed = settled.error_estimate->force + sequence.error_estimate->force;
  auto a = pair_forces(settled), b = pair_forces(sequence);
  for (const auto& [pair, force] : a) b.emplace(pair, 0.0);
  for (const auto& [pair, force] : b) a.emplace(pair, 0.0);
  double largest = 0.0;
  for (const auto& [pair, force] : b) largest = std::max(largest, force);
  for (const auto& [pair, force] : a) {
    const double there = b.at(pair);
    EXPECT_LE(std::fabs(force - there), allowed * std::max(force, there) + 1e-9 * largest) << pair;
  }
}

TEST(IterativeSolver, SolverOptionsValidation) {
  SolverOptions valid;
  valid.overlap_tolerance = 1e-7;
  std::string why;
  EXPECT_TRUE(valid.is_valid(&why)) << why;
  // Each broken option on its own, and the reason it is named by.
  const std::pair<std::function<void(SolverOptions&)>, std::string> broken[] = {
      {[](SolverOptions& o) { o.rule = UpdateRule::seed; }, "rule seed needs the step c"},
      {[](SolverOptions& o) { o.c = -0.1; }, "c must be positive and finite"},
      {[](SolverOptions& o) { o.c = INFINITY; }, "c must be positive and finite"},
      {[](SolverOptions& o) { o.overlap_tolerance = 0.0; }, "overlap tolerance must be positive"},
      {[](SolverOptions& o) { o.energy_tolerance = -1.0; }, "energy tolerance must not be"},
      {[](SolverOptions& o) { o.energy_window = 0; }, "energy window must be at least 1"},
      {[](SolverOptions& o) { o.max_iterations = 0; }, "max iterations must be at least 1"},
      {[](SolverOptions& o) { o.margin_factor = 0.0; }, "margin factor must be positive"},
      {[](SolverOptions& o) { o.exact_answer_below = -1.0; }, "exact_answer_below must not be"},
  };
  for (const auto& [breaks, reason] : broken) {
    SolverOptions o = valid;
    breaks(o);
    why.clear();
    EXPECT_FALSE(o.is_valid(&why)) << reason;
    EXPECT_NE(why.find(reason), std::string::npos) << why;
  }
  SolverOptions seed = valid;
  seed.rule = UpdateRule::seed;
  seed.c = 0.1;
  EXPECT_TRUE(seed.is_valid(&why)) << why;
}

}  // namespace
}  // namespace fibrecheck
