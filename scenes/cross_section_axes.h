#pragma once

#include <Eigen/Core>
#include <utility>

namespace fibrecheck {

/// Two unit vectors (g1, g2) completing `axis` to a right-handed orthonormal basis; for the x axis
/// they are y and z. The cross-section plane of a tow along `axis` (seed §4.3.3) and of a load
/// path's compaction.
std::pair<Eigen::Vector3d, Eigen::Vector3d> cross_section_axes(const Eigen::Vector3d& axis);

}  // namespace fibrecheck
