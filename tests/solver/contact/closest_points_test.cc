// Closest points of two segments (Eqs. 4.16–4.24), swept over degenerate geometry: parallel,
// coincident, collinear, touching, 1e-12 gaps and segment ends. The reference is a brute-force
// search over both parameters.
#include "closest_points.h"

#include <gtest/gtest.h>

#include <random>

namespace fibrecheck {
namespace {

using V = Eigen::Vector3d;

double brute_force_distance(const V& a1, const V& a2, const V& b1, const V& b2) {
  // Distance is convex in (µA, µB): a fine grid then local refinement finds the minimum.
  double best = INFINITY, bu = 0, bv = 0;
  const int n = 200;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double d = ((a1 + (a2 - a1) * i / n) - (b1 + (b2 - b1) * j / n)).norm();
      if (d < best) best = d, bu = double(i) / n, bv = double(j) / n;
    }
  double step = 1.0 / n;
  for (int it = 0; it < 60; ++it, step *= 0.7)
    for (double du : {-step, 0.0, step})
      for (double dv : {-step, 0.0, step}) {
        const double u = std::clamp(bu + du, 0.0, 1.0), v = std::clamp(bv + dv, 0.0, 1.0);
        const double d = ((a1 + (a2 - a1) * u) - (b1 + (b2 - b1) * v)).norm();
        if (d < best) best = d, bu = u, bv = v;
      }
  return best;
}

void expect_consistent(const ClosestPoints& cp, const V& a1, const V& a2, const V& b1,
                       const V& b2) {
  ASSERT_TRUE(std::isfinite(cp.mu_a) && std::isfinite(cp.mu_b) && std::isfinite(cp.distance));
  EXPECT_GE(cp.mu_a, 0.0);
  EXPECT_LE(cp.mu_a, 1.0);
  EXPECT_GE(cp.mu_b, 0.0);
  EXPECT_LE(cp.mu_b, 1.0);
  EXPECT_NEAR((cp.a - (a1 + cp.mu_a * (a2 - a1))).norm(), 0.0, 1e-15);
  EXPECT_NEAR((cp.b - (b1 + cp.mu_b * (b2 - b1))).norm(), 0.0, 1e-15);
  EXPECT_NEAR(cp.distance, (cp.b - cp.a).norm(), 1e-15);
}

TEST(ClosestPoints, SkewSegmentsSolveEquations4_22And4_23) {
  // A along x, B along y lifted by 2: the interior solution µA = 0.3, µB = 0.6.
  const V a1(0, 0, 0), a2(1, 0, 0), b1(0.3, -0.6, 2), b2(0.3, 0.4, 2);
  const ClosestPoints cp = segment_closest_points(a1, a2, b1, b2);
  expect_consistent(cp, a1, a2, b1, b2);
  EXPECT_NEAR(cp.mu_a, 0.3, 1e-14);
  EXPECT_NEAR(cp.mu_b, 0.6, 1e-14);
  EXPECT_NEAR(cp.distance, 2.0, 1e-14);
  EXPECT_FALSE(cp.parallel);
  // Eqs. 4.18–4.19: Bc − Ac is perpendicular to both segments.
  EXPECT_NEAR((cp.b - cp.a).dot(a2 - a1), 0.0, 1e-14);
  EXPECT_NEAR((cp.b - cp.a).dot(b2 - b1), 0.0, 1e-14);
}

TEST(ClosestPoints, RandomSegmentsAgreeWithBruteForce) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const V a1(u(rng), u(rng), u(rng)), a2(u(rng), u(rng), u(rng));
    const V b1(u(rng), u(rng), u(rng)), b2(u(rng), u(rng), u(rng));
    const ClosestPoints cp = segment_closest_points(a1, a2, b1, b2);
    expect_consistent(cp, a1, a2, b1, b2);
    // The search's own precision is ~1e-8; it can never beat the exact minimum.
    const double brute = brute_force_distance(a1, a2, b1, b2);
    EXPECT_LE(cp.distance, brute + 1e-15) << "trial " << trial;
    EXPECT_NEAR(cp.distance, brute, 1e-7) << "trial " << trial;
  }
}

TEST(ClosestPoints, ParallelSegmentsTakeTheMiddleOfTheCommonStretch) {
  // Eq. 4.24: the denominator of Eq. 4.22 is zero; B overlaps A on [0.4, 1] of A.
  const V a1(0, 0, 0), a2(1, 0, 0), b1(0.4, 0.02, 0), b2(1.6, 0.02, 0);
  const ClosestPoints cp = segment_closest_points(a1, a2, b1, b2);
  expect_consistent(cp, a1, a2, b1, b2);
  EXPECT_TRUE(cp.parallel);
  EXPECT_NEAR(cp.distance, 0.02, 1e-15);
  EXPECT_NEAR(cp.mu_a, 0.7, 1e-14);
  EXPECT_NEAR(cp.a.x(), cp.b.x(), 1e-14);
  // Reversed direction of B gives the same points.
  const ClosestPoints back = segment_closest_points(a1, a2, b2, b1);
  EXPECT_NEAR((back.a - cp.a).norm(), 0.0, 1e-14);
}

