// Candidate contacts of a deformed state (seed §4.3.3). Test problems and known answers, written
// out here (r = 0.01 mm unless stated, margin m = 0.1·r_min = 0.001 mm):
//  - A along x and B along y crossing at 0.3 of A and 0.6 of B with centre distance h: one point
//    contact at s_A = 0.3, s_B = 0.6, normal +z, overlap rA + rB − h, weight 1, slice −1 — when
//    the gap h − rA − rB is below m (strictly), and none otherwise.
//  - Two tow fibres along x, A resting on B (testing::parallel): one line contact per slice i,
//    s_A = s_B = (i + 1/2)/n, weight 1/n (Eq. 4.28), normal −z (from A down to B), overlap 0;
//    with B shifted along the axis the slices span both fibres and s_A, s_B are the fractions of
//    each fibre at the slice's axial position.
//  - A fibre a gap g < m above a floor (testing::pressed_onto_wall): a wall contact at each of the
//    n quadrature points (j + 1/2)/n, overlap −g, weight 1/n, the wall's normal.
//  - Displacements: a rigid shift by u changes every gap by n·u; a shift linear along the fibre,
//    u_z = −3m·s on a gap of 2m, leaves the gap 2m − 3m·s, so exactly the stations with s > 1/3
//    are candidates (a linear shift is exactly what the detection grid interpolates).
//  - LineQuadrature::gauss(c): 2c line contacts per pair, weights 1/(2c), at the Gauss points.
//  - Sliding: A m/2 above B, shifted by (0, 1.5r, −0.3m). Along the undeformed normal (−z) the gap
//    is 0.2m, so under the linearised contact every slice is a candidate with overlap −0.2m;
//    the displaced centres are √((1.5r)² + (2r + 0.2m)²) − 2r = 5.16m apart, so under the
//    deformed contact none is. Shifted by (0, 1.5r, +0.6m) the gap is 1.1m under both: none.
//    A crossing with a gap of m/2 whose fibre B moves by (1 mm, 0, −0.3m), past A's end: along
//    the undeformed normal (+z, at the chords' closest points) the gap is 0.2m, a candidate with
//    overlap −0.2m; the displaced fibres are 0.3 mm apart, no candidate.
#include "contact_detection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_scenes.h"

