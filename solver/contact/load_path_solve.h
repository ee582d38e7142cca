#pragma once

#include <functional>

#include "load_path.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// Runs a scene's load path with one solver: each step's scene (scene_at_step) solved by
/// `solve_step`, which receives the previous step's result (none for the first) to start from.
/// The returned result is the last step's, with `steps` holding one entry per finished step; a
/// step that does not converge ends the path with its status, the finished steps kept. Iterations
/// and wall time add up over the steps, and the warnings gather, each the first time a step gives
/// it, named by that step. A scene without steps is solved once, as it stands.
Result solve_load_path(const Scene& scene,
                       const std::function<Result(const Scene&, const Result*)>& solve_step);

}  // namespace fibrecheck
