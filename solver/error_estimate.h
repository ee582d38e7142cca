#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "contact_geometry.h"
#include "fibre.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// An a posteriori estimate of the iteration error of a final state: how far its deflections,
/// contact forces and strain energy lie from the exact answer of its own sliced contact problem,
/// relative as the comparison measures errors (DESIGN §6) — the largest deflection difference over
/// the largest deflection, the worst contact pair's |ΔF|/F on its resultant, |ΔU|/U on ½ΣP·v.
///
/// Why it works: the overlaps the state leaves at the contacts that push are the residual of the
/// contact problem, d = d₀ − W·P. If the pushing set is right, the exact forces are P + δ with
/// W_AA·δ = d_A on that set A: one solve with the contact compliance restricted to A, by
/// conjugate gradients preconditioned by each fibre's stiffness at its stations (FibreStiffness),
/// which on line contacts takes a handful of products with W. Where the correction would move
/// contacts near switching — a corrected force below zero, or a free contact it makes overlap —
/// the pushing set was not yet the answer's, and the contact problem of the candidate list is
/// solved from the final state instead (projected conjugate gradients, as rule cg, to a thousandth
/// of the final residual), so that what those contacts add is in the estimate too.
///
/// It assumes: the candidate list holds every contact of the answer; the normals (and crossing
/// places) of the state are those of the answer, so that under the deformed contact it estimates
/// the error of the last linearised problem; friction forces are held at their final values (the
/// normal problem's error only).
/// With `answer`, also returns the contacts as the estimate's answer has them (forces, and under
/// the deformed contact normals and tangents).
ErrorEstimate estimate_iteration_error(const Scene& scene, const std::vector<Fibre>& fibres,
                                       const ContactGeometry& geometry,
                                       const std::vector<Contact>& contacts,
                                       std::vector<Contact>* answer = nullptr);

}  // namespace fibrecheck
