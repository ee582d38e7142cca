#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "contact_detection.h"
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
/// of the final residual, on the candidates near touching: solve_frictionless_problem), so that
/// what those contacts add is in the estimate too.
///
/// Under the deformed contact the answer's crossings act at the closest points of its own deformed
/// fibres and its normals point between its own displaced centres: the crossings step there and the
/// normals turn, and the problem linearised about them is solved again, up to eight times, until
/// neither moves. Where they still turn then (on compacted tows each pass takes them only 10–15 %
/// of the rest of their way), the rest of the way the passes' contraction predicts is added to the
/// answer's forces before the errors are measured.
///
/// With Coulomb friction the frictions are unknowns as well (coulomb_answer: Newton steps of the
/// frictional problem); under the seed's friction rule, which solves no problem of its own, they
/// are held at their final values.
///
/// It assumes: the candidate list holds every contact of the answer; in a load path, the step's
/// slip origins are the answer's, so that it estimates the error of the step's own problem and not
/// what earlier steps' errors leave in the origins.
///
/// With `answer`, also returns the contacts as the estimate's answer has them (forces and
/// frictions, and under the deformed contact places, normals and tangents). With `answer_only`
/// the caller wants that answer and not the estimate: where a problem on the way does not settle,
/// the normals are not turned again (the answer will not be taken, and the errors it gives are
/// rougher).
ErrorEstimate estimate_iteration_error(const Scene& scene, const std::vector<Fibre>& fibres,
                                       const ContactDetector& detector,
                                       const std::vector<Contact>& contacts,
                                       std::vector<Contact>* answer = nullptr,
                                       bool answer_only = false);

}  // namespace fibrecheck
