#include "cross_section_axes.h"

#include <Eigen/Geometry>

namespace fibrecheck {

std::pair<Eigen::Vector3d, Eigen::Vector3d> cross_section_axes(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.normalized();
  // Start from the global axis least aligned with the tow axis, in the cyclic order after it, so
  // that the x axis gives (y, z), the y axis (z, x) and the z axis (x, y).
  int k = 0;
  a.cwiseAbs().maxCoeff(&k);
  Eigen::Vector3d g1 = Eigen::Vector3d::Unit((k + 1) % 3);
  g1 = (g1 - g1.dot(a) * a).normalized();
  const Eigen::Vector3d g2 = a.cross(g1);
  return {g1, g2};
}

}  // namespace fibrecheck
