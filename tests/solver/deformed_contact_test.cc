// Contact on the deformed fibres (seed Eqs. 4.14–4.15): the iterative solver against the closed
// forms of tests/deformed_contact_ground_truths.h, in both contact models.
#include <gtest/gtest.h>

#include "deformed_contact_ground_truths.h"
#include "iterative_solver.h"

namespace fibrecheck {
namespace {

Result solve(const Scene& scene) {
  validate_scene(scene);
  return solve_iteratively(scene, SolverOptions::from_scene(scene));
}

double total_force(const Result& r) {
  double total = 0.0;
  for (const ContactResult& c : r.contacts) total += c.total_force;
  return total;
}

Eigen::Vector3d mid_span(const Result& r, int fibre) {
  return r.fibres[fibre].displacement[50];
}

// The normal turns by 13° to 32°: the deformed answer is the closed form to 1e-6, force and
// displacements; the linearised one is its own closed form (18 % higher on the first case).
TEST(DeformedContact, OffsetParallelFibresMeetTheClosedForm) {
  for (const testing::OffsetParallel& c : testing::offset_parallel_cases()) {
    SCOPED_TRACE(c.c0.transpose());
    const Result r = solve(c.scene());
    ASSERT_EQ(r.status, Status::converged) << r.message;
    EXPECT_NEAR(total_force(r), c.P(), 1e-6 * c.P());
    EXPECT_LE((mid_span(r, 0) - c.u_a()).norm(), 1e-6 * c.u_a().norm());
    EXPECT_LE((mid_span(r, 1) - c.u_b()).norm(), 1e-6 * c.u_b().norm());
    const Result linear = solve(c.scene(ContactGeometryModel::linearised));
    ASSERT_EQ(linear.status, Status::converged) << linear.message;
    EXPECT_NEAR(total_force(linear), c.P_linearised(), 1e-6 * c.P_linearised());
  }
}

// In the small-load limit the two models agree to second order: halving the load quarters the
// difference of their forces.
TEST(DeformedContact, ModelsAgreeToSecondOrderForSmallLoads) {
  const double r = 0.01;
  double difference[2];
  for (int i = 0; i < 2; ++i) {
    const double e = i == 0 ? 0.2 : 0.1;
    testing::OffsetParallel c{{0, 0, 2.001 * r}, {0, 0.4 * e * r, -0.3 * e * r}};
    difference[i] = total_force(solve(c.scene())) -
                    total_force(solve(c.scene(ContactGeometryModel::linearised)));
  }
  EXPECT_LT(difference[0], 0.0);  // the turned normal pushes less
  EXPECT_NEAR(difference[0] / difference[1], 4.0, 0.2);
}

// A crossing pushed along one fibre: its closest points slide with it and it keeps the force of
// the closed form at the slid place (the linearised contact stays where the chords cross).
TEST(DeformedContact, PushedCrossingSlidesAndKeepsItsForce) {
  testing::PushedCrossing c;
  c.H = 0.02 / c.C_b();  // B's crossing point moves 2 radii along A
  const Result r = solve(c.scene());
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_NEAR(r.contacts[0].points[0].position, c.slid(), 1e-3);
  EXPECT_NEAR(total_force(r), c.P(), 2e-4 * c.P());
  const Result linear = solve(c.scene(ContactGeometryModel::linearised));
  EXPECT_NEAR(linear.contacts[0].points[0].position, 0.5, 1e-12);
}

}  // namespace
}  // namespace fibrecheck
