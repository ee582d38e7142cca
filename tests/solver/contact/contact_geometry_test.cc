// Where a contact acts and how much it overlaps, on the undeformed fibres (small deflections).
// Test problems and known answers, written out here:
//  - A along x, B along y at x = 0.3 a height h above A (B reaches A at 0.6 of its length): the
//    chords are closest at s_A = 0.3, s_B = 0.6, the normal is +z, and for displacements u_A, u_B
//    the overlap is d = (rA + rB) − (h + u_Bz − u_Az): tangential displacements change nothing.
//  - B tilted about x by θ, passing the point (0.4, 0, 0) + h·n₀ with n₀ = (0, −sin θ, cos θ):
//    s_A = 0.4, normal n₀, d = (rA + rB) − h − n₀·(u_B − u_A).
//  - A slice between two tow fibres along x whose stations differ axially: the axial part of
//    Bc − Ac is dropped, so the normal is the cross-section direction and d = rA + rB − h.
//  - A wall with point p and unit normal n: d = r − n·(Ac + u_A − p); u_B plays no part.
//  - Coincident centres (fibres through each other): no direction can be trusted; the normal is
//    A's axis × B's (x × y = +z) for a crossing, the second cross-section axis for a slice (z for
//    the x axis, x for the y axis), unit and finite, `normal_held` set, and the same every time.
#include "contact_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_scenes.h"

namespace fibrecheck {
namespace {

using V = Eigen::Vector3d;
using testing::fibre;

// Every number here is a sum of a few terms of size ≤ 1 mm: rounding is a few ulp of 1, ~1e-16;
// 1e-15 leaves room for the closest-point solve on the chords.
constexpr double kTight = 1e-15;
constexpr double kPlace = 1e-14;  // closest-point parameters from Eqs. 4.22–4.23 (a division)

const double rA = 0.01, rB = 0.008;

std::vector<Fibre> fibres_of(const std::vector<FibreSpec>& specs, const V& axis = V::UnitX()) {
  std::vector<Fibre> fibres;
  for (const FibreSpec& s : specs) fibres.push_back(make_fibre(s, axis, 10.0));
  return fibres;
}

// Two parallel tow fibres along x, B a height h above A, and the slice between them at mid-span.
std::vector<Fibre> stacked(double h) {
  return fibres_of({fibre("A", {0, 0, 0}, {1, 0, 0}, rA), fibre("B", {0, 0, h}, {1, 0, h}, rB)});
}

Contact mid_span_slice(const ContactGeometry& geometry) {
  Contact c;
  c.kind = ContactKind::line;
  c.a = 0;
  c.b = 1;
  c.s_a = c.s_b = 0.5;
  geometry.place_on_undeformed(c);
  return c;
}

Contact point_contact() {
  Contact c;
  c.kind = ContactKind::point;
  c.a = 0;
  c.b = 1;
  c.normal = V(1, 0, 0);  // rubbish that place_on_undeformed must overwrite
  c.normal_held = true;
  return c;
}

TEST(ContactGeometry, CrossingActsAtTheClosestPointsOfTheChords) {
  const double h = 0.0175;
  const auto fibres = fibres_of(
      {fibre("A", {0, 0, 0}, {1, 0, 0}, rA), fibre("B", {0.3, -0.6, h}, {0.3, 0.4, h}, rB)});
  const ContactGeometry geometry(fibres, {}, V::UnitX());
  Contact c = point_contact();
  geometry.place_on_undeformed(c);
  EXPECT_NEAR(c.s_a, 0.3, kPlace);
  EXPECT_NEAR(c.s_b, 0.6, kPlace);
  EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kTight);
  EXPECT_FALSE(c.normal_held);

