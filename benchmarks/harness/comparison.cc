#include "comparison.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.h"

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
                           const std::string& reason, const std::optional<Result>& other_geometry) {
  Comparison c;
  c.other_geometry = other_geometry;
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
  if (other_geometry && other_geometry->status == Status::converged) {
    const bool deformed = slices.geometry == "deformed";
    c.geometry = measure_errors(deformed ? *other_geometry : slices,
                                deformed ? slices : *other_geometry, what);
  }
  if (continuous && continuous->finite_elements)
    c.truth_error_estimate = continuous->finite_elements->line_force_error_estimate;
  return c;
}

Scene in_other_geometry(const Scene& scene) {
  Scene other = scene;
  other.contact.geometry = scene.contact.geometry == ContactGeometryModel::deformed
                               ? ContactGeometryModel::linearised
                               : ContactGeometryModel::deformed;
  return other;
}

std::string other_geometry_label(const Scene& scene) {
  return std::string("reference_slices_") + to_string(in_other_geometry(scene).contact.geometry);
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
  say("the reference on the same slices in the other contact geometry");
  const Result other = solvers.reference_slices(in_other_geometry(scene));
  std::optional<Result> continuous;
  if (needs_continuous_reference(scene)) {
    say("the reference with continuous line contact (the ground truth)");
    continuous = solvers.reference_continuous(scene);
  }
  return compare_results(scene.name, user, converged, slices, continuous, "", other);
}

namespace {

RunSummary summary_of(const Result& r) {
  return {r.solver,      r.rule, to_string(r.status), to_string(r.criterion), r.iterations,
          r.wall_time_s, r.c,    r.c_stable_limit};
}

}  // namespace

ComparisonRecord record_of(const Comparison& c,
                           const std::vector<std::pair<std::string, std::string>>& files) {
  ComparisonRecord r;
  r.scene = c.scene;
  r.comparable = c.comparable;
  r.reason = c.reason;
  r.runs = {{"user", summary_of(c.user)},
            {"converged", summary_of(c.converged)},
            {"reference_slices", summary_of(c.slices)}};
  if (c.continuous) r.runs["reference_continuous"] = summary_of(*c.continuous);
  if (c.other_geometry)
    r.runs[std::string("reference_slices_") + c.other_geometry->geometry] =
        summary_of(*c.other_geometry);
  r.geometry_model = c.user.geometry;
  r.geometry = c.other_geometry && c.other_geometry->status == Status::converged
                   ? c.geometry.errors
                   : Errors{NAN, NAN, NAN};
  r.rule = c.user.rule;
  r.c = c.user.c;
  r.ground_truth = c.continuous ? "reference_continuous" : "reference_slices";
  r.truth_error_estimate = c.truth_error_estimate;
  r.total = c.total.errors;
  r.iteration = c.iteration.errors;
  if (c.comparable) {
    r.estimate = estimated_errors(c.user);
    r.effectivity = effectivity(r.estimate, r.iteration, measurable_above(c.agreement.errors));
  }
  r.slicing = c.slicing.errors;
  r.agreement = c.agreement.errors;
  r.pairs = c.total.pairs;
  for (const auto& [label, file] : files) r.files[label] = file;
  return r;
}

nlohmann::json to_json(const Comparison& c,
                       const std::vector<std::pair<std::string, std::string>>& files) {
  return to_json(record_of(c, files));
}

void write_comparison(const std::string& folder, const Scene& scene, const Comparison& c) {
  const std::filesystem::path dir(folder);
  std::vector<std::pair<std::string, std::string>> files = {
      {"scene", "scene.json"},
      {"user", "user.result.json"},
      {"converged", "converged.result.json"},
      {"reference_slices", "reference_slices.result.json"}};
  if (c.continuous) files.push_back({"reference_continuous", "reference_continuous.result.json"});
  write_scene((dir / "scene.json").string(), scene);
  write_result((dir / "user.result.json").string(), c.user);
  write_result((dir / "converged.result.json").string(), c.converged);
  write_result((dir / "reference_slices.result.json").string(), c.slices);
  if (c.continuous)
    write_result((dir / "reference_continuous.result.json").string(), *c.continuous);
  if (c.other_geometry) {
    const std::string label = other_geometry_label(scene);
    files.push_back({label, label + ".result.json"});
    write_result((dir / (label + ".result.json")).string(), *c.other_geometry);
  }
  write_file_atomically((dir / "compare.json").string(), to_json(c, files).dump(1) + "\n");
}

std::string comparison_table(const std::vector<Comparison>& comparisons) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof line, "%-22s %-12s %9s %9s %9s  %9s %9s %9s  %9s %6s  %8s %8s\n",
                "scene", "rule", "deflect.", "force", "energy", "iteration", "slicing", "geometry",
                "estimate", "eff.", "user_s", "truth_s");
  out << line;
  for (const Comparison& c : comparisons) {
    if (!c.comparable) {
      std::snprintf(line, sizeof line, "%-22s %-12s not comparable: %s\n", c.scene.c_str(),
                    c.user.rule.c_str(), c.reason.c_str());
      out << line;
      continue;
    }
    // The estimate and its effectivity on the force, the error the estimate is made for.
    const Errors estimate = estimated_errors(c.user);
    const double index =
        effectivity(estimate, c.iteration.errors, measurable_above(c.agreement.errors)).force;
    std::snprintf(line, sizeof line,
                  "%-22s %-12s %9.2e %9.2e %9.2e  %9.2e %9.2e %9.2e  %9.2e %6.2f  %8.3f %8.3f\n",
                  c.scene.c_str(), c.user.rule.c_str(), c.total.errors.deflection,
                  c.total.errors.force, c.total.errors.energy, c.iteration.errors.worst(),
                  c.slicing.errors.worst(), c.geometry.errors.worst(), estimate.force, index,
                  c.user.wall_time_s, c.truth().wall_time_s);
    out << line;
  }
  return out.str();
}

}  // namespace fibrecheck
