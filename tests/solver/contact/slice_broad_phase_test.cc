// The slice broad phase must find exactly the pairs the all-pairs test finds, in any packing.
#include "slice_broad_phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace fibrecheck {
namespace {

TEST(SliceBroadPhase, FindsTheSamePairsAsAllPairs) {
  std::mt19937_64 rng(5);
  for (int n : {2, 3, 17, 300, 2000}) {
    for (double margin : {0.0, 0.002, 0.05}) {
      const double side = std::sqrt(n * M_PI * 1e-4 / 0.5);
      std::uniform_real_distribution<double> u(-side, side), r(0.005, 0.015);
      std::vector<Eigen::Vector2d> centres(n);
      std::vector<double> radii(n);
      for (int i = 0; i < n; ++i) centres[i] = {u(rng), u(rng)}, radii[i] = r(rng);
      std::vector<std::pair<int, int>> grid, all;
      slice_pairs(centres, radii, margin, grid);
      slice_pairs_all(centres, radii, margin, all);
      EXPECT_EQ(grid, all) << "n = " << n << ", margin = " << margin;
      if (n >= 300) {
        EXPECT_FALSE(all.empty());
      }
      // Each centre reaching further by its own length (up to one radius, a few far).
      std::uniform_real_distribution<double> e(0.0, 0.01);
      std::vector<double> reach(n);
      for (int i = 0; i < n; ++i) reach[i] = i % 7 == 0 ? 5 * e(rng) : e(rng);
      std::vector<std::pair<int, int>> wider;
      slice_pairs(centres, radii, margin, grid, reach);
      slice_pairs_all(centres, radii, margin, wider, reach);
      EXPECT_EQ(grid, wider) << "n = " << n << ", margin = " << margin << ", with reach";
      EXPECT_TRUE(std::includes(wider.begin(), wider.end(), all.begin(), all.end()));
    }
  }
}

TEST(SliceBroadPhase, ReachAddsToTheMarginOfEachPairItsTwoCentresReach) {
  // Gap 0.01 between the first two discs: within margin 0.002 only with reach 0.004 + 0.0041.
  const std::vector<Eigen::Vector2d> centres = {{0, 0}, {0.03, 0}, {0.1, 0}};
  const std::vector<double> radii = {0.01, 0.01, 0.01};
  std::vector<std::pair<int, int>> pairs;
  slice_pairs(centres, radii, 0.002, pairs, {0.004, 0.0039, 0.0});
  EXPECT_TRUE(pairs.empty());
  slice_pairs(centres, radii, 0.002, pairs, {0.004, 0.0041, 0.0});
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 1}}));
}

TEST(SliceBroadPhase, TouchingAndCoincidentCentres) {
  // Exactly touching discs are not within (strict test); coincident ones are.
  const std::vector<Eigen::Vector2d> centres = {{0, 0}, {0.02, 0}, {0.02, 0}, {5, 5}};
  const std::vector<double> radii = {0.01, 0.01, 0.01, 0.01};
  std::vector<std::pair<int, int>> pairs;
  slice_pairs(centres, radii, 0.0, pairs);
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{1, 2}}));
  slice_pairs(centres, radii, 1e-12, pairs);
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 2}}));
}

}  // namespace
}  // namespace fibrecheck