  EXPECT_NEAR(geometry.overlap_along_normal(c, V::Zero(), V::Zero()), rA + rB - h, kTight);
  const V u_a(0.1, 0.2, 0.003), u_b(-0.05, 0.3, -0.001);
  EXPECT_NEAR(geometry.overlap_along_normal(c, u_a, u_b), rA + rB - (h - 0.001 - 0.003), kTight);
  // Sliding along the normal-free directions changes nothing; moving apart opens a gap.
  EXPECT_NEAR(geometry.overlap_along_normal(c, V(0.2, -0.1, 0), V(0.4, 0.7, 0)), rA + rB - h,
              kTight);
  EXPECT_NEAR(geometry.overlap_along_normal(c, V(0, 0, -0.01), V(0, 0, 0.01)), rA + rB - h - 0.02,
              kTight);
}

TEST(ContactGeometry, TiltedCrossingHasTheCommonPerpendicularAsNormal) {
  for (double theta : {0.3, 1.0, M_PI / 2 - 1e-3}) {
    const V n0(0, -std::sin(theta), std::cos(theta)), d(0, std::cos(theta), std::sin(theta));
    const double h = 0.02;
    const V centre_b = V(0.4, 0, 0) + h * n0;
    const auto fibres = fibres_of({fibre("A", {0, 0, 0}, {1, 0, 0}, rA),
                                   fibre("B", centre_b - 0.25 * d, centre_b + 0.75 * d, rB)});
    const ContactGeometry geometry(fibres, {}, V::UnitX());
    Contact c = point_contact();
    geometry.place_on_undeformed(c);
    EXPECT_NEAR(c.s_a, 0.4, kPlace) << theta;
    EXPECT_NEAR(c.s_b, 0.25, kPlace) << theta;
    EXPECT_NEAR((c.normal - n0).norm(), 0.0, kPlace) << theta;
    EXPECT_NEAR(c.normal.norm(), 1.0, kTight);
    const V u_a(0.001, 0.002, -0.003), u_b(0.004, -0.001, 0.002);
    EXPECT_NEAR(geometry.overlap_along_normal(c, u_a, u_b), rA + rB - h - n0.dot(u_b - u_a), kPlace)
        << theta;
  }
}

TEST(ContactGeometry, SliceDropsTheAxialPart) {
  // Tow fibres along x, B a height h above A and starting 0.1 further along: the slice at x = 0.5
  // has s_A = 0.5 and s_B = 0.4; give B's station 0.02 mm off axially to see the axial part go.
  const double h = 0.0179;
  const auto fibres =
      fibres_of({fibre("A", {0, 0, 0}, {1, 0, 0}, rA), fibre("B", {0.1, 0, h}, {1.1, 0, h}, rB)});
  const ContactGeometry geometry(fibres, {}, V::UnitX());
  Contact c;
  c.kind = ContactKind::line;
  c.a = 0;
  c.b = 1;
  c.slice = 3;
  c.s_a = 0.5;
  c.s_b = 0.42;  // x = 0.52
  geometry.place_on_undeformed(c);
  EXPECT_EQ(c.s_a, 0.5);  // a slice keeps its stations
  EXPECT_EQ(c.s_b, 0.42);
  EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kTight);
  EXPECT_FALSE(c.normal_held);
  EXPECT_NEAR(geometry.overlap_along_normal(c, V::Zero(), V::Zero()), rA + rB - h, kTight);
  // Axial displacements are dropped too; only the z parts count.
  EXPECT_NEAR(geometry.overlap_along_normal(c, V(0.3, 0.001, 0.002), V(-0.2, 0, -0.0005)),
              rA + rB - (h - 0.0005 - 0.002), kTight);
}

TEST(ContactGeometry, SliceOnATowAxisThatIsNotNormalised) {
  // Tow axis given as (1, 1, 0): the geometry normalises it; B lies along the axis and above A.
  const V t = V(1, 1, 0).normalized();
  const double h = 0.02;
  const auto fibres =
      fibres_of({fibre("A", {0, 0, 0}, t, rA), fibre("B", h * V::UnitZ(), h * V::UnitZ() + t, rB)},
                V(1, 1, 0));
  const ContactGeometry geometry(fibres, {}, V(1, 1, 0));
  EXPECT_NEAR((geometry.tow_axis() - t).norm(), 0.0, kTight);
  Contact c;
  c.kind = ContactKind::line;
  c.a = 0;
  c.b = 1;
  c.s_a = 0.5;
  c.s_b = 0.6;  // 0.1 mm further along the axis
  geometry.place_on_undeformed(c);
  EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kTight);
  EXPECT_NEAR(geometry.overlap_along_normal(c, 0.5 * t, V::Zero()), rA + rB - h, kTight);
}

TEST(ContactGeometry, WallOverlapIsRadiusMinusDistanceToThePlane) {
  const auto fibres = fibres_of({fibre("F", {0, 0, 0}, {1, 0, 0}, rA)});
  WallSpec floor;
  floor.id = "floor";
  floor.point = {0.3, 0.7, -0.012};
  floor.normal = {0, 0, 1};
  WallSpec slope;
  slope.id = "slope";
  slope.point = {0, 0, -0.02};
  slope.normal = V(0, 1, 1).normalized();
  const ContactGeometry geometry(fibres, {floor, slope}, V::UnitX());
  for (int w = 0; w < 2; ++w) {
    const WallSpec& wall = w == 0 ? floor : slope;
    Contact c;
    c.kind = ContactKind::wall;
    c.a = 0;
    c.b = w;
    c.slice = 4;
    c.s_a = 0.25;
    c.normal = wall.normal;
    const Contact before = c;
    geometry.place_on_undeformed(c);  // a wall contact keeps its place and normal
    EXPECT_EQ(c.s_a, before.s_a);
    EXPECT_EQ(c.normal, before.normal);
    EXPECT_FALSE(c.normal_held);
    const V centre(0.25, 0, 0);
    for (const V& u : {V(0, 0, 0), V(0.5, 0.5, -0.003), V(0, -0.004, 0.001)}) {
      const double expected = rA - wall.normal.dot(centre + u - wall.point);
      // The other side's displacement means nothing for a wall.
      EXPECT_NEAR(geometry.overlap_along_normal(c, u, V(7, 7, 7)), expected, kTight) << wall.id;
    }
  }
  // By hand for the floor: r − (0 − (−0.012)) = −0.002, then moved down 0.003: +0.001.
  Contact c;
  c.kind = ContactKind::wall;
  c.a = 0;
  c.b = 0;
  c.s_a = 0.25;
  c.normal = floor.normal;
  EXPECT_NEAR(geometry.overlap_along_normal(c, V::Zero(), V::Zero()), -0.002, kTight);
  EXPECT_NEAR(geometry.overlap_along_normal(c, V(0.5, 0.5, -0.003), V::Zero()), 0.001, kTight);
}

