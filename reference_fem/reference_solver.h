#pragma once

#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// The implicit reference (DESIGN §3): the fibres as finite-element beams (BeamModel) and every
/// contact solved at once, exactly, as the complementarity problem P ≥ 0, d = d0 − W·P ≤ 0,
/// P·d = 0 — W built from finite-element solves under unit contact force pairs, the problem solved
/// by an active-set method (no penalty parameter in the answer). An outer loop re-detects the
/// contact geometry on the deformed fibres, with the same rule as the iterative solver (a pushing
/// contact keeps its place and normal), re-meshes, and stops when the active set and the places no
/// longer change. Line contacts use the same slices as the iterative solver. Friction is not
/// modelled (the result says so in `stages`).
struct ReferenceOptions {
  int max_outer_iterations = 30;
  int max_active_set_iterations = 100000;
};

Result solve_reference(const Scene& scene, const ReferenceOptions& options = {});

}  // namespace fibrecheck
