// Contacts and walls in the result schema (DESIGN §5). Test problem: tow fibres A (y = 0) and C
// (y = 0.03) along x on [0, 1], r = 0.01, a fibre B along y crossing A, and a floor (normal +z)
// and a side wall (normal +y). Known answers, by hand:
//  - points grouped by (kind, pair) in the order the pairs first appear, only points with P > 0,
//    each at s_A with the force A receives; total_force = |Σ F| — for F₁ = (0, 1, −2)·1e-4,
//    F₂ = (0, −1, −2)·1e-4 and F₃ = (1, 0, 1)·1e-4 that is |(1, 0, −3)|·1e-4 = √10·1e-4 N, not
//    Σ|F| = (2√5 + √2)·1e-4;
//  - a point's place is the midpoint of the two displaced centres, for a wall A's displaced centre
//    less r·n (the touching point on the wall);
//  - a wall's force is the sum of the normal forces P of its contacts (friction not included), its
//    footprint the bounding box of the fibres' ends projected on the wall, widened by r:
//    floor (x, y): [−0.01, 1.01] × [−0.01, 0.04] = 1.02 × 0.05 = 0.051 mm²;
//    side wall (z, x): [−0.01, 0.01] × [−0.01, 1.01] = 0.02 × 1.02 = 0.0204 mm²;
//    pressure = force / footprint area; a wall without force has pressure 0.
#include "contact_results.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_scenes.h"

namespace fibrecheck {
namespace {

using V = Eigen::Vector3d;
using testing::fibre;

// Sums of a few forces of order 1e-4 N (rounding ~1e-20) and lengths ≤ 1 mm (~1e-16).
constexpr double kForce = 1e-18;
constexpr double kLength = 1e-15;

std::vector<Fibre> tow_fibres() {
  return {make_fibre(fibre("A", {0, 0, 0}, {1, 0, 0}), V::UnitX(), 10),
          make_fibre(fibre("C", {0, 0.03, 0}, {1, 0.03, 0}), V::UnitX(), 10)};
}

std::vector<WallSpec> floor_and_side() {
  WallSpec floor, side;
  floor.id = "floor";
  floor.point = {0, 0, -0.01};
  floor.normal = V::UnitZ();
  side.id = "side";
  side.point = {0, -0.01, 0};
  side.normal = V::UnitY();
  return {floor, side};
}

Contact make(ContactKind kind, int a, int b, double s_a, double s_b, double force,
             V normal = V::UnitZ()) {
  Contact c;
  c.kind = kind;
  c.a = a;
  c.b = b;
  c.s_a = s_a;
  c.s_b = s_b;
  c.force = force;
  c.normal = normal;
  return c;
}

TEST(ContactResults, PointsAreGroupedByPairInOrderOfFirstAppearance) {
  auto fibres = tow_fibres();
  fibres.push_back(make_fibre(fibre("B", {0.5, -0.5, 0.02}, {0.5, 0.5, 0.02}), V::UnitX(), 10));
  const auto walls = floor_and_side();
  const std::vector<Contact> contacts = {
      make(ContactKind::line, 0, 1, 0.1, 0.1, 1e-4, V::UnitY()),
      make(ContactKind::point, 0, 2, 0.5, 0.5, 2e-4),
      make(ContactKind::line, 0, 1, 0.3, 0.3, 0.0, V::UnitY()),  // no force: left out
      make(ContactKind::wall, 0, 0, 0.7, 0.0, 5e-5),
      make(ContactKind::line, 0, 1, 0.9, 0.9, 3e-4, V::UnitY()),
      make(ContactKind::wall, 1, 0, 0.2, 0.0, 0.0),               // a pair with no force at all
      make(ContactKind::wall, 0, 1, 0.4, 0.0, 1e-5, V::UnitY()),  // same numbers as A–C, a wall
  };
  std::vector<V> force_on_a, u_a, u_b;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    force_on_a.push_back(contacts[k].force_on_a());
    u_a.push_back(V(0, 0, -1e-3 * (k + 1)));
    u_b.push_back(V(0, 0, 2e-3 * (k + 1)));
  }
  const std::vector<ContactResult> results =
      contact_results(contacts, fibres, walls, force_on_a, u_a, u_b);
  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[0].fibres[0], "A");
  EXPECT_EQ(results[0].fibres[1], "C");
  EXPECT_EQ(results[0].kind, "line");
  EXPECT_EQ(results[1].fibres[1], "B");
  EXPECT_EQ(results[1].kind, "point");
  EXPECT_EQ(results[2].fibres[1], "floor");
  EXPECT_EQ(results[2].kind, "wall");
  EXPECT_EQ(results[3].fibres[1], "side");
  EXPECT_EQ(results[3].kind, "wall");

  ASSERT_EQ(results[0].points.size(), 2u);
  EXPECT_EQ(results[0].points[0].position, 0.1);
  EXPECT_EQ(results[0].points[1].position, 0.9);
  EXPECT_TRUE(results[0].points[0].force == V(0, -1e-4, 0));  // A receives −P·n
  EXPECT_NEAR(results[0].total_force, 4e-4, kForce);
  // Midpoint of the displaced centres: slice 0.1 of A at (0.1, 0, −1e-3), of C at
  // (0.1, 0.03, 2e-3).
  EXPECT_NEAR((results[0].points[0].point - V(0.1, 0.015, 0.5e-3)).norm(), 0.0, kLength);
  EXPECT_NEAR((results[0].points[1].point - V(0.9, 0.015, 0.5 * (-5e-3 + 10e-3))).norm(), 0.0,
              kLength);