namespace fibrecheck {
namespace {

using V = Eigen::Vector3d;
using testing::fibre;
using Grid = std::vector<std::vector<V>>;

// Overlaps are differences of coordinates of size ≤ 0.05 mm: rounding ~1e-17, so 1e-16 absolute.
// Stations from the line quadrature and the chords' closest points: a few ulp of 1, so 1e-14.
constexpr double kOverlap = 1e-16;
constexpr double kStation = 1e-14;

Grid zero_grid(const ContactDetector& detector, std::size_t fibres) {
  return Grid(fibres, std::vector<V>(detector.grid().size(), V::Zero()));
}

/// Every grid point of fibre `f` displaced by u(s).
template <class F>
void displace(Grid& grid, const ContactDetector& detector, int f, F u) {
  for (std::size_t j = 0; j < detector.grid().size(); ++j) grid[f][j] = u(detector.grid()[j]);
}

int count(const std::vector<Contact>& contacts, ContactKind kind) {
  int n = 0;
  for (const Contact& c : contacts) n += c.kind == kind;
  return n;
}

TEST(ContactDetection, CandidateMarginIsATenthOfTheSmallestRadius) {
  const std::vector<Fibre> fibres = make_fibres(testing::crossing(0.3, 0.6, 0, 0.01, 0.004));
  EXPECT_DOUBLE_EQ(candidate_margin(fibres), 0.0004);
  EXPECT_DOUBLE_EQ(candidate_margin(fibres, 0.5), 0.002);
  EXPECT_DOUBLE_EQ(candidate_margin(fibres, 0.0), 0.0);
  EXPECT_EQ(kCandidateMarginFactor, 0.1);
}

TEST(ContactDetection, GridHasMaxOfSlicesAndTwentySteps) {
  for (int slices : {1, 5, 20, 50, 73}) {
    Scene scene = testing::crossing(0.3, 0.6, 0);
    scene.contact.slices = slices;
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, candidate_margin(fibres));
    const int m = std::max(slices, 20);
    ASSERT_EQ(detector.grid().size(), static_cast<std::size_t>(m + 1)) << slices;
    for (int j = 0; j <= m; ++j) EXPECT_NEAR(detector.grid()[j], double(j) / m, 1e-16);
    EXPECT_EQ(detector.grid().front(), 0.0);
    EXPECT_EQ(detector.grid().back(), 1.0);
  }
}

TEST(ContactDetection, CrossingFibresAreOnePointContactAtTheClosestPointsOfTheChords) {
  struct Case {
    double sa, sb, overlap, ra, rb;
  };
  for (const Case& k : {Case{0.3, 0.6, 0.002, 0.01, 0.01}, Case{0.7, 0.2, 0.001, 0.01, 0.006},
                        Case{0.5, 0.5, 0.0, 0.01, 0.01}, Case{0.05, 0.95, 0.0005, 0.008, 0.01}}) {
    const Scene scene = testing::crossing(k.sa, k.sb, k.overlap, k.ra, k.rb);
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, candidate_margin(fibres));
    const std::vector<Contact> contacts = detector.detect(zero_grid(detector, fibres.size()));
    ASSERT_EQ(contacts.size(), 1u) << k.sa;
    const Contact& c = contacts[0];
    EXPECT_EQ(c.kind, ContactKind::point);
    EXPECT_EQ(c.a, 0);
    EXPECT_EQ(c.b, 1);
    EXPECT_EQ(c.slice, -1);
    EXPECT_EQ(c.weight, 1.0);
    EXPECT_EQ(c.force, 0.0);
    EXPECT_TRUE(c.friction == V::Zero());
    EXPECT_NEAR(c.s_a, k.sa, kStation);
    EXPECT_NEAR(c.s_b, k.sb, kStation);
    EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kStation);
    EXPECT_FALSE(c.normal_held);
    EXPECT_NEAR(c.overlap, k.overlap, kOverlap);
  }
}

TEST(ContactDetection, APairIsACandidateOnlyWhenItsGapIsBelowTheMargin) {
  const double margin = 0.001;
  // Gaps well inside, just inside, just outside and far outside; 1e-6 relative is 1e-9 mm, far
  // above the rounding of the centre distance (~1e-17 mm).
  struct Case {
    double gap;
    bool candidate;
  };
  for (const Case& k : {Case{0.0, true}, Case{1e-12, true}, Case{0.5 * margin, true},
                        Case{margin * (1 - 1e-6), true}, Case{margin * (1 + 1e-6), false},
                        Case{10 * margin, false}}) {
    const Scene scene = testing::crossing(0.3, 0.6, -k.gap);
    const auto fibres = make_fibres(scene);
    ASSERT_DOUBLE_EQ(candidate_margin(fibres), margin);
    const ContactDetector detector(fibres, scene, margin);
    const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
    ASSERT_EQ(contacts.size(), k.candidate ? 1u : 0u) << "gap " << k.gap;
    if (k.candidate) {
      EXPECT_NEAR(contacts[0].overlap, -k.gap, kOverlap) << "gap " << k.gap;
    }
  }
}

TEST(ContactDetection, TheMarginIsDecidedByTheDistanceNotByBoundingBoxes) {
  // B tilted 45° about x, crossing A at 0.3 with the gap along n₀ = (0, −1, 1)/√2: the boxes of
  // the two fibres overlap whatever the gap, so only the distance can tell.
  const double m = 0.001;
  const V n0 = V(0, -1, 1).normalized(), d = V(0, 1, 1).normalized();
  for (const auto& [gap, candidate] :
       {std::pair{m * (1 - 1e-6), true}, std::pair{m * (1 + 1e-6), false}, std::pair{5 * m, false},
        std::pair{0.0, true}}) {
    const V centre = V(0.3, 0, 0) + (0.02 + gap) * n0;
    Scene scene;
    scene.fibres = {fibre("A", {0, 0, 0}, {1, 0, 0}),
                    fibre("B", centre - 0.5 * d, centre + 0.5 * d)};
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
    ASSERT_EQ(contacts.size(), candidate ? 1u : 0u) << "gap " << gap;
    if (candidate) {
      EXPECT_NEAR(contacts[0].overlap, -gap, 1e-15) << "gap " << gap;  // n₀ has irrational parts
      EXPECT_NEAR((contacts[0].normal - n0).norm(), 0.0, kStation);
    }
  }
}

