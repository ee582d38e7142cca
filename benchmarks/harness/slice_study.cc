#include "slice_study.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "study_store.h"

namespace fibrecheck {

std::vector<SliceStudyScene> run_slice_study(const std::vector<Scene>& scenes,
                                             const SliceStudyOptions& options,
                                             const Solvers& solvers, const std::string& folder) {
  StudyStore store(folder, "slice_study");
  StudyProgress progress("slice study", scenes.size() * (options.slices.size() + 1), options.quiet);
  std::vector<SliceStudyScene> out;
  std::size_t index = 0;
  for (const Scene& scene : scenes) {
    progress.start(index++, scene.name + ": ground truth");
    const Result truth = stored_ground_truth(scene, solvers, folder);
    SliceStudyScene study;
    study.scene = scene.name;
    study.rule = to_string(scene.solver.rule);
    study.tolerance = scene.overlap_tolerance();
    study.truth_time_s = truth.wall_time_s;
    if (truth.finite_elements)
      study.truth_error_estimate = truth.finite_elements->line_force_error_estimate;
    for (int n : options.slices) {
      const std::string key = scene.name + "/" + std::to_string(n);
      if (!store.has(key)) {
        progress.start(index, scene.name + ", " + std::to_string(n) + " slices");
        Scene sliced = scene;
        sliced.contact.slices = n;
        const Result run = solvers.iterative(sliced);
        const Errors e = measure_errors(run, truth, scene.name).errors;
        nlohmann::json point = to_json(e);
        point.update({{"scene", scene.name},
                      {"slices", n},
                      {"iterative_time_s", run.wall_time_s},
                      {"iterations", run.iterations},
                      {"status", to_string(run.status)}});
        store.add(key, point);
      } else {
        progress.skip();
      }
      ++index;
      const nlohmann::json& p = store.get(key);
      SliceStudyPoint point;
      point.slices = n;
      point.time_s = p["iterative_time_s"];
      point.iterations = p["iterations"];
      point.status = p["status"];
      point.errors = {p["deflection_error"], p["force_error"], p["energy_error"]};
      study.points.push_back(point);
    }
    std::vector<double> n, d, f, u;
    for (const SliceStudyPoint& p : study.points) {
      n.push_back(p.slices);
      d.push_back(p.errors.deflection);
      f.push_back(p.errors.force);
      u.push_back(p.errors.energy);
    }
    study.order = {observed_order(n, d), observed_order(n, f), observed_order(n, u)};
    out.push_back(study);
  }
  nlohmann::json all = nlohmann::json::array();
  std::vector<std::vector<std::string>> rows;
  for (const SliceStudyScene& s : out) {
    all.push_back(to_json(s));
    for (const SliceStudyPoint& p : s.points)
      rows.push_back({s.scene, std::to_string(p.slices), cell(p.time_s), cell(p.errors.deflection),
                      cell(p.errors.force), cell(p.errors.energy), std::to_string(p.iterations),
                      p.status});
  }
  write_file_atomically((std::filesystem::path(folder) / "slice_study.json").string(),
                        all.dump(1) + "\n");
  write_csv((std::filesystem::path(folder) / "slice_study.csv").string(),
            {"scene", "slices", "iterative_time_s", "deflection_error", "force_error",
             "energy_error", "iterations", "status"},
            rows);
  return out;
}

nlohmann::json to_json(const SliceStudyScene& s) {
  nlohmann::json points = nlohmann::json::array();
  for (const SliceStudyPoint& p : s.points) {
    nlohmann::json j = to_json(p.errors);
    j.update({{"slices", p.slices},
              {"iterative_time_s", p.time_s},
              {"iterations", p.iterations},
              {"status", p.status}});
    points.push_back(j);
  }
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  return {{"scene", s.scene},
          {"rule", s.rule},
          {"overlap_tolerance", s.tolerance},
          {"truth_time_s", s.truth_time_s},
          {"truth_error_estimate", s.truth_error_estimate},
          {"order",
           {{"deflection_error", number(s.order.deflection)},
            {"force_error", number(s.order.force)},
            {"energy_error", number(s.order.energy)}}},
          {"points", points}};
}

}  // namespace fibrecheck
