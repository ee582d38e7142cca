#include "friction_study.h"

#include <filesystem>

#include "atomic_file.h"
#include "csv_file.h"
#include "load_path.h"
#include "study_store.h"
#include "tow_generator.h"

namespace fibrecheck {

namespace {

using nlohmann::json;

/// The tow of `fibres` compacted in one step to F, its contacts with μ.
Scene frictional_tow(const FrictionStudyOptions& options, int fibres, double compaction,
                     double mu) {
  TowOptions tow;
  tow.fibres = fibres;
  tow.slices = options.slices;
  tow.seed = options.seed;
  tow.volume_fraction = options.volume_fraction;
  tow.compaction = compaction;
  tow.friction = mu;
  Scene scene = generate_tow(tow);
  scene.solver.max_iterations = options.max_iterations;
  scene.name =
      "tow_" + std::to_string(fibres) + "_F" + key_number(compaction) + "_mu" + key_number(mu);
  return scene;
}

double mean_wall_pressure(const Result& r) {
  if (r.walls.empty()) return NAN;
  double sum = 0.0;
  for (const WallResult& w : r.walls) sum += w.pressure;
  return sum / static_cast<double>(r.walls.size());
}

FrictionPoint measured(const Scene& scene, int fibres, double compaction, double mu,
                       const Result& r) {
  FrictionPoint p;
  p.fibres = fibres;
  p.compaction = compaction;
  p.mu = mu;
  p.model = to_string(scene.contact.friction_model);
  p.fibre_volume_fraction = fibre_volume_fraction(scene);
  p.status = to_string(r.status);
  p.criterion = to_string(r.criterion);
  p.message = r.message;
  p.iterations = r.iterations;
  p.geometric_updates = r.geometric_updates;
  p.time_s = r.wall_time_s;
  if (r.friction) {
    p.stick_residual = r.friction->stick_residual;
    p.slip_residual = r.friction->slip_residual;
  }
  p.pressure = mean_wall_pressure(r);
  return p;
}

void write_friction_study(const std::vector<FrictionPoint>& points, const std::string& folder) {
  json all = json::array();
  std::vector<std::vector<std::string>> rows;
  for (const FrictionPoint& p : points) {
    all.push_back(to_json(p));
    rows.push_back({std::to_string(p.fibres), cell(p.compaction), cell(p.fibre_volume_fraction),
                    cell(p.mu), p.model, p.status, p.criterion, std::to_string(p.iterations),
                    std::to_string(p.geometric_updates), cell(p.time_s), cell(p.stick_residual),
                    cell(p.slip_residual), cell(p.pressure)});
  }
  const std::filesystem::path dir(folder);
  write_file_atomically((dir / "friction_study.json").string(), all.dump(1) + "\n");
  write_csv((dir / "friction_study.csv").string(),
            {"fibres", "compaction", "fibre_volume_fraction", "mu", "friction_model", "status",
             "criterion", "iterations", "geometric_updates", "time_s", "stick_residual_mm",
             "slip_residual_mm", "pressure_MPa"},
            rows);
}

/// One run of the study: a tow, its size, F and μ, and the friction model it is solved with.
struct FrictionRun {
  Scene scene;
  int fibres;
  double compaction, mu;
};

/// Every run, each tow generated once: options no tow can be made with are refused before the
/// study writes anything.
std::vector<FrictionRun> friction_runs(const FrictionStudyOptions& options) {
  std::vector<FrictionRun> runs;
  for (int fibres : options.fibres)
    for (double compaction : options.compactions)
      for (double mu : options.mu) {
        const Scene tow = frictional_tow(options, fibres, compaction, mu);
        for (FrictionModel model : {FrictionModel::seed, FrictionModel::coulomb}) {
          runs.push_back({tow, fibres, compaction, mu});
          runs.back().scene.contact.friction_model = model;
        }
      }
  return runs;
}

}  // namespace

std::vector<FrictionPoint> run_friction_study(const FrictionStudyOptions& options,
                                              const std::function<Result(const Scene&)>& iterative,
                                              const std::string& folder) {
  const std::vector<FrictionRun> runs = friction_runs(options);
  StudyStore store(folder, "friction_study");
  StudyProgress progress("friction study", runs.size(), options.quiet);
  std::vector<FrictionPoint> points;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const FrictionRun& run = runs[i];
    const std::string model = to_string(run.scene.contact.friction_model);
    const std::string key = run.scene.name + "/" + model;
    if (store.has(key)) {
      progress.skip();
    } else {
      progress.start(i, run.scene.name + ", " + model + " friction");
      store.add(key, to_json(measured(run.scene, run.fibres, run.compaction, run.mu,
                                      iterative(run.scene))));
    }
    points.push_back(store.get(key).get<FrictionPoint>());
  }
  write_friction_study(points, folder);
  return points;
}

}  // namespace fibrecheck