TEST(ContactDetection, FibreEndingBesideAnotherTouchesAtItsEnd) {
  // B along y in A's plane, beyond A's end x = 1 by the contact distance plus 0.5m (candidate) or
  // plus 2m (not): the closest point of A is its end, s_A = 1, and the normal is +x.
  const double m = 0.001;
  for (double extra : {0.5 * m, 2 * m}) {
    Scene scene;
    const double x = 1.0 + 0.02 + extra;
    scene.fibres = {fibre("A", {0, 0, 0}, {1, 0, 0}), fibre("B", {x, -0.5, 0}, {x, 0.5, 0})};
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
    if (extra > m) {
      EXPECT_TRUE(contacts.empty());
      continue;
    }
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].s_a, 1.0, kStation);
    EXPECT_NEAR(contacts[0].s_b, 0.5, kStation);
    EXPECT_NEAR((contacts[0].normal - V::UnitX()).norm(), 0.0, kStation);
    EXPECT_NEAR(contacts[0].overlap, -extra, 1e-15);  // x − 1.02 rounds at ~1e-16
  }
}

TEST(ContactDetection, FibresThroughEachOtherHoldAFiniteNormal) {
  // Centrelines intersecting (overlap rA + rB): no side is preferred; the normal is x × y.
  const Scene scene = testing::crossing(0.4, 0.5, 0.02);
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
  ASSERT_EQ(contacts.size(), 1u);
  ASSERT_TRUE(contacts[0].normal.allFinite());
  EXPECT_TRUE(contacts[0].normal_held);
  EXPECT_NEAR((contacts[0].normal - V::UnitZ()).norm(), 0.0, kStation);
  EXPECT_NEAR(contacts[0].overlap, 0.02, kOverlap);
}

TEST(ContactDetection, ParallelFibresOffTheTowAxisAreOnePointContact) {
  // Both along y (tow axis x): not sliced; their chords are parallel (Eq. 4.24): the contact sits
  // in the middle of the common stretch, s = 0.5 on both, normal +x, touching.
  Scene scene;
  scene.fibres = {fibre("A", {0, 0, 0}, {0, 1, 0}), fibre("B", {0.02, 0, 0}, {0.02, 1, 0})};
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  EXPECT_FALSE(detector.slicing());
  EXPECT_TRUE(detector.point_search());
  const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].kind, ContactKind::point);
  EXPECT_NEAR(contacts[0].s_a, 0.5, kStation);
  EXPECT_NEAR(contacts[0].s_b, 0.5, kStation);
  EXPECT_NEAR((contacts[0].normal - V::UnitX()).norm(), 0.0, kStation);
  EXPECT_NEAR(contacts[0].overlap, 0.0, kOverlap);
}

TEST(ContactDetection, ParallelTowFibresGiveOneLineContactPerSliceOfWeightOneOverN) {
  for (int n : {1, 4, 50}) {
    const Scene scene = testing::parallel(1e-4, n);  // A (r 0.01) on B (r 0.008), touching
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, candidate_margin(fibres));
    const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
    ASSERT_EQ(contacts.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const Contact& c = contacts[i];
      EXPECT_EQ(c.kind, ContactKind::line);
      EXPECT_EQ(c.a, 0);
      EXPECT_EQ(c.b, 1);
      EXPECT_EQ(c.slice, i);
      EXPECT_DOUBLE_EQ(c.weight, 1.0 / n);
      EXPECT_NEAR(c.s_a, (i + 0.5) / n, kStation);
      EXPECT_NEAR(c.s_b, (i + 0.5) / n, kStation);
      EXPECT_NEAR(detector.slice_position(i), (i + 0.5) / n, kStation);
      EXPECT_NEAR((c.normal + V::UnitZ()).norm(), 0.0, kStation);
      EXPECT_NEAR(c.overlap, 0.0, kOverlap);
    }
  }
}

