#pragma once

#include <functional>

#include "reference_solver.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// The continuous line contact refined until its line force is known to
/// `options.refinement_tolerance` (DESIGN §3: the ground truth of slice studies, to 1e-4 in line
/// force). The line force converges at first order (a force next to a pinned end moves nothing), so
/// the change from one refinement to the next says little about what is left. Instead each
/// refinement K, from min(options.refine, coarsest_refinement) up to options.max_refine, is solved
/// by `solve_once` (given the options with that refinement); from the third on, the summed line and
/// wall force is extrapolated (Richardson) with the order observed on the last three, and the
/// refinement stops when two successive extrapolations agree to the tolerance. Every line and wall
/// pair then carries its extrapolated force, the result its refinement, order and error estimate.
/// A refinement that does not converge, or a scene without line contact, ends it at once.
Result solve_refined_until_settled(
    const Scene& scene, const ReferenceOptions& options,
    const std::function<Result(const ReferenceOptions& once)>& solve_once);

}  // namespace fibrecheck
