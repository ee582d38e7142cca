#pragma once

#include <Eigen/Core>

namespace fibrecheck {

/// Closest points Ac = A1 + µA(A2 − A1), Bc = B1 + µB(B2 − B1) of two segments (Eqs. 4.16–4.17).
struct ClosestPoints {
  double mu_a = 0.0;  ///< µA ∈ [0, 1]
  double mu_b = 0.0;  ///< µB ∈ [0, 1]
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double distance = 0.0;  ///< ‖Bc − Ac‖
  bool parallel = false;  ///< the denominator of Eq. 4.22 vanished (Eq. 4.24)
};

/// Closest points of segments A1A2 and B1B2. Interior solution by Eqs. 4.22–4.23, clamped to the
/// segments. When the segments are parallel (Eq. 4.24: ‖A2−A1‖²‖B2−B1‖² − ((B2−B1)·(A2−A1))² = 0)
/// every point of the common stretch is equally close; the exact branch returns its midpoint, or
/// the nearest ends where the projections do not overlap — never a NaN. Zero-length segments are
/// treated as points.
ClosestPoints segment_closest_points(const Eigen::Ref<const Eigen::Vector3d>& a1,
                                     const Eigen::Ref<const Eigen::Vector3d>& a2,
                                     const Eigen::Ref<const Eigen::Vector3d>& b1,
                                     const Eigen::Ref<const Eigen::Vector3d>& b2);

}  // namespace fibrecheck