TEST(ContactDetection, SlicesSpanTheTowAndTakeEachFibresOwnFraction) {
  // A on [0, 1], B on [0.2, 1.2] along x: the tow spans [0, 1.2]; six slices at x = 0.1, 0.3, …,
  // 1.1. Slices 1–4 (x = 0.3…0.9) cut both: s_A = x, s_B = x − 0.2.
  Scene scene;
  scene.fibres = {fibre("A", {0, 0, 0.02}, {1, 0, 0.02}), fibre("B", {0.2, 0, 0}, {1.2, 0, 0})};
  scene.contact.slices = 6;
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(detector.slice_position(i), 0.1 + 0.2 * i, kStation);
  const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
  ASSERT_EQ(contacts.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const double x = 0.3 + 0.2 * k;
    EXPECT_EQ(contacts[k].slice, k + 1);
    EXPECT_NEAR(contacts[k].s_a, x, kStation);
    EXPECT_NEAR(contacts[k].s_b, x - 0.2, kStation);
    EXPECT_DOUBLE_EQ(contacts[k].weight, 1.0 / 6);
    EXPECT_NEAR(contacts[k].overlap, 0.0, kOverlap);
  }
  // B reversed (from x = 1.2 back to 0.2): the same slices, s_B = 1.2 − x.
  std::swap(scene.fibres[1].start, scene.fibres[1].end);
  const auto reversed = make_fibres(scene);
  const ContactDetector back(reversed, scene, candidate_margin(reversed));
  const auto again = back.detect(zero_grid(back, reversed.size()));
  ASSERT_EQ(again.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(again[k].slice, k + 1);
    EXPECT_NEAR(again[k].s_a, 0.3 + 0.2 * k, kStation);
    EXPECT_NEAR(again[k].s_b, 1.2 - (0.3 + 0.2 * k), kStation);
    EXPECT_NEAR(again[k].overlap, 0.0, kOverlap);
  }
}

TEST(ContactDetection, GaussLineQuadratureGivesTwoPointsPerCell) {
  const Scene scene = testing::parallel(1e-4, 10);
  const auto fibres = make_fibres(scene);
  const int cells = 7;
  const ContactDetector detector(fibres, scene, candidate_margin(fibres),
                                 LineQuadrature::gauss(cells));
  EXPECT_EQ(detector.line_quadrature().size(), 2 * cells);
  const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
  ASSERT_EQ(contacts.size(), static_cast<std::size_t>(2 * cells));
  const double offset = 1.0 / (2.0 * std::sqrt(3.0));
  double total = 0;
  for (int k = 0; k < 2 * cells; ++k) {
    const double expected = (k / 2 + 0.5 + (k % 2 ? offset : -offset)) / cells;
    EXPECT_EQ(contacts[k].kind, ContactKind::line);
    EXPECT_EQ(contacts[k].slice, k);
    EXPECT_NEAR(contacts[k].s_a, expected, kStation);
    EXPECT_NEAR(contacts[k].s_b, expected, kStation);
    EXPECT_DOUBLE_EQ(contacts[k].weight, 1.0 / (2 * cells));
    total += contacts[k].weight;
  }
  EXPECT_NEAR(total, 1.0, 1e-15);
}

