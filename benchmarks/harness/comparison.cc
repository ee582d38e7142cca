#include "comparison.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

namespace fibrecheck {

double seed_stable_limit(const Scene& scene, const Solvers& solvers) {
  Scene probe = scene;
  probe.solver.rule = UpdateRule::seed;
  probe.solver.c = 1.0;
  probe.solver.max_iterations = 1;
  return solvers.iterative(probe).c_stable_limit;
}

bool needs_continuous_reference(const Scene& scene) {
  if (!scene.walls.empty()) return true;
  const Eigen::Vector3d axis = scene.contact.axis.normalized();
  int tow = 0;
  for (const FibreSpec& f : scene.fibres) {
    const Eigen::Vector3d t = (f.end - f.start).normalized();
    if (std::fabs(t.dot(axis)) >= std::cos(scene.contact.parallel_angle_deg * M_PI / 180.0)) ++tow;
  }
  return tow >= 2;
}

Comparison compare_results(const std::string& scene, const Result& user, const Result& converged,
                           const Result& slices, const std::optional<Result>& continuous,
                           const std::string& reason) {
  Comparison c;
  c.scene = scene;
  c.user = user;
  c.converged = converged;
  c.slices = slices;
  c.continuous = continuous;
  c.reason = reason;
  // The user's run is measured whatever its status (a run stopped at its cap is what the user
  // got); the references must have an answer to measure against.
  if (slices.status != Status::converged && c.reason.empty())
    c.reason = "the reference on slices ended " + std::string(to_string(slices.status)) + ": " +
               slices.message;
  if (continuous && continuous->status != Status::converged && c.reason.empty())
    c.reason = "the continuous reference ended " + std::string(to_string(continuous->status)) +
               ": " + continuous->message;
  c.comparable = c.reason.empty();
  if (!c.comparable) return c;
  const std::string what = "comparison of " + scene;
  c.total = measure_errors(user, c.truth(), what);
  c.iteration = measure_errors(user, slices, what);
  c.slicing = continuous ? measure_errors(slices, *continuous, what) : ErrorReport{};
  c.agreement = measure_errors(converged, slices, what);
  if (continuous && continuous->finite_elements)
    c.truth_error_estimate = continuous->finite_elements->line_force_error_estimate;
  return c;
}

Result ground_truth(const Scene& scene, const Solvers& solvers) {
  return needs_continuous_reference(scene) ? solvers.reference_continuous(scene)
                                           : solvers.reference_slices(scene);
}

Result stored_ground_truth(const Scene& scene, const Solvers& solvers, const std::string& folder) {
  const std::string path =
      (std::filesystem::path(folder) / (scene.name + ".truth.result.json")).string();
  if (std::filesystem::exists(path)) return read_result(path);
  const Result truth = ground_truth(scene, solvers);
  write_result(path, truth);
  return truth;
}

Comparison compare_scene(const Scene& scene, const Solvers& solvers,
                         const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  say("the iterative solver as the scene says");
  const Result user = solvers.iterative(scene);
  Scene tight = scene;
  tight.solver.overlap_tolerance = 1e-4 * scene.overlap_tolerance();
  tight.solver.max_iterations = std::max<long>(scene.solver.max_iterations, 1000000);
  say("the iterative solver converged to 1e-4 of the scene's tolerance");
  const Result converged = solvers.iterative(tight);
  say("the reference on the same slices");
  const Result slices = solvers.reference_slices(scene);
  std::optional<Result> continuous;
  if (needs_continuous_reference(scene)) {
    say("the reference with continuous line contact (the ground truth)");
    continuous = solvers.reference_continuous(scene);
  }
  return compare_results(scene.name, user, converged, slices, continuous);
}

namespace {
nlohmann::json run_json(const Result& r) {
  return {{"solver", r.solver},
          {"rule", r.rule},
          {"status", to_string(r.status)},
          {"criterion", to_string(r.criterion)},
          {"iterations", r.iterations},
          {"wall_time_s", r.wall_time_s},
          {"c", r.c},
          {"c_stable_limit", r.c_stable_limit}};
}
}  // namespace

nlohmann::json to_json(const Comparison& c,
                       const std::vector<std::pair<std::string, std::string>>& files) {
  nlohmann::json j;
  j["scene"] = c.scene;
  j["comparable"] = c.comparable;
  if (!c.comparable) j["not_comparable"] = c.reason;
  j["runs"] = {{"user", run_json(c.user)},
               {"converged", run_json(c.converged)},
               {"reference_slices", run_json(c.slices)}};
  if (c.continuous) j["runs"]["reference_continuous"] = run_json(*c.continuous);
  j["rule"] = c.user.rule;
  j["c"] = c.user.c;
  j["ground_truth"] = c.continuous ? "reference_continuous" : "reference_slices";
  j["ground_truth_error_estimate"] = c.truth_error_estimate;
  if (c.comparable) {
    const nlohmann::json total = to_json(c.total.errors);
    for (auto it = total.begin(); it != total.end(); ++it) j[it.key()] = it.value();
    j["iteration_error"] = to_json(c.iteration.errors);
    j["slicing_error"] = to_json(c.slicing.errors);
    j["agreement_error"] = to_json(c.agreement.errors);
    j["pairs"] = nlohmann::json::array();
    for (std::size_t i = 0; i < c.total.pairs.size(); ++i) {
      nlohmann::json row = to_json(c.total.pairs[i]);
      row["force_user"] = row["force_run"];
      row.erase("force_run");
      j["pairs"].push_back(row);
    }
  }
  j["files"] = nlohmann::json::object();
  for (const auto& [label, file] : files) j["files"][label] = file;
  return j;
}

std::string comparison_table(const std::vector<Comparison>& comparisons) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof line, "%-22s %-12s %9s %9s %9s  %9s %9s  %8s %8s\n", "scene", "rule",
                "deflect.", "force", "energy", "iteration", "slicing", "user_s", "truth_s");
  out << line;
  for (const Comparison& c : comparisons) {
    if (!c.comparable) {
      std::snprintf(line, sizeof line, "%-22s %-12s not comparable: %s\n", c.scene.c_str(),
                    c.user.rule.c_str(), c.reason.c_str());
      out << line;
      continue;
    }
    std::snprintf(line, sizeof line, "%-22s %-12s %9.2e %9.2e %9.2e  %9.2e %9.2e  %8.3f %8.3f\n",
                  c.scene.c_str(), c.user.rule.c_str(), c.total.errors.deflection,
                  c.total.errors.force, c.total.errors.energy, c.iteration.errors.worst(),
                  c.slicing.errors.worst(), c.user.wall_time_s, c.truth().wall_time_s);
    out << line;
  }
  return out.str();
}

}  // namespace fibrecheck
