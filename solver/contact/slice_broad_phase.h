#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace fibrecheck {

/// Broad phase of one cross-section slice (seed §4.3.3, Figure 4.11): the pairs of fibre centres
/// (discs of radius r in the slice plane) whose gap is below `margin`, found by hashing centres
/// into a uniform grid of cell size 2·r_max + margin and testing only neighbouring cells —
/// O(n) for a tow's bounded packing density instead of O(n²).
/// `pairs` receives (i, j) with i < j, sorted. With `reach` (one length per centre, mm) a pair
/// counts when its gap is below margin + reach_i + reach_j, and the cells grow to match.
void slice_pairs(const std::vector<Eigen::Vector2d>& centres, const std::vector<double>& radii,
                 double margin, std::vector<std::pair<int, int>>& pairs,
                 const std::vector<double>& reach = {});

/// The same pairs by testing all n(n−1)/2 pairs (reference for tests and benchmarks).
void slice_pairs_all(const std::vector<Eigen::Vector2d>& centres, const std::vector<double>& radii,
                     double margin, std::vector<std::pair<int, int>>& pairs,
                     const std::vector<double>& reach = {});

}  // namespace fibrecheck
