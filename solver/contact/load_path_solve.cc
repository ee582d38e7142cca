#include "load_path_solve.h"

#include <algorithm>
#include <string>

namespace fibrecheck {

Result solve_load_path(const Scene& scene,
                       const std::function<Result(const Scene&, const Result*)>& solve_step) {
  if (scene.steps.empty()) return solve_step(scene, nullptr);
  Result last;
  std::vector<StepResult> steps;
  std::vector<std::string> warnings, seen;
  long iterations = 0;
  double seconds = 0.0;
  for (std::size_t i = 0; i < scene.steps.size(); ++i) {
    const Scene stepped = scene_at_step(scene, scene.steps[i]);
    Result r = solve_step(stepped, i == 0 ? nullptr : &last);
    steps.push_back(step_result(stepped, scene.steps[i], r));
    iterations += r.iterations;
    seconds += r.wall_time_s;
    const std::string step =
        "step " + std::to_string(i + 1) + " of " + std::to_string(scene.steps.size()) + ": ";
    for (const std::string& w : r.warnings)
      if (std::find(seen.begin(), seen.end(), w) == seen.end())
        seen.push_back(w), warnings.push_back(step + w);
    last = std::move(r);
    if (last.status != Status::converged) {
      last.message = "step " + std::to_string(i + 1) + " of " + std::to_string(scene.steps.size()) +
                     ": " + last.message;
      break;
    }
  }
  last.steps = std::move(steps);
  last.warnings = std::move(warnings);
  last.iterations = iterations;
  last.wall_time_s = seconds;
  return last;
}

}  // namespace fibrecheck
