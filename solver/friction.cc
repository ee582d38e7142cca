#include "friction.h"

namespace fibrecheck {

Eigen::Vector3d coulomb_capped_friction(const Eigen::Vector3d& previous_resultant,
                                        const Eigen::Vector3d& normal, double normal_force,
                                        double mu) {
  Eigen::Vector3d tangential = previous_resultant - previous_resultant.dot(normal) * normal;
  const double cap = mu * normal_force;
  const double size = tangential.norm();
  if (size > cap) tangential *= (size > 0.0 ? cap / size : 0.0);
  return tangential;
}

}  // namespace fibrecheck
