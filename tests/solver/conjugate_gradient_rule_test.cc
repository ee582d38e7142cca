// Rule cg: the frictionless contact problem solved by preconditioned conjugate gradients with
// projections. It must reach the closed forms and the other rules' equilibria, in few products of
// W where the line contacts dominate, and take the same path on one thread as on two.
#include <gtest/gtest.h>
#include <omp.h>

#include "input_error.h"
#include "iterative_solver.h"
#include "test_scenes.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

Result solve(const Scene& scene) {
  return solve_iteratively(scene, SolverOptions::from_scene(scene));
}

// The closed form of two parallel fibres sharing a uniform load (DESIGN §7): the preconditioner
// inverts the line's compliance exactly, so a handful of products suffice for any slice count
// (ten projected steps to settle which slices push, then conjugate gradients), where the
// accelerated rule needs 31 000 iterations at 100 slices and stalls at 1 000.
TEST(ConjugateGradientRule, ParallelFibresInAFewProducts) {
  const double q = 1e-4;
  const double EIa = testing::bending_stiffness(0.01, 80000);
  const double EIb = testing::bending_stiffness(0.008, 70000);
  for (int slices : {100, 1000}) {
    Scene s = testing::parallel(q, slices);
    s.solver.rule = UpdateRule::conjugate_gradient;
    const Result r = solve(s);
    ASSERT_EQ(r.status, Status::converged) << r.message;
    EXPECT_EQ(r.rule, "cg");
    EXPECT_LE(r.iterations, 20) << slices << " slices";
    ASSERT_EQ(r.contacts.size(), 1u);
    const double line = q * EIb / (EIa + EIb);
    EXPECT_NEAR(r.contacts[0].total_force, line, 0.01 * line);
    const double mid = 5 * q / (384 * (EIa + EIb));
    EXPECT_NEAR(-r.fibres[0].displacement[s.output.samples / 2].z(), mid, 1e-3 * mid);
    EXPECT_LT(r.max_overlap, s.overlap_tolerance());
    EXPECT_LT(r.gap_force_residual, s.overlap_tolerance());
  }
}

// A compacted tow under the linearised contact, whose problem is one fixed quadratic programme:
// the same equilibrium as the accelerated rule (both within t_d of it), every contact just
// touching.
TEST(ConjugateGradientRule, CompactedTowReachesTheAcceleratedRulesEquilibrium) {
  TowOptions tow;
  tow.fibres = 19;
  tow.slices = 40;
  tow.seed = 5;
  Scene s = generate_tow(tow);
  s.contact.geometry = ContactGeometryModel::linearised;
  s.solver.rule = UpdateRule::accelerated;
  const Result accelerated = solve(s);
  s.solver.rule = UpdateRule::conjugate_gradient;
  const Result cg = solve(s);
  ASSERT_EQ(accelerated.status, Status::converged) << accelerated.message;
  ASSERT_EQ(cg.status, Status::converged) << cg.message;
  EXPECT_LT(cg.max_overlap, s.overlap_tolerance());
  EXPECT_LT(cg.gap_force_residual, s.overlap_tolerance());
  EXPECT_NEAR(cg.strain_energy_exact, accelerated.strain_energy_exact,
              1e-4 * accelerated.strain_energy_exact);
  ASSERT_EQ(cg.contacts.size(), accelerated.contacts.size());
  double largest = 0.0;
  for (const ContactResult& c : accelerated.contacts) largest = std::max(largest, c.total_force);
  for (std::size_t i = 0; i < cg.contacts.size(); ++i)
    EXPECT_NEAR(cg.contacts[i].total_force, accelerated.contacts[i].total_force, 1e-3 * largest);
}

// One thread and two give the same iterations, forces and energies to the last bit, for rule cg
// (its sums are taken in fixed blocks) and for the accelerated rule with its working set, on a
// tow large enough for every parallel loop over the candidates to split.
TEST(ConjugateGradientRule, OneThreadAndTwoTakeTheSamePath) {
  TowOptions tow;
  tow.fibres = 150;
  tow.slices = 100;
  tow.seed = 3;
  Scene s = generate_tow(tow);
  for (UpdateRule rule : {UpdateRule::conjugate_gradient, UpdateRule::accelerated}) {
    s.solver.rule = rule;
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const Result one = solve(s);
    omp_set_num_threads(2);
    const Result two = solve(s);
    omp_set_num_threads(threads);
    ASSERT_EQ(one.status, Status::converged) << one.message;
    EXPECT_GT(one.candidates, 8192);
    EXPECT_EQ(one.iterations, two.iterations) << to_string(rule);
    EXPECT_EQ(one.strain_energy_exact, two.strain_energy_exact) << to_string(rule);
    EXPECT_EQ(one.strain_energy, two.strain_energy) << to_string(rule);
    ASSERT_EQ(one.contacts.size(), two.contacts.size());
    for (std::size_t i = 0; i < one.contacts.size(); ++i)
      EXPECT_EQ(one.contacts[i].total_force, two.contacts[i].total_force) << to_string(rule);
  }
}

TEST(ConjugateGradientRule, RefusesFriction) {
  Scene s = testing::crossing(0.5, 0.5, 1e-3);
  s.solver.rule = UpdateRule::conjugate_gradient;
  s.contact.friction = 0.2;
  try {
    validate_scene(s);
    FAIL() << "rule cg with friction was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("solver.rule"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fibrecheck