TEST(ContactGeometry, CoincidentCentresHoldADeterministicUnitNormal) {
  // Crossing fibres through each other (h = 0) and barely apart (below half the contact distance).
  for (double h : {0.0, 1e-12, 1e-6, 0.49 * (rA + rB), -0.49 * (rA + rB)}) {
    const auto fibres = fibres_of(
        {fibre("A", {0, 0, 0}, {1, 0, 0}, rA), fibre("B", {0.3, -0.6, h}, {0.3, 0.4, h}, rB)});
    const ContactGeometry geometry(fibres, {}, V::UnitX());
    Contact c = point_contact();
    c.normal_held = false;
    geometry.place_on_undeformed(c);
    ASSERT_TRUE(c.normal.allFinite()) << h;
    EXPECT_TRUE(c.normal_held) << h;
    EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kTight) << h;  // x × y
    Contact again = point_contact();
    geometry.place_on_undeformed(again);
    EXPECT_EQ(again.normal, c.normal);
    // The overlap stays finite and linear: (rA + rB) − (h + Δu_z).
    EXPECT_NEAR(geometry.overlap_along_normal(c, V::Zero(), V(0, 0, 0.001)), rA + rB - h - 0.001,
                kTight);
  }
  // Just above half the contact distance the direction is trusted again.
  const double h = 0.51 * (rA + rB);
  const auto fibres = fibres_of(
      {fibre("A", {0, 0, 0}, {1, 0, 0}, rA), fibre("B", {0.3, -0.6, -h}, {0.3, 0.4, -h}, rB)});
  const ContactGeometry geometry(fibres, {}, V::UnitX());
  Contact c = point_contact();
  geometry.place_on_undeformed(c);
  EXPECT_FALSE(c.normal_held);
  EXPECT_NEAR((c.normal + V::UnitZ()).norm(), 0.0, kTight);  // B is below: −z, not x × y = +z
}

TEST(ContactGeometry, CoincidentParallelFibresAndSlicesHoldTheSecondCrossSectionAxis) {
  // Tow axis x: the second cross-section axis is z. Tow axis y: (z, x), so x.
  struct Case {
    V axis, along, held;
  };
  for (const Case& k :
       {Case{V::UnitX(), V::UnitX(), V::UnitZ()}, Case{V::UnitY(), V::UnitY(), V::UnitX()}}) {
    const auto fibres = fibres_of(
        {fibre("A", V::Zero(), k.along, rA), fibre("B", 0.2 * k.along, 1.2 * k.along, rB)}, k.axis);
    const ContactGeometry geometry(fibres, {}, k.axis);
    Contact slice;
    slice.kind = ContactKind::line;
    slice.a = 0;
    slice.b = 1;
    slice.s_a = 0.5;
    slice.s_b = 0.3;
    slice.normal = V(1, 1, 1);
    geometry.place_on_undeformed(slice);
    EXPECT_TRUE(slice.normal_held);
    EXPECT_NEAR((slice.normal - k.held).norm(), 0.0, kTight);
    // Coincident parallel chords as a crossing: A's axis × B's is zero, so the same axis.
    Contact point = point_contact();
    geometry.place_on_undeformed(point);
    ASSERT_TRUE(point.normal.allFinite());
    ASSERT_TRUE(std::isfinite(point.s_a) && std::isfinite(point.s_b));
    EXPECT_TRUE(point.normal_held);
    EXPECT_NEAR((point.normal - k.held).norm(), 0.0, kTight);
    EXPECT_NEAR(geometry.overlap_along_normal(point, V::Zero(), V::Zero()), rA + rB, kTight);
  }
}