TEST(ClosestPoints, ParallelSegmentsWithoutCommonStretchUseNearestEnds) {
  const V a1(0, 0, 0), a2(1, 0, 0), b1(1.5, 0.1, 0), b2(2.5, 0.1, 0);
  const ClosestPoints cp = segment_closest_points(a1, a2, b1, b2);
  expect_consistent(cp, a1, a2, b1, b2);
  EXPECT_NEAR(cp.mu_a, 1.0, 1e-15);
  EXPECT_NEAR(cp.mu_b, 0.0, 1e-15);
  EXPECT_NEAR(cp.distance, std::hypot(0.5, 0.1), 1e-14);
  const ClosestPoints left = segment_closest_points(b1, b2, a1, a2);
  EXPECT_NEAR(left.distance, cp.distance, 1e-14);
}

TEST(ClosestPoints, CoincidentAndCollinearSegmentsGiveZeroDistanceAndNoNaN) {
  const V a1(0, 0, 0), a2(1, 1, 1);
  const ClosestPoints same = segment_closest_points(a1, a2, a1, a2);
  expect_consistent(same, a1, a2, a1, a2);
  EXPECT_NEAR(same.distance, 0.0, 1e-15);
  const ClosestPoints collinear = segment_closest_points(a1, a2, a2, V(2, 2, 2));
  expect_consistent(collinear, a1, a2, a2, V(2, 2, 2));
  EXPECT_NEAR(collinear.distance, 0.0, 1e-15);
}

TEST(ClosestPoints, NearlyParallelAndTinyGapsStayAccurate) {
  // Gaps from 1e-12 up and angles down to 1e-9 rad: distances to 1e-15 absolute.
  for (double gap : {0.0, 1e-12, 1e-9, 1e-3}) {
    for (double angle : {0.0, 1e-12, 1e-9, 1e-6, 1e-3}) {
      const V a1(0, 0, 0), a2(1, 0, 0);
      const V b1(0.2, gap, -angle * 0.5), b2(0.8, gap, angle * 0.5);
      const ClosestPoints cp = segment_closest_points(a1, a2, b1, b2);
      expect_consistent(cp, a1, a2, b1, b2);
      EXPECT_NEAR(cp.distance, gap, 1e-15) << "gap " << gap << ", angle " << angle;
    }
  }
}

TEST(ClosestPoints, TouchingEndsAndZeroLengthSegments) {
  const V a1(0, 0, 0), a2(1, 0, 0);
  // B starts exactly at A's end.
  const ClosestPoints touching = segment_closest_points(a1, a2, V(1, 0, 0), V(1, 1, 0));
  EXPECT_NEAR(touching.distance, 0.0, 1e-15);
  EXPECT_NEAR(touching.mu_a, 1.0, 1e-15);
  EXPECT_NEAR(touching.mu_b, 0.0, 1e-15);
  // B is a point beside A's middle; A is a point; both are points.
  const ClosestPoints point_b = segment_closest_points(a1, a2, V(0.25, 0.5, 0), V(0.25, 0.5, 0));
  EXPECT_NEAR(point_b.mu_a, 0.25, 1e-15);
  EXPECT_NEAR(point_b.distance, 0.5, 1e-15);
  const ClosestPoints point_a = segment_closest_points(V(2, 0, 0), V(2, 0, 0), a1, a2);
  EXPECT_NEAR(point_a.mu_b, 1.0, 1e-15);
  EXPECT_NEAR(point_a.distance, 1.0, 1e-15);
  const ClosestPoints points = segment_closest_points(a1, a1, a2, a2);
  EXPECT_NEAR(points.distance, 1.0, 1e-15);
  // The closest point of A is an end while B's is interior (clamping branch).
  const ClosestPoints end = segment_closest_points(a1, a2, V(1.5, -1, 0.1), V(1.5, 1, 0.1));
  EXPECT_NEAR(end.mu_a, 1.0, 1e-15);
  EXPECT_NEAR(end.mu_b, 0.5, 1e-15);
  EXPECT_NEAR(end.distance, std::hypot(0.5, 0.1), 1e-14);
}

}  // namespace
}  // namespace fibrecheck
