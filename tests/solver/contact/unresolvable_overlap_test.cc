// Overlaps that no force can resolve (DESIGN §2, §8). Test problem: fibres A (L = 1 mm, r = 0.01,
// E = 80 000) and B (L = 2 mm, r = 0.008, E = 70 000). Known answers, written out here:
//  - the immovable compliance is 1e-12 · max L³/(48EI) with EI = E·πr⁴/4, here B's
//    8/(48·70 000·π·0.008⁴/4);
//  - an overlap above the tolerance at a contact whose self-compliance is at or below it is
//    reported, with the fibre (or wall) ids, the position and the overlap in the message; an
//    overlap at or below the tolerance, or at a contact that can move, is not;
//  - two fibres whose pinned supports overlap (testing::overlapping_supports, B 0.015 above A at
//    the shared start, overlap 0.005) are unresolvable at s = 0 of both.
#include "unresolvable_overlap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "compliance_operator.h"
#include "contact_detection.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

using testing::fibre;

std::vector<Fibre> two_fibres() {
  return {make_fibre(fibre("A", {0, 0, 0}, {1, 0, 0}, 0.01, 80000), Eigen::Vector3d::UnitX(), 10),
          make_fibre(fibre("B", {0, 0, 1}, {0, 2, 1}, 0.008, 70000), Eigen::Vector3d::UnitX(), 10)};
}

Contact contact(ContactKind kind, double s_a, double s_b, int b = 1) {
  Contact c;
  c.kind = kind;
  c.a = 0;
  c.b = b;
  c.s_a = s_a;
  c.s_b = s_b;
  return c;
}

TEST(UnresolvableOverlap, ImmovableComplianceIsATrillionthOfTheLargestMidSpanCompliance) {
  const auto fibres = two_fibres();
  const double EI_b = 70000 * M_PI * std::pow(0.008, 4) / 4;
  const double EI_a = 80000 * M_PI * std::pow(0.01, 4) / 4;
  ASSERT_GT(8 / (48 * EI_b), 1 / (48 * EI_a));  // B is the softer one
  // One rounding per operation on numbers of order one: 1e-14 relative.
  EXPECT_NEAR(immovable_compliance(fibres), 1e-12 * 8 / (48 * EI_b),
              1e-14 * 1e-12 * 8 / (48 * EI_b));
  EXPECT_NEAR(immovable_compliance({fibres[0]}), 1e-12 / (48 * EI_a), 1e-14 * 1e-12 / (48 * EI_a));
  EXPECT_EQ(immovable_compliance({}), 0.0);
}

TEST(UnresolvableOverlap, ReportsAnOverlapWhereNothingCanMoveWithIdsAndPosition) {
  const auto fibres = two_fibres();
  const double tolerance = 1e-7;
  const std::vector<Contact> contacts = {contact(ContactKind::point, 0.25, 0.75)};
  const auto why = find_unresolvable_overlap(contacts, {0.005}, {0.0}, tolerance, fibres, {});
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("fibres A and B"), std::string::npos) << *why;
  EXPECT_NE(why->find("s = 0.25 of A"), std::string::npos) << *why;
  EXPECT_NE(why->find("s = 0.75 of B"), std::string::npos) << *why;
  EXPECT_NE(why->find("0.005"), std::string::npos) << *why;
  EXPECT_NE(why->find("cannot be resolved"), std::string::npos) << *why;
}

TEST(UnresolvableOverlap, BelowToleranceOrMovableIsNothing) {
  const auto fibres = two_fibres();
  const double immovable = immovable_compliance(fibres);
  const double tolerance = 1e-7;
  const std::vector<Contact> one = {contact(ContactKind::point, 0.0, 0.0)};
  struct Case {
    double overlap, compliance;
    bool reported;
  };
  for (const Case& k : {
           Case{0.005, 0.0, true},
           Case{0.005, immovable, true},           // at the threshold: still immovable
           Case{0.005, 1.001 * immovable, false},  // just movable
           Case{0.005, 1e-3, false},
           Case{tolerance, 0.0, false},  // at the tolerance: not an overlap
           Case{1.001 * tolerance, 0.0, true}, Case{0.0, 0.0, false},
           Case{-0.01, 0.0, false},  // a gap
       }) {
    const auto why =
        find_unresolvable_overlap(one, {k.overlap}, {k.compliance}, tolerance, fibres, {});
    EXPECT_EQ(why.has_value(), k.reported)
        << "overlap " << k.overlap << ", compliance " << k.compliance;
  }
  EXPECT_FALSE(find_unresolvable_overlap({}, {}, {}, tolerance, fibres, {}).has_value());
}