TEST(ContactDetection, ThreeTowFibresInARowPairOnlyNeighbours) {
  // A, C, D along x at y = 0, 0.02, 0.04 (r 0.01): per slice A–C and C–D touch, A–D is 0.02 apart.
  Scene scene;
  scene.fibres = {fibre("A", {0, 0, 0}, {1, 0, 0}), fibre("C", {0, 0.02, 0}, {1, 0.02, 0}),
                  fibre("D", {0, 0.04, 0}, {1, 0.04, 0})};
  scene.contact.slices = 5;
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  EXPECT_TRUE(detector.broad_phase());
  const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
  ASSERT_EQ(contacts.size(), 10u);
  for (const Contact& c : contacts) {
    EXPECT_EQ(c.kind, ContactKind::line);
    EXPECT_EQ(c.b, c.a + 1);
    EXPECT_NEAR((c.normal - V::UnitY()).norm(), 0.0, kStation);
    EXPECT_NEAR(c.overlap, 0.0, kOverlap);
  }
}

TEST(ContactDetection, TowPairIsSlicedAndACrossingFibreIsPointSearched) {
  // A and C along x side by side (touching), B along y on top of both at x = 0.5.
  Scene scene;
  scene.fibres = {fibre("A", {0, 0, 0}, {1, 0, 0}), fibre("C", {0, 0.02, 0}, {1, 0.02, 0}),
                  fibre("B", {0.5, -0.5, 0.02}, {0.5, 0.5, 0.02})};
  scene.contact.slices = 10;
  const auto fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  EXPECT_TRUE(detector.slicing());
  EXPECT_TRUE(detector.point_search());
  EXPECT_TRUE(detector.broad_phase());
  EXPECT_FALSE(detector.walls());
  const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
  EXPECT_EQ(count(contacts, ContactKind::line), 10);
  ASSERT_EQ(count(contacts, ContactKind::point), 2);
  for (const Contact& c : contacts) {
    if (c.kind == ContactKind::line) {
      EXPECT_EQ(c.a, 0);
      EXPECT_EQ(c.b, 1);
      continue;
    }
    EXPECT_EQ(c.b, 2);  // never a point contact between the two tow fibres
    EXPECT_NEAR(c.s_a, 0.5, kStation);
    EXPECT_NEAR(c.s_b, c.a == 0 ? 0.5 : 0.52, kStation);
    EXPECT_NEAR((c.normal - V::UnitZ()).norm(), 0.0, kStation);
    EXPECT_NEAR(c.overlap, 0.0, kOverlap);
  }
}

TEST(ContactDetection, WallsGiveWallContactsAtTheQuadraturePoints) {
  const double margin = 0.001;
  for (int walls : {1, 2}) {
    const Scene scene = testing::pressed_onto_wall(1e-4, 0.4 * margin, walls);  // 51 slices
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, margin);
    EXPECT_FALSE(detector.slicing());
    EXPECT_FALSE(detector.point_search());
    EXPECT_FALSE(detector.broad_phase());
    EXPECT_TRUE(detector.walls());
    const auto contacts = detector.detect(zero_grid(detector, fibres.size()));
    ASSERT_EQ(contacts.size(), static_cast<std::size_t>(51 * walls));
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const Contact& c = contacts[k];
      const int j = static_cast<int>(k) / walls;
      EXPECT_EQ(c.kind, ContactKind::wall);
      EXPECT_EQ(c.a, 0);
      EXPECT_EQ(c.b, static_cast<int>(k) % walls);
      EXPECT_EQ(c.slice, j);
      EXPECT_NEAR(c.s_a, (j + 0.5) / 51, kStation);
      EXPECT_DOUBLE_EQ(c.weight, 1.0 / 51);
      EXPECT_TRUE(c.normal == V::UnitZ());
      EXPECT_NEAR(c.overlap, -0.4 * margin, kOverlap);
    }
  }
  // A gap beyond the margin gives nothing.
  const Scene far = testing::pressed_onto_wall(1e-4, 1.5 * margin);
  const auto fibres = make_fibres(far);
  const ContactDetector detector(fibres, far, margin);
  EXPECT_TRUE(detector.detect(zero_grid(detector, fibres.size())).empty());
}

