#include "slice_broad_phase.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fibrecheck {

namespace {

bool within(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double ra, double rb,
            double margin) {
  const double reach = ra + rb + margin;
  return (a - b).squaredNorm() < reach * reach;
}

double extra(const std::vector<double>& reach, int i) {
  return reach.empty() ? 0.0 : reach[i];
}

}  // namespace

void slice_pairs(const std::vector<Eigen::Vector2d>& centres, const std::vector<double>& radii,
                 double margin, std::vector<std::pair<int, int>>& pairs,
                 const std::vector<double>& reach) {
  pairs.clear();
  const int n = static_cast<int>(centres.size());
  if (n < 2) return;
  double r_max = 0.0;
  Eigen::Vector2d lo = centres[0], hi = centres[0];
  for (int i = 0; i < n; ++i) {
    r_max = std::max(r_max, radii[i] + extra(reach, i));
    lo = lo.cwiseMin(centres[i]);
    hi = hi.cwiseMax(centres[i]);
  }
  const double cell = 2.0 * r_max + margin;
  // Cells counted from the lower-left corner; 2³¹ columns is far beyond any tow.
  const double columns = std::floor((hi[0] - lo[0]) / cell) + 3.0;
  auto cell_of = [&](const Eigen::Vector2d& c, std::int64_t& ix, std::int64_t& iy) {
    ix = static_cast<std::int64_t>(std::floor((c[0] - lo[0]) / cell));
    iy = static_cast<std::int64_t>(std::floor((c[1] - lo[1]) / cell));
  };
  const std::int64_t stride = static_cast<std::int64_t>(columns);
  std::vector<std::pair<std::int64_t, int>> keyed(n);
  for (int i = 0; i < n; ++i) {
    std::int64_t ix, iy;
    cell_of(centres[i], ix, iy);
    keyed[i] = {iy * stride + ix, i};
  }
  std::sort(keyed.begin(), keyed.end());
  // Each point looks at its own cell and the four neighbours "after" it, so each pair is seen once.
  const std::int64_t offsets[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
  for (int k = 0; k < n; ++k) {
    const int i = keyed[k].second;
    std::int64_t ix, iy;
    cell_of(centres[i], ix, iy);
    for (const auto& o : offsets) {
      const std::int64_t key = (iy + o[1]) * stride + (ix + o[0]);
      auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(key, -1));
      for (; it != keyed.end() && it->first == key; ++it) {
        const int j = it->second;
        if (o[0] == 0 && o[1] == 0 && j <= i) continue;
        if (within(centres[i], centres[j], radii[i] + extra(reach, i), radii[j] + extra(reach, j),
                   margin))
          pairs.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
}

void slice_pairs_all(const std::vector<Eigen::Vector2d>& centres, const std::vector<double>& radii,
                     double margin, std::vector<std::pair<int, int>>& pairs,
                     const std::vector<double>& reach) {
  pairs.clear();
  const int n = static_cast<int>(centres.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (within(centres[i], centres[j], radii[i] + extra(reach, i), radii[j] + extra(reach, j),
                 margin))
        pairs.emplace_back(i, j);
}

}  // namespace fibrecheck
