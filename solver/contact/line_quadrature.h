#pragma once

#include <vector>

namespace fibrecheck {

/// Where a line contact is sampled and how much of the line each sample stands for (seed §4.3.3,
/// Figures 4.11–4.12). Positions are fractions of the tow's axial extent (slices) or of a fibre's
/// length (fibre–wall contact); the weights of a rule sum to one.
struct LineQuadrature {
  std::vector<double> position;
  std::vector<double> weight;

  /// The seed's n cross-sections: the midpoints of n equal intervals, each carrying 1/n of the
  /// line's force (Eq. 4.28) — the one-point Gauss rule on n cells.
  static LineQuadrature slices(int n);
  /// The continuous line contact: the two Gauss points of each of `cells` equal cells, each
  /// carrying half a cell; it converges to the line contact itself as the cells are refined.
  static LineQuadrature gauss(int cells);

  int size() const { return static_cast<int>(position.size()); }
};

}  // namespace fibrecheck