  ASSERT_EQ(results[1].points.size(), 1u);
  EXPECT_NEAR(results[1].total_force, 2e-4, kForce);
  EXPECT_NEAR((results[1].points[0].point - V(0.5, 0, 0.5 * (-2e-3 + 0.02 + 4e-3))).norm(), 0.0,
              kLength);

  // The floor's point: A's displaced centre (0.7, 0, −4e-3) less r·n.
  ASSERT_EQ(results[2].points.size(), 1u);
  EXPECT_EQ(results[2].points[0].position, 0.7);
  EXPECT_TRUE(results[2].points[0].force == V(0, 0, 5e-5));  // a wall pushes with +P·n
  EXPECT_NEAR((results[2].points[0].point - V(0.7, 0, -4e-3 - 0.01)).norm(), 0.0, kLength);
  EXPECT_NEAR(results[2].total_force, 5e-5, kForce);
}

TEST(ContactResults, TotalForceIsTheMagnitudeOfTheResultant) {
  const auto fibres = tow_fibres();
  // Two points whose sideways parts cancel and a third pulling back partly.
  const std::vector<Contact> contacts = {make(ContactKind::line, 0, 1, 0.2, 0.2, 1.0),
                                         make(ContactKind::line, 0, 1, 0.4, 0.4, 1.0),
                                         make(ContactKind::line, 0, 1, 0.6, 0.6, 1.0)};
  const std::vector<V> force_on_a = {V(0, 1e-4, -2e-4), V(0, -1e-4, -2e-4), V(1e-4, 0, 1e-4)};
  const std::vector<V> zero(3, V::Zero());
  const auto results = contact_results(contacts, fibres, {}, force_on_a, zero, zero);
  ASSERT_EQ(results.size(), 1u);
  ASSERT_EQ(results[0].points.size(), 3u);
  // Σ F = (1, 0, −3)·1e-4: |Σ F| = √10·1e-4 < Σ|F| = (2√5 + √2)·1e-4.
  EXPECT_NEAR(results[0].total_force, std::sqrt(10.0) * 1e-4, kForce);
  // Friction in the force vector counts; the points keep exactly the vectors given.
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(results[0].points[k].force == force_on_a[k]);
}

TEST(ContactResults, NothingCarriesForceNothingIsReported) {
  const auto fibres = tow_fibres();
  std::vector<Contact> contacts = {make(ContactKind::line, 0, 1, 0.2, 0.2, 0.0),
                                   make(ContactKind::line, 0, 1, 0.4, 0.4, -1e-9),
                                   make(ContactKind::line, 0, 1, 0.6, 0.6, NAN)};
  const std::vector<V> any(3, V(1, 1, 1));
  EXPECT_TRUE(contact_results(contacts, fibres, {}, any, any, any).empty());
  EXPECT_TRUE(contact_results({}, fibres, {}, {}, {}, {}).empty());
}

TEST(WallResults, ForceIsTheSumOfNormalForcesAndPressureIsPerFootprintArea) {
  const auto fibres = tow_fibres();
  const auto walls = floor_and_side();
  std::vector<Contact> contacts = {
      make(ContactKind::wall, 0, 0, 0.25, 0, 3e-4),
      make(ContactKind::wall, 1, 0, 0.75, 0, 2e-4),
      make(ContactKind::wall, 0, 1, 0.5, 0, 4e-5, V::UnitY()),
      make(ContactKind::line, 0, 1, 0.5, 0.5, 9.0),  // b = 1 but not a wall: not the side's
      make(ContactKind::point, 0, 0, 0.5, 0.5, 9.0),
  };
  contacts[0].friction = V(1e-4, 0, 0);  // friction is no normal reaction
  const std::vector<WallResult> results = wall_results(contacts, fibres, walls);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].id, "floor");
  EXPECT_NEAR(results[0].force, 5e-4, kForce);
  EXPECT_NEAR(results[0].area, 1.02 * 0.05, 1e-15);
  EXPECT_NEAR(results[0].pressure, 5e-4 / (1.02 * 0.05), 1e-14 * 5e-4 / (1.02 * 0.05));
  EXPECT_EQ(results[1].id, "side");
  EXPECT_NEAR(results[1].force, 4e-5, kForce);
  EXPECT_NEAR(results[1].area, 0.02 * 1.02, 1e-15);
  EXPECT_NEAR(results[1].pressure, 4e-5 / (0.02 * 1.02), 1e-14 * 4e-5 / (0.02 * 1.02));
}

TEST(WallResults, AWallWithoutContactsHasZeroForceAndPressure) {
  const auto fibres = tow_fibres();
  WallSpec end;
  end.id = "end";
  end.point = {1.01, 0, 0};
  end.normal = -V::UnitX();  // its plane (y, z): [−0.01, 0.04] × [−0.01, 0.01]
  const auto results = wall_results({}, fibres, {end});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].force, 0.0);
  EXPECT_EQ(results[0].pressure, 0.0);
  EXPECT_NEAR(results[0].area, 0.05 * 0.02, 1e-16);
  EXPECT_TRUE(wall_results({}, fibres, {}).empty());
}

}  // namespace
}  // namespace fibrecheck
