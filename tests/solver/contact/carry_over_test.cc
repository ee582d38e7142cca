// Carrying forces over a re-detection. Test problem: a previous list of contacts with known forces
// and friction, and a newly found list. Known answer, by hand: a contact found again (same kind,
// fibres and slice) takes the previous force and friction and keeps its new geometry, origin = its
// index in the previous list; a new one keeps zero force and friction, origin −1; a previous
// contact that pushes (P > 0) but was not found again is appended unchanged, in the order of the
// previous list, origin = its index there; one that does not push (P = 0) is dropped.
#include "carry_over.h"

#include <gtest/gtest.h>

#include "contact_detection.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

using V = Eigen::Vector3d;

Contact make(ContactKind kind, int a, int b, int slice, double force = 0.0,
             V friction = V::Zero()) {
  Contact c;
  c.kind = kind;
  c.a = a;
  c.b = b;
  c.slice = slice;
  c.force = force;
  c.friction = friction;
  return c;
}

TEST(CarryOver, FoundAgainKeepsForceNewStartsAtZeroPushingLostIsAppended) {
  const std::vector<Contact> previous = {
      make(ContactKind::point, 0, 1, -1, 2e-4, V(1e-5, 0, 0)),  // found again
      make(ContactKind::line, 0, 2, 3, 0.0),                    // lost, not pushing: dropped
      make(ContactKind::wall, 1, 0, 5, 1.5e-4, V(0, 2e-6, 0)),  // lost, pushing: appended
      make(ContactKind::line, 0, 2, 4, 7e-5),                   // found again
  };
  std::vector<Contact> found = {
      make(ContactKind::line, 0, 2, 4),
      make(ContactKind::point, 1, 2, -1),  // new
      make(ContactKind::point, 0, 1, -1),
  };
  found[0].s_a = 0.45;  // the new geometry must stay
  found[0].overlap = -3e-6;
  found[2].normal = V::UnitY();
  const std::vector<long> origin = carry_over(previous, found);

  ASSERT_EQ(found.size(), 4u);
  ASSERT_EQ(origin, (std::vector<long>{3, -1, 0, 2}));
  EXPECT_EQ(found[0].force, 7e-5);
  EXPECT_TRUE(found[0].friction == V::Zero());
  EXPECT_EQ(found[0].s_a, 0.45);
  EXPECT_EQ(found[0].overlap, -3e-6);
  EXPECT_EQ(found[1].force, 0.0);
  EXPECT_TRUE(found[1].friction == V::Zero());
  EXPECT_EQ(found[2].force, 2e-4);
  EXPECT_TRUE(found[2].friction == V(1e-5, 0, 0));
  EXPECT_TRUE(found[2].normal == V::UnitY());
  // The appended one is the previous contact as it was.
  EXPECT_EQ(found[3].kind, ContactKind::wall);
  EXPECT_EQ(found[3].a, 1);
  EXPECT_EQ(found[3].slice, 5);
  EXPECT_EQ(found[3].force, 1.5e-4);
  EXPECT_TRUE(found[3].friction == V(0, 2e-6, 0));
}

TEST(CarryOver, KindFibresAndSliceAllTellContactsApart) {
  // Same numbers (a = 0, b = 1, slice 2) under three kinds, and neighbouring slices: none may take
  // another's force.
  const std::vector<Contact> previous = {
      make(ContactKind::wall, 0, 1, 2, 1.0), make(ContactKind::line, 0, 1, 3, 2.0),
      make(ContactKind::line, 1, 0, 2, 3.0), make(ContactKind::point, 0, 1, -1, 4.0)};
  std::vector<Contact> found = {make(ContactKind::line, 0, 1, 2),
                                make(ContactKind::point, 0, 2, -1)};
  const std::vector<long> origin = carry_over(previous, found);
  EXPECT_EQ(origin, (std::vector<long>{-1, -1, 0, 1, 2, 3}));
  EXPECT_EQ(found[0].force, 0.0);
  EXPECT_EQ(found[1].force, 0.0);
  for (std::size_t k = 2; k < found.size(); ++k)
    EXPECT_EQ(found[k].force, previous[origin[k]].force);
}

