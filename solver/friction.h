#pragma once

#include <Eigen/Core>

namespace fibrecheck {

/// The friction approximation of §4.3.4: after the normal turned to `normal` and the normal force
/// became `normal_force`, the tangential force keeps the previous resultant `previous_resultant`
/// (Eqs. 4.29–4.30) — its part off the new normal — capped by Coulomb, ‖F‖ ≤ μN (Eqs. 4.31–4.33).
/// Returns F, the friction force on the same fibre as the resultant.
Eigen::Vector3d coulomb_capped_friction(const Eigen::Vector3d& previous_resultant,
                                        const Eigen::Vector3d& normal, double normal_force,
                                        double mu);

}  // namespace fibrecheck
