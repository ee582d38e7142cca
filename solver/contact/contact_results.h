#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// The contacts of a solved state in the result schema (DESIGN §5): points grouped by pair in
/// order of first appearance, only points that carry force, `total_force` the magnitude of the
/// resultant. Per contact k: `force_on_a[k]` (N) is the force fibre A receives, `u_a[k]` and
/// `u_b[k]` (mm) the displacements of its two sides.
std::vector<ContactResult> contact_results(const std::vector<Contact>& contacts,
                                           const std::vector<Fibre>& fibres,
                                           const std::vector<WallSpec>& walls,
                                           const std::vector<Eigen::Vector3d>& force_on_a,
                                           const std::vector<Eigen::Vector3d>& u_a,
                                           const std::vector<Eigen::Vector3d>& u_b);

/// Each wall's total normal reaction and its pressure over the tow's footprint on the wall.
std::vector<WallResult> wall_results(const std::vector<Contact>& contacts,
                                     const std::vector<Fibre>& fibres,
                                     const std::vector<WallSpec>& walls);

}  // namespace fibrecheck