TEST(UnresolvableOverlap, TheFirstOffendingContactIsNamedWallsAndSlicesToo) {
  const auto fibres = two_fibres();
  WallSpec floor;
  floor.id = "floor";
  floor.point = {0, 0, -0.01};  // A's supports just touch it (a support inside it is unresolvable)
  std::vector<Contact> contacts = {contact(ContactKind::point, 0.5, 0.5),
                                   contact(ContactKind::wall, 0.125, 0.0, 0),
                                   contact(ContactKind::line, 0.375, 0.625)};
  contacts[2].slice = 7;
  // The first is movable, the second and third are not: the wall contact is named.
  const auto wall = find_unresolvable_overlap(contacts, {0.01, 0.002, 0.003}, {1e-2, 0.0, 0.0},
                                              1e-7, fibres, {floor});
  ASSERT_TRUE(wall.has_value());
  EXPECT_NE(wall->find("fibre A and wall floor at s = 0.125 of A"), std::string::npos) << *wall;
  EXPECT_NE(wall->find("0.002"), std::string::npos) << *wall;
  // With the wall movable the slice is named, with its index.
  const auto slice = find_unresolvable_overlap(contacts, {0.01, 0.002, 0.003}, {1e-2, 1e-2, 0.0},
                                               1e-7, fibres, {floor});
  ASSERT_TRUE(slice.has_value());
  EXPECT_NE(slice->find("fibres A and B at s = 0.375 of A (s = 0.625 of B), slice 7"),
            std::string::npos)
      << *slice;
  EXPECT_NE(slice->find("0.003"), std::string::npos) << *slice;
}

TEST(UnresolvableOverlap, OverlappingPinnedSupportsAreFoundInADetectedScene) {
  const Scene scene = testing::overlapping_supports();
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  const std::vector<std::vector<Eigen::Vector3d>> grid(
      fibres.size(), std::vector<Eigen::Vector3d>(detector.grid().size(), Eigen::Vector3d::Zero()));
  const std::vector<Contact> contacts = detector.detect(grid);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].s_a, 0.0, 1e-15);
  EXPECT_NEAR(contacts[0].s_b, 0.0, 1e-15);
  std::vector<double> overlap, compliance;
  for (const Contact& c : contacts) {
    overlap.push_back(c.overlap);
    compliance.push_back(self_compliance(c, fibres));
  }
  EXPECT_NEAR(overlap[0], 0.005, 1e-16);  // rA + rB − 0.015, one rounding
  EXPECT_LE(compliance[0], immovable_compliance(fibres));
  const auto why = find_unresolvable_overlap(contacts, overlap, compliance,
                                             scene.overlap_tolerance(), fibres, scene.walls);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("fibres A and B at s = 0 of A (s = 0 of B)"), std::string::npos) << *why;
  // The same pair crossing in the middle of both can be pushed apart: nothing to report.
  const Scene free = testing::crossing(0.5, 0.5, 0.005);
  const auto free_fibres = make_fibres(free);
  Contact middle = contacts[0];
  middle.s_a = middle.s_b = 0.5;
  EXPECT_FALSE(find_unresolvable_overlap({middle}, {0.005}, {self_compliance(middle, free_fibres)},
                                         1e-7, free_fibres, {})
                   .has_value());
}

}  // namespace
}  // namespace fibrecheck

namespace fibrecheck {
namespace {

// Supports closer than the sum of the radii overlap where neither fibre can move, though no
// slice or contact point sits there (slices lie at the midpoints of their intervals).
TEST(OverlappingSupports, CoincidentFibresAndSharedSupportsAreFound) {
  Scene same;
  same.fibres = {testing::fibre("A", {0, 0, 0}, {1, 0, 0}),
                 testing::fibre("B", {0, 0, 0}, {1, 0, 0})};
  const auto why = find_overlapping_supports(make_fibres(same), 1e-7);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("overlap 0.02 mm between fibres A and B at s = 0 of A (s = 0 of B)"),
            std::string::npos)
      << *why;
  // Crossing right above one support, but the other fibre's supports are far: A's support does
  // not overlap B's, so B can yield there.
  Scene one;
  one.fibres = {testing::fibre("A", {0, 0, 0}, {1, 0, 0}),
                testing::fibre("B", {0, -0.5, 0.0199}, {0, 0.5, 0.0199})};
  EXPECT_FALSE(find_overlapping_supports(make_fibres(one), 1e-7).has_value());
  // Supports that just touch, or overlap by less than the tolerance, are fine.
  Scene touching;
  touching.fibres = {testing::fibre("A", {0, 0, 0}, {1, 0, 0}),
                     testing::fibre("B", {0, 0, 0.02}, {1, 0, 0.02})};
  EXPECT_FALSE(find_overlapping_supports(make_fibres(touching), 1e-7).has_value());
}

}  // namespace
}  // namespace fibrecheck
