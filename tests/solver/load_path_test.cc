// Load paths: a scene's steps scale the cross-section (compaction factor F about the tow's centre)
// and the loads (load factor); each step is solved from the last and listed in the result.

#include "load_path.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "iterative_solver.h"
#include "load_path_solve.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

double force_between_a_and_b(const Result& r) {
  double total = 0.0;
  for (const ContactResult& c : r.contacts) total += c.total_force;
  return total;
}

// B crosses A at 0.3 of A and 0.6 of B, h above it. Compacting by F about the centre of the four
// supports brings B to F·h above A and shortens B (it lies across the axis) to F·L_B, so
// P(F) = (r_A + r_B − F·h) / (C_A + C_B(F)), C_B(F) = a²b²/(3EI·F·L_B) with a = 0.6F, b = 0.4F.
TEST(LoadPath, CompactionStepsMeetTheClosedFormAtEveryStep) {
  Scene s = testing::crossing(0.3, 0.6, 1e-4);
  s.solver.overlap_tolerance = 1e-13;
  const double h = 0.02 - 1e-4, EI = testing::bending_stiffness(0.01, 80000);
  const double CA = testing::compliance(0.3, 1.0, EI);
  for (double F : {1.0, 0.999, 0.995}) s.steps.push_back({F, 1.0});
  const Result r = solve_iteratively(s, SolverOptions::from_scene(s));
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 3u);
  double vf = 0.0;
  long iterations = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.steps[i].status, Status::converged);
    EXPECT_GT(r.steps[i].fibre_volume_fraction, vf);  // the section shrinks
    vf = r.steps[i].fibre_volume_fraction;
    EXPECT_DOUBLE_EQ(r.steps[i].contacts_per_fibre, 1.0);  // one point, two fibres
    iterations += r.steps[i].iterations;
  }
  EXPECT_EQ(r.iterations, iterations);
  const double F = 0.995;
  const double CB = std::pow(0.6 * F * 0.4 * F, 2) / (3.0 * EI * F);
  const double P = (0.02 - F * h) / (CA + CB);
  EXPECT_NEAR(force_between_a_and_b(r), P, 1e-9 * P);
  // Each step is the scene at that step: solved alone, the last gives the same answer.
  const Scene last = scene_at_step(s, s.steps.back());
  EXPECT_TRUE(last.steps.empty());
  const Result alone = solve_iteratively(last, SolverOptions::from_scene(last));
  EXPECT_NEAR(force_between_a_and_b(alone), P, 1e-9 * P);
}

// Progress on a long sequence says which step it is in: every report of step k says k of 3, and
// the steps report in order (each step compacts the crossing further, so each has work to do).
TEST(LoadPath, ProgressSaysWhichStep) {
  Scene s = testing::crossing(0.3, 0.6, 1e-4);
  s.solver.overlap_tolerance = 1e-13;
  for (double F : {0.999, 0.995, 0.99}) s.steps.push_back({F, 1.0});
  SolverOptions options = SolverOptions::from_scene(s);
  options.progress_interval_s = 0.0;
  std::vector<int> steps_seen;
  options.progress = [&](const IterationProgress& p) {
    EXPECT_EQ(p.steps, 3);
    if (steps_seen.empty() || steps_seen.back() != p.step) steps_seen.push_back(p.step);
  };
  const Result r = solve_iteratively(s, options);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  EXPECT_EQ(steps_seen, (std::vector<int>{1, 2, 3}));
  // A single scene reports no step.
  s.steps.clear();
  options.progress = [](const IterationProgress& p) { EXPECT_EQ(p.steps, 0); };
  EXPECT_EQ(solve_iteratively(s, options).status, Status::converged);
}

// Loading, unloading and reloading: frictionless contact is linear in the load while the
// contact stays closed, R = λ·P·C_B/(C_A + C_B) at the last step's load factor λ.
TEST(LoadPath, LoadFactorsScaleTheLoads) {
  const double P = 1e-4, EI = testing::bending_stiffness(0.01, 80000);
  Scene s = testing::loaded_crossing(P);
  s.solver.overlap_tolerance = 1e-14;
  s.steps = {{1.0, 1.0}, {1.0, 0.25}, {1.0, 2.0}};
  const Result r = solve_iteratively(s, SolverOptions::from_scene(s));
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 3u);
  const double CA = testing::compliance(0.3, 1.0, EI), CB = testing::compliance(0.6, 1.0, EI);
  EXPECT_NEAR(force_between_a_and_b(r), 2.0 * P * CB / (CA + CB), 1e-9 * P);
  // The strain energy grows with the square of the load factor.
  EXPECT_NEAR(r.steps[1].strain_energy / r.steps[0].strain_energy, 0.0625, 1e-6);
  EXPECT_NEAR(r.steps[2].strain_energy / r.steps[0].strain_energy, 4.0, 1e-6);
}

// A step that cannot be solved ends the path with its status; the finished steps are kept. Two
// parallel fibres 0.03 mm apart (centre to centre): compacted by 0.5 their supports overlap.
TEST(LoadPath, AStepThatFailsEndsThePath) {
  Scene s;
  s.fibres = {testing::fibre("A", {0, 0, 0}, {1, 0, 0}),
              testing::fibre("B", {0, 0, 0.03}, {1, 0, 0.03})};
  s.steps = {{1.0, 1.0}, {0.9, 1.0}, {0.5, 1.0}, {0.4, 1.0}};
  const Result r = solve_iteratively(s, SolverOptions::from_scene(s));
  EXPECT_EQ(r.status, Status::unresolvable);
  ASSERT_EQ(r.steps.size(), 3u);
  EXPECT_EQ(r.steps[0].status, Status::converged);
  EXPECT_EQ(r.steps[1].status, Status::converged);
  EXPECT_EQ(r.steps[2].status, Status::unresolvable);
  EXPECT_NE(r.message.find("step 3 of 4"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("pinned supports"), std::string::npos) << r.message;
}

// A warning an earlier step gives stays in the result, named by the first step that gave it, and
// is not repeated for the steps that give it again.
TEST(LoadPath, WarningsOfEveryStepAreKept) {
  Scene s;
  s.fibres = {testing::fibre("A", {0, 0, 0}, {1, 0, 0})};
  s.steps = {{1.0, 1.0}, {0.9, 1.0}, {0.8, 1.0}};
  int step = 0;
  const Result r = solve_load_path(s, [&](const Scene&, const Result*) {
    Result one;
    one.status = Status::converged;
    ++step;
    if (step >= 2) one.warnings = {"from the second step on"};
    if (step == 3) one.warnings.push_back("only the third");
    return one;
  });
  EXPECT_EQ(r.status, Status::converged);
  ASSERT_EQ(r.steps.size(), 3u);
  EXPECT_EQ(r.warnings, (std::vector<std::string>{"step 2 of 3: from the second step on",
                                                  "step 3 of 3: only the third"}));
}

}  // namespace
}  // namespace fibrecheck