TEST(ContactDetection, DisplacementsMoveCrossingCandidatesInAndOut) {
  const double m = 0.001;
  // A gap of 2m closed by a rigid shift of B by −1.5m along z (and 0.1 mm along x, which only
  // moves where the deformed fibres are closest): the overlap is −0.5m, at the undeformed place.
  {
    const Scene scene = testing::crossing(0.3, 0.6, -2 * m);
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    Grid grid = zero_grid(detector, fibres.size());
    EXPECT_TRUE(detector.detect(grid).empty());
    displace(grid, detector, 1, [&](double) { return V(0.1, 0, -1.5 * m); });
    const auto contacts = detector.detect(grid);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].s_a, 0.3, kStation);
    EXPECT_NEAR(contacts[0].s_b, 0.6, kStation);
    EXPECT_NEAR(contacts[0].overlap, -0.5 * m, kOverlap);
  }
  // An overlap of 2m lifted away by 2m + 2m: no longer a candidate; by 2m + 0.5m: gap 0.5m.
  {
    const Scene scene = testing::crossing(0.3, 0.6, 2 * m);
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    Grid grid = zero_grid(detector, fibres.size());
    displace(grid, detector, 0, [&](double) { return V(0, 0, -4 * m); });
    EXPECT_TRUE(detector.detect(grid).empty());
    displace(grid, detector, 0, [&](double) { return V(0, 0, -2.5 * m); });
    const auto contacts = detector.detect(grid);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].overlap, -0.5 * m, kOverlap);
  }
}

TEST(ContactDetection, LinearDisplacementBringsExactlyTheStationsBeyondAThirdIn) {
  const double m = 0.001;
  const auto u = [&](double s) { return V(0, 0, -3 * m * s); };
  // Line contacts: A 2m above B, 50 slices at (i + 1/2)/50; s > 1/3 from i = 17 on: 33 contacts.
  {
    Scene scene = testing::parallel(1e-4, 50, 0.01, 0.01);
    scene.fibres[0].start.z() += 2 * m;
    scene.fibres[0].end.z() += 2 * m;
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    Grid grid = zero_grid(detector, fibres.size());
    EXPECT_TRUE(detector.detect(grid).empty());
    displace(grid, detector, 0, u);
    const auto contacts = detector.detect(grid);
    ASSERT_EQ(contacts.size(), 33u);
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const double s = (k + 17 + 0.5) / 50;
      EXPECT_EQ(contacts[k].slice, static_cast<int>(k) + 17);
      EXPECT_NEAR(contacts[k].overlap, -2 * m + 3 * m * s, kOverlap);
    }
  }
  // Wall contacts: a gap of 2m, 51 stations at (j + 1/2)/51; s > 1/3 from j = 17 on: 34 contacts.
  {
    const Scene scene = testing::pressed_onto_wall(1e-4, 2 * m);
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    Grid grid = zero_grid(detector, fibres.size());
    EXPECT_TRUE(detector.detect(grid).empty());
    displace(grid, detector, 0, u);
    const auto contacts = detector.detect(grid);
    ASSERT_EQ(contacts.size(), 34u);
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const double s = (k + 17 + 0.5) / 51;
      EXPECT_EQ(contacts[k].slice, static_cast<int>(k) + 17);
      EXPECT_NEAR(contacts[k].s_a, s, kStation);
      EXPECT_NEAR(contacts[k].overlap, -2 * m + 3 * m * s, kOverlap);
    }
  }
}

TEST(ContactDetection, UnderTheLinearisedContactTheOverlapAlongTheUndeformedNormalDecides) {
  const double m = 0.001, r = 0.01;
  Scene scene = testing::parallel(1e-4, 50, r, r);
  scene.fibres[0].start.z() += 0.5 * m;
  scene.fibres[0].end.z() += 0.5 * m;
  for (ContactGeometryModel model :
       {ContactGeometryModel::linearised, ContactGeometryModel::deformed}) {
    scene.contact.geometry = model;
    const auto fibres = make_fibres(scene);
    const ContactDetector detector(fibres, scene, m);
    Grid grid = zero_grid(detector, fibres.size());
    displace(grid, detector, 0, [&](double) { return V(0, 1.5 * r, -0.3 * m); });
    const auto contacts = detector.detect(grid);
    if (model == ContactGeometryModel::deformed) {
      EXPECT_TRUE(contacts.empty());
    } else {
      ASSERT_EQ(contacts.size(), 50u);
      for (const Contact& c : contacts) {
        EXPECT_NEAR((c.normal + V::UnitZ()).norm(), 0.0, kStation);
        EXPECT_NEAR(c.overlap, -0.2 * m, kOverlap);
      }
    }
    displace(grid, detector, 0, [&](double) { return V(0, 1.5 * r, 0.6 * m); });
    EXPECT_TRUE(detector.detect(grid).empty());
  }
}

