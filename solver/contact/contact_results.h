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
                                           const std::vector<Eigen::Vector3d>& u_b,
                                           double mu = 0.0);

/// True when a contact that carries force slips: its friction force is on the Coulomb circle,
/// |F| = μN (to 1e-9 relative).
bool slips(const Contact& contact, double mu);

/// Coulomb's conditions at every contact that carries force (DESIGN §2, `coulomb` model): a
/// sticking point must not slip, a slipping one must slip along its friction force, and no
/// friction force may exceed μN (contacts without force must carry none).
FrictionFigures friction_figures(const std::vector<Contact>& contacts, double mu,
                                 FrictionModel model);

/// The same conditions for Tresca's law: the disk radius of contact k is `bounds[k]` (N) instead
/// of μN (the inner problem of a Tresca fixed point).
FrictionFigures tresca_figures(const std::vector<Contact>& contacts, const Eigen::VectorXd& bounds);

/// Each wall's total normal reaction and its pressure over the tow's footprint on the wall.
std::vector<WallResult> wall_results(const std::vector<Contact>& contacts,
                                     const std::vector<Fibre>& fibres,
                                     const std::vector<WallSpec>& walls);

}  // namespace fibrecheck
