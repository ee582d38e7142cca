#pragma once

#include <vector>

#include "contact.h"
#include "contact_geometry.h"
#include "fibre.h"
#include "superposition.h"

namespace fibrecheck {

/// How far a state is from Coulomb's frictional contact problem, and its answer.
struct CoulombAnswer {
  int steps = 0;         ///< Newton steps taken
  bool settled = false;  ///< the residual fell to the share asked of it
};

/// The answer of the frictional contact problem with Coulomb's law (DESIGN §2, Eq. 4.31),
/// linearised about the contacts' normals, from the state `contacts` holds (normal forces,
/// frictions, slip origins): `contacts` gets the answer's forces and frictions.
///
/// Why: a frictional state's error is in its frictions as much as in its normal forces, and the
/// frictionless residual equation holds the frictions fixed. Each contact that pushes has one
/// equation for its overlap; one that sticks (|F| < μP) one more per tangent for its slip, its
/// friction free; one that slips keeps its friction on the edge of the disk, μP along its
/// direction, and a crossing that slips one more for its slip across that direction, which turns
/// with its friction (by the slip along it times the turn). The normal forces, the sticking
/// frictions and the slipping crossings' turns then solve one linear system with the frictional
/// Delassus operator (overlaps and slips that forces and frictions remove), the slipping
/// frictions following the normal forces: a Newton step of the frictional problem with the
/// contacts' states held. The slipping frictions make it unsymmetric: it is solved by GMRES,
/// preconditioned with each fibre's stiffness at its stations (a friction along t acts as a
/// normal force along ∓t). The step is put back on the cone, the states are read again, and the
/// Newton steps repeat until what is left falls below `share` of what the state left, a few times
/// at most; the state that left least is the answer. From a rough state contacts that slip can
/// wedge fibres against each other, the systems are then nearly singular, and the steps do not
/// settle: the caller then holds the frictions instead.
CoulombAnswer coulomb_answer(const std::vector<Fibre>& fibres, const Superposition& beams,
                             const ContactGeometry& geometry, double mu, double share,
                             std::vector<Contact>& contacts);

}  // namespace fibrecheck
