#pragma once

#include <functional>
#include <vector>

#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// The scene as it stands at one step of its load path (seed §4.3.1, compaction of a tow): every
/// position — fibre supports and wall points — scaled by the step's compaction factor F about the
/// tow's centre in the cross-section plane (⊥ contact.axis; the centre is the middle of the walls'
/// box where two pairs of opposite walls bound the section, else the mean of the fibres'
/// supports), and every load times the step's load factor. F = 1 and load factor 1 give the scene
/// as written. The step list itself is dropped from the result.
Scene scene_at_step(const Scene& scene, const LoadStep& step);

/// The fibre volume fraction of a (stepped) scene: the fibres' cross-sections πr² over the area
/// between its walls in the cross-section plane when two pairs of opposite walls bound it, else
/// over the bounding box of the fibres' supports grown by their radii.
double fibre_volume_fraction(const Scene& scene);

/// One step's entry in a result (DESIGN §5 `steps[]`), from that step's scene and result.
StepResult step_result(const Scene& stepped, const LoadStep& step, const Result& result);

/// Runs a scene's load path with one solver: each step's scene (scene_at_step) solved by
/// `solve_step`, which receives the previous step's result (none for the first) to start from.
/// The returned result is the last step's, with `steps` holding one entry per finished step; a
/// step that does not converge ends the path with its status, the finished steps kept. Iterations
/// and wall time add up over the steps. A scene without steps is solved once, as it stands.
Result solve_load_path(const Scene& scene,
                       const std::function<Result(const Scene&, const Result*)>& solve_step);

}  // namespace fibrecheck