TEST(ContactDetection, UnderTheLinearisedContactACrossingIsMeasuredAtTheChordsClosestPoints) {
  const double m = 0.001;
  Scene crossing = testing::crossing(0.3, 0.6, -0.5 * m);
  for (ContactGeometryModel model :
       {ContactGeometryModel::linearised, ContactGeometryModel::deformed}) {
    crossing.contact.geometry = model;
    const auto fibres = make_fibres(crossing);
    const ContactDetector detector(fibres, crossing, m);
    Grid grid = zero_grid(detector, fibres.size());
    displace(grid, detector, 1, [&](double) { return V(1.0, 0, -0.3 * m); });
    const auto contacts = detector.detect(grid);
    if (model == ContactGeometryModel::deformed) {
      EXPECT_TRUE(contacts.empty());
    } else {
      ASSERT_EQ(contacts.size(), 1u);
      EXPECT_EQ(contacts[0].kind, ContactKind::point);
      EXPECT_NEAR(contacts[0].s_a, 0.3, kStation);
      EXPECT_NEAR(contacts[0].s_b, 0.6, kStation);
      EXPECT_NEAR((contacts[0].normal - V::UnitZ()).norm(), 0.0, kStation);
      EXPECT_NEAR(contacts[0].overlap, -0.2 * m, kOverlap);
    }
  }
}

TEST(ContactDetection, StagesFollowTheScene) {
  struct Case {
    const char* name;
    Scene scene;
    bool slicing, points, broad, walls;
  };
  Scene single;
  single.fibres = {fibre("A", {0, 0, 0}, {1, 0, 0})};
  Scene off_axis_pair;
  off_axis_pair.fibres = {fibre("A", {0, 0, 0}, {0, 1, 0}), fibre("B", {0.5, 0, 0}, {0.5, 1, 0})};
  Scene tow_and_crossing = testing::parallel(1e-4, 10);
  tow_and_crossing.fibres.push_back(fibre("X", {0.5, -0.5, 0.05}, {0.5, 0.5, 0.05}));
  // Just inside the parallel angle (10°) a fibre is a tow fibre; just outside it is not.
  Scene tilted = testing::parallel(1e-4, 10);
  tilted.fibres[0].end = {1, std::tan(9.9 * M_PI / 180), 0.018};
  Scene skewed = tilted;
  skewed.fibres[0].end = {1, std::tan(10.1 * M_PI / 180), 0.018};
  const Case cases[] = {
      {"crossing", testing::crossing(0.3, 0.6, 0), false, true, false, false},
      {"parallel", testing::parallel(1e-4, 10), true, false, false, false},
      {"wall", testing::pressed_onto_wall(1e-4, 0), false, false, false, true},
      {"single", single, false, false, false, false},
      {"off-axis pair", off_axis_pair, false, true, false, false},
      {"tow and crossing", tow_and_crossing, true, true, true, false},
      {"tilted 9.9°", tilted, true, false, false, false},
      {"tilted 10.1°", skewed, false, true, false, false},
  };
  for (const Case& k : cases) {
    const auto fibres = make_fibres(k.scene);
    const ContactDetector detector(fibres, k.scene, 0.001);
    EXPECT_EQ(detector.slicing(), k.slicing) << k.name;
    EXPECT_EQ(detector.point_search(), k.points) << k.name;
    EXPECT_EQ(detector.broad_phase(), k.broad) << k.name;
    EXPECT_EQ(detector.walls(), k.walls) << k.name;
  }
}

}  // namespace
}  // namespace fibrecheck
