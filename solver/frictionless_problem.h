#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "contact_geometry.h"
#include "fibre.h"
#include "scene.h"
#include "superposition.h"

namespace fibrecheck {

/// The force each contact's fibre A receives under normal forces `P` and the contacts' friction.
std::vector<Eigen::Vector3d> forces_on_a(const std::vector<Contact>& contacts,
                                         const Eigen::VectorXd& P);

/// Every contact's overlap along its normal under the normal forces `P` (and the scene's loads),
/// the contacts attached to `beams`; with `energy`, also the exact strain energy ½ΣP·v.
Eigen::VectorXd contact_overlaps(const Superposition& beams, const ContactGeometry& geometry,
                                 const std::vector<Contact>& contacts, const Eigen::VectorXd& P,
                                 double* energy = nullptr);

/// How solve_frictionless_problem ended.
struct FrictionlessProblemOutcome {
  bool settled = false;      ///< the answer meets the tolerance on every candidate
  Eigen::Index members = 0;  ///< candidates the last solve was made on
  int growths = 0;           ///< times candidates outside joined
};

/// The frictionless contact problem of the candidate list `contacts` (attached to `beams`), with
/// their normals held: forces P ≥ 0 that leave no overlap where P = 0 and no gap where P > 0,
/// beyond `tolerance` (mm), solved from forces `P` (replaced by the answer) with overlaps `d`.
///
/// Why on a subset: on a compacted tow most candidates are far from touching, and a product with W
/// costs in proportion to the candidates it is made over. So the problem is solved
/// (by the projected conjugate gradients of rule cg, in products with W whose number times the
/// candidates they are made over is at most `max_work` a solve) on the candidates that push or lie
/// within `reach` (mm) of touching; a candidate outside that the answer makes overlap by more than
/// the tolerance joins, with every other the answer brings within reach, and the problem is solved
/// again from there, until none does. The answer is judged by its own overlaps, measured afresh on
/// every candidate.
FrictionlessProblemOutcome solve_frictionless_problem(
    const Scene& scene, const std::vector<Fibre>& fibres, const Superposition& beams,
    const ContactGeometry& geometry, const std::vector<Contact>& contacts, double reach,
    double tolerance, double max_work, const Eigen::VectorXd& d, Eigen::VectorXd& P);

}  // namespace fibrecheck
