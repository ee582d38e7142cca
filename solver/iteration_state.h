#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"

namespace fibrecheck {

/// What the iteration of §4.3.2 works on, shared by the loop, the update rules, the working set
/// and the Tresca radii: the current candidate contacts with their forces and overlaps, the force
/// each contact's fibre A receives, the displacements of both sides of every contact, and what
/// the rules carry per contact from one update to the next.
struct IterationState {
  std::vector<Contact> contacts;
  std::vector<Eigen::Vector3d> force_on_a;  ///< N, matches `contacts` when `forces_gathered`
  std::vector<Eigen::Vector3d> u_a, u_b;    ///< mm, at the last evaluation
  bool forces_gathered = false;

  /// The accelerated rule's iterates P_k and P_{k−1} (N), and with Coulomb friction F_k, F_{k−1}.
  Eigen::VectorXd iterate, previous;
  std::vector<Eigen::Vector3d> friction_iterate, previous_friction;
  /// Coulomb friction: each contact's Tresca radius, the disk |F| ≤ bound its friction stays in.
  Eigen::VectorXd bound;

  /// force_on_a from the contacts' forces.
  void gather_forces();

  /// The contact list becomes `found`, whose contact i was contacts[origin[i]] (or is new where
  /// origin[i] < 0): the iterates and radii follow their contacts, new ones start from their own
  /// force and friction (radius μ times the force).
  void take_over(std::vector<Contact> found, const std::vector<long>& origin, bool coulomb,
                 double mu);
};

}  // namespace fibrecheck
