#include "slice_study.h"

#include <filesystem>

#include "atomic_file.h"
#include "csv_file.h"
#include "study_store.h"

namespace fibrecheck {

namespace {

/// The point at n slices: from the study's journal, or run and kept there (with its scene).
SliceStudyPoint slice_point(const Scene& scene, int n, const Result& truth, const Solvers& solvers,
                            StudyStore& store, StudyProgress& progress, std::size_t index) {
  const std::string key = scene.name + "/" + std::to_string(n);
  if (store.has(key)) {
    progress.skip();
    return store.get(key).get<SliceStudyPoint>();
  }
  progress.start(index, scene.name + ", " + std::to_string(n) + " slices");
  Scene sliced = scene;
  sliced.contact.slices = n;
  const Result run = solvers.iterative(sliced);
  SliceStudyPoint point;
  point.slices = n;
  point.time_s = run.wall_time_s;
  point.iterations = run.iterations;
  point.status = to_string(run.status);
  point.errors = measure_errors(run, truth, scene.name).errors;
  nlohmann::json line = to_json(point);
  line["scene"] = scene.name;
  store.add(key, line);
  return point;
}

/// The observed orders of the three errors over the study's slice counts.
Errors observed_orders(const std::vector<SliceStudyPoint>& points) {
  std::vector<double> n, d, f, u;
  for (const SliceStudyPoint& p : points) {
    n.push_back(p.slices);
    d.push_back(p.errors.deflection);
    f.push_back(p.errors.force);
    u.push_back(p.errors.energy);
  }
  return {observed_order(n, d), observed_order(n, f), observed_order(n, u)};
}

void write_slice_study(const std::vector<SliceStudyScene>& studies, const std::string& folder) {
  nlohmann::json all = nlohmann::json::array();
  std::vector<std::vector<std::string>> rows;
  for (const SliceStudyScene& s : studies) {
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
}

}  // namespace

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
    for (int n : options.slices)
      study.points.push_back(slice_point(scene, n, truth, solvers, store, progress, index++));
    study.order = observed_orders(study.points);
    out.push_back(study);
  }
  write_slice_study(out, folder);
  return out;
}

}  // namespace fibrecheck