TEST(CarryOver, EmptyListsAndTheEdgeOfPushing) {
  // Nothing before: everything is new.
  {
    std::vector<Contact> found = {make(ContactKind::point, 0, 1, -1),
                                  make(ContactKind::wall, 0, 0, 1)};
    EXPECT_EQ(carry_over({}, found), (std::vector<long>{-1, -1}));
    EXPECT_EQ(found.size(), 2u);
  }
  // Nothing found: only the pushing ones survive; the smallest positive force still pushes.
  {
    const std::vector<Contact> previous = {
        make(ContactKind::line, 0, 1, 0, 0.0), make(ContactKind::line, 0, 1, 1, 1e-300),
        make(ContactKind::line, 0, 1, 2, -1e-9), make(ContactKind::line, 0, 1, 3, 5e-5)};
    std::vector<Contact> found;
    EXPECT_EQ(carry_over(previous, found), (std::vector<long>{1, 3}));
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0].force, 1e-300);
    EXPECT_EQ(found[1].force, 5e-5);
  }
  // Both empty.
  {
    std::vector<Contact> found;
    EXPECT_TRUE(carry_over({}, found).empty());
    EXPECT_TRUE(found.empty());
  }
}

TEST(CarryOver, AppendedContactsComeInThePreviousOrderWhateverTheHashing) {
  // 500 pushing slices of which every third is found again (in reverse order): the others are
  // appended in increasing previous index, the same on every call.
  std::vector<Contact> previous;
  for (int i = 0; i < 500; ++i)
    previous.push_back(make(ContactKind::line, i % 7, 7 + i % 5, i, 1e-6 * (i + 1)));
  std::vector<Contact> found;
  for (int i = 499; i >= 0; --i)
    if (i % 3 == 0) found.push_back(make(ContactKind::line, i % 7, 7 + i % 5, i));
  const std::size_t again = found.size();
  std::vector<Contact> copy = found;
  const std::vector<long> origin = carry_over(previous, found);
  EXPECT_EQ(carry_over(previous, copy), origin);
  ASSERT_EQ(found.size(), 500u);
  for (std::size_t k = 0; k < again; ++k) {
    EXPECT_EQ(origin[k], 499 - 3 * static_cast<long>(k) - 499 % 3);
    EXPECT_EQ(found[k].force, previous[origin[k]].force);
  }
  long last = -1;
  for (std::size_t k = again; k < found.size(); ++k) {
    EXPECT_GT(origin[k], last);
    EXPECT_NE(origin[k] % 3, 0);
    last = origin[k];
  }
}

TEST(CarryOver, KeysSurviveARebuildOfTheCandidateList) {
  // The same state detected twice: every contact is found again, in place, with its force.
  Scene scene = testing::parallel(1e-4, 12);
  scene.fibres.push_back(testing::fibre("X", {0.5, -0.5, 0.036}, {0.5, 0.5, 0.036}));
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  const std::vector<std::vector<V>> grid(fibres.size(),
                                         std::vector<V>(detector.grid().size(), V::Zero()));
  std::vector<Contact> previous = detector.detect(grid);
  ASSERT_EQ(previous.size(), 13u);  // 12 slices of the tow pair, X on A
  for (std::size_t k = 0; k < previous.size(); ++k) previous[k].force = 1e-5 * (k + 1);
  std::vector<Contact> found = detector.detect(grid);
  const std::vector<long> origin = carry_over(previous, found);
  ASSERT_EQ(found.size(), previous.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    EXPECT_EQ(origin[k], static_cast<long>(k));
    EXPECT_EQ(found[k].force, previous[k].force);
  }
}

}  // namespace
}  // namespace fibrecheck