TEST(ContactGeometry, MeasureSetsEveryOverlapFromItsOwnDisplacements) {
  const double h = 0.0175;
  const auto fibres = fibres_of({fibre("A", {0, 0, 0}, {1, 0, 0}, rA),
                                 fibre("B", {0.3, -0.6, h}, {0.3, 0.4, h}, rB),
                                 fibre("C", {0, 0, -0.019}, {1, 0, -0.019}, rA)});
  WallSpec floor;
  floor.id = "floor";
  floor.point = {0, 0, -0.04};
  const ContactGeometry geometry(fibres, {floor}, V::UnitX());
  std::vector<Contact> contacts(3);
  contacts[0] = point_contact();
  contacts[1].kind = ContactKind::line;
  contacts[1].a = 0;
  contacts[1].b = 2;
  contacts[1].s_a = contacts[1].s_b = 0.7;
  contacts[2].kind = ContactKind::wall;
  contacts[2].a = 2;
  contacts[2].b = 0;
  contacts[2].s_a = 0.1;
  contacts[2].normal = floor.normal;
  for (Contact& c : contacts) geometry.place_on_undeformed(c);
  EXPECT_NEAR((contacts[1].normal + V::UnitZ()).norm(), 0.0, kTight);  // from A down to C
  const std::vector<V> u_a = {V(0, 0, -0.001), V(0, 0, -0.002), V(0, 0, -0.011)};
  const std::vector<V> u_b = {V(0, 0, 0.0005), V(0, 0, 0.0015), V(9, 9, 9)};
  geometry.measure(contacts, u_a, u_b);
  EXPECT_NEAR(contacts[0].overlap, rA + rB - (h + 0.0005 + 0.001), kTight);
  EXPECT_NEAR(contacts[1].overlap, 2 * rA - (0.019 - 0.002 - 0.0015), kTight);
  EXPECT_NEAR(contacts[2].overlap, rA - (-0.019 - 0.011 + 0.04), kTight);
}

// The deformed model: B, a height h above A, pushed sideways by w turns the slice's normal to
// (0, w, h)/√(w² + h²), and its tangent (the cross-section line ⊥ n) with it. A friction force on
// the old tangent turns into the new one at its full size, the same way round: had it been
// projected, a contact slipping at the edge of its Coulomb disk (|F| = μP) would fall inside by
// the factor cos θ = h/√(w² + h²) and count as sticking with all the slip it has.
TEST(ContactGeometry, FrictionTurnsWithTheTangentAtItsFullSize) {
  const double h = 0.018, w = 0.01;
  const auto fibres = stacked(h);
  const ContactGeometry geometry(fibres, {}, V::UnitX(), ContactGeometryModel::deformed);
  Contact c = mid_span_slice(geometry);
  ASSERT_EQ(c.tangents, 1);
  const V before = 3e-6 * c.tangent;
  c.friction = before;
  geometry.follow(c, V::Zero(), V(0, w, 0));
  const V n = V(0, w, h).normalized();
  EXPECT_NEAR((c.normal - n).norm(), 0.0, kTight);
  EXPECT_NEAR(c.friction.dot(n), 0.0, 1e-15 * before.norm());
  EXPECT_NEAR(c.friction.norm(), before.norm(), 1e-15 * before.norm());
  EXPECT_NEAR(c.friction.dot(before) / before.squaredNorm(), h / std::hypot(w, h), 1e-14);
}

// Centres that have passed through each other: B, a height h above A, moved down by 2h + e ends
// h + e below it, farther than half the contact distance, so the displaced centres give a
// direction, but one against the contact's normal. Taking it would push B on through A and set
// this slice against its neighbours, which still push B up. The slice keeps its normal and its
// overlap is measured along it: (rA + rB) + h + e, more than the radii, not (rA + rB) − (h + e).
TEST(ContactGeometry, CentresThatPassedThroughEachOtherKeepTheNormal) {
  const double h = 0.018, e = 0.002;
  const auto fibres = stacked(h);
  const ContactGeometry geometry(fibres, {}, V::UnitX(), ContactGeometryModel::deformed);
  Contact c = mid_span_slice(geometry);
  const V through(0, 0.001, -(2 * h + e));
  EXPECT_TRUE(geometry.passed_through(c, V::Zero(), through));
  geometry.follow(c, V::Zero(), through);
  EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kTight);
  EXPECT_NEAR(geometry.overlap(c, V::Zero(), through), rA + rB + h + e, kTight);
  // Short of the other side the normal follows as before.
  const V short_of_it(0, 0.001, -0.4 * h);
  EXPECT_FALSE(geometry.passed_through(c, V::Zero(), short_of_it));
  geometry.follow(c, V::Zero(), short_of_it);
  EXPECT_NEAR((c.normal - V(0, 0.001, 0.6 * h).normalized()).norm(), 0.0, kTight);
}

}  // namespace
}  // namespace fibrecheck
