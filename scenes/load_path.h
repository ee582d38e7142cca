#pragma once

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

}  // namespace fibrecheck
