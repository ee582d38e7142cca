// The contact problem held as saddle points of the beams and the contacts (W never formed) gives
// the answers of the assembled compliance matrix, meets the closed forms, and takes the singular
// sets the regularisation is for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "deformed_contact_ground_truths.h"
#include "reference_solver.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

using testing::bending_stiffness;
using testing::compliance;

Result held_as(const Scene& scene, ContactAssembly assembly) {
  ReferenceOptions options;
  options.contact_assembly = assembly;
  return solve_reference(scene, options);
}

double summed_force(const Result& r) {
  double sum = 0.0;
  for (const ContactResult& c : r.contacts) sum += c.total_force;
  for (const WallResult& w : r.walls) sum += w.force;
  return sum;
}

// Both are exact solutions of one problem, so they agree to the round-off of their
// factorisations wherever the problem determines the answer well: deflections, energies and the
// summed force to 1e-9 (they meet at 1e-12 on these scenes). A line contact's single slices are
// determined less well: its compliance is a smooth kernel, W_SS of the parallel fibres' 100
// slices has a condition number of 4.9e7, and every finite-element solve behind either method is
// accepted at a backward error of 1e-12 — so the slice forces are held to 4.9e7 × 1e-12 ≈ 5e-5
// of the largest (they meet at about 1e-6).
TEST(SaddlePointContact, GivesTheAnswersOfTheComplianceMatrix) {
  for (const char* name : {"parallel_fibres", "two_fibres_crossing"}) {
    SCOPED_TRACE(name);
    const Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/" + name + ".json");
    const Result matrix = held_as(scene, ContactAssembly::compliance_matrix);
    const Result saddle = held_as(scene, ContactAssembly::saddle_point);
    ASSERT_EQ(matrix.status, Status::converged) << matrix.message;
    ASSERT_EQ(saddle.status, Status::converged) << saddle.message;
    EXPECT_NE(saddle.message.find("held as saddle points"), std::string::npos) << saddle.message;
    EXPECT_EQ(matrix.message.find("held as saddle points"), std::string::npos);
    EXPECT_NEAR(saddle.strain_energy, matrix.strain_energy, 1e-9 * matrix.strain_energy);
    EXPECT_NEAR(summed_force(saddle), summed_force(matrix), 1e-9 * summed_force(matrix));
    double largest_u = 0.0, largest_force = 0.0;
    for (const FibreResult& f : matrix.fibres)
      for (const Eigen::Vector3d& u : f.displacement) largest_u = std::max(largest_u, u.norm());
    for (const ContactResult& c : matrix.contacts)
      for (const ContactPoint& p : c.points)
        largest_force = std::max(largest_force, p.force.norm());
    ASSERT_EQ(matrix.fibres.size(), saddle.fibres.size());
    for (std::size_t f = 0; f < matrix.fibres.size(); ++f)
      for (std::size_t j = 0; j < matrix.fibres[f].displacement.size(); ++j)
        EXPECT_LE((matrix.fibres[f].displacement[j] - saddle.fibres[f].displacement[j]).norm(),
                  1e-9 * largest_u);
    ASSERT_EQ(matrix.contacts.size(), saddle.contacts.size());
    for (std::size_t k = 0; k < matrix.contacts.size(); ++k) {
      ASSERT_EQ(matrix.contacts[k].points.size(), saddle.contacts[k].points.size());
      for (std::size_t i = 0; i < matrix.contacts[k].points.size(); ++i)
        EXPECT_LE((matrix.contacts[k].points[i].force - saddle.contacts[k].points[i].force).norm(),
                  5e-5 * largest_force);
    }
  }
}

// The deformed contact's sequence of linearised solves, each as saddle points: the closed form of
// two offset parallel fibres, whose normal turns by 13° to 32°.
TEST(SaddlePointContact, DeformedContactMeetsTheClosedForm) {
  for (const testing::OffsetParallel& c : testing::offset_parallel_cases()) {
    SCOPED_TRACE(c.c0.transpose());
    const Result r = held_as(c.scene(), ContactAssembly::saddle_point);
    ASSERT_EQ(r.status, Status::converged) << r.message;
    EXPECT_NEAR(summed_force(r), c.P(), 1e-6 * c.P());
    EXPECT_LE((r.fibres[1].displacement[50] - c.u_b()).norm(), 1e-6 * c.u_b().norm());
  }
}

// Two walls in one plane constrain the same motion twice: MUMPS finds the null pivot, the set is
// regularised as the assembled one is, and the total is the closed form R = P − g/C(L/2).
TEST(SaddlePointContact, TwoWallsInOnePlaneShareTheReaction) {
  const double EI = bending_stiffness(0.01, 80000), C = compliance(0.5, 1.0, EI);
  const double P = 1e-4, gap = 0.5 * P * C;
  const Result r = held_as(testing::pressed_onto_wall(P, gap, 2), ContactAssembly::saddle_point);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.walls.size(), 2u);
  EXPECT_NEAR(r.walls[0].force + r.walls[1].force, P - gap / C, 1e-8 * P);
}

// An overlap at two pinned supports: every side of the contact is pinned, which the saddle points
// read from the supports' constraints; said at once, as with the compliance matrix.
TEST(SaddlePointContact, OverlapAtTwoPinnedSupportsIsUnresolvable) {
  const Result r = held_as(testing::overlapping_supports(), ContactAssembly::saddle_point);
  EXPECT_EQ(r.status, Status::unresolvable);
  EXPECT_NE(r.message.find("A and B"), std::string::npos) << r.message;
}

// Asked for where they cannot hold the problem (friction), the saddle points are not used, and
// the result says so rather than quietly holding the compliance matrix.
TEST(SaddlePointContact, AskedForWithFrictionTheResultSaysTheMatrixHeldIt) {
  Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/two_fibres_crossing.json");
  scene.contact.friction = 0.3;
  const Result r = held_as(scene, ContactAssembly::saddle_point);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  EXPECT_EQ(r.message.find("held as saddle points"), std::string::npos) << r.message;
  EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) {
    return w.find("with friction, held the compliance matrix") != std::string::npos;
  }));
}

}  // namespace
}  // namespace fibrecheck
