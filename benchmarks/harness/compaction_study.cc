#include "compaction_study.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "csv_file.h"
#include "input_error.h"
#include "study_store.h"

namespace fibrecheck {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// The scenes as the study runs them, checked before anything runs: each with walls, and with a
/// load path (`options.steps` steps down to the final compaction where it has none).
std::vector<Scene> stepped_scenes(const std::vector<Scene>& input,
                                  const CompactionStudyOptions& options) {
  std::vector<Scene> scenes = input;
  for (Scene& scene : scenes) {
    if (scene.walls.empty())
      throw InputError(scene.source, "walls",
                       "the compaction study measures the pressure on the walls: the scene has "
                       "none");
    if (scene.steps.empty()) {
      if (options.steps <= 0)
        throw InputError(scene.source, "steps",
                         "the scene has no load path: write `steps`, or give --steps K and "
                         "--final-compaction F");
      for (int k = 1; k <= options.steps; ++k)
        scene.steps.push_back({1.0 - (1.0 - options.final_compaction) * k / options.steps, 1.0});
    }
  }
  return scenes;
}

/// The mean pressure on the walls (MPa): each wall's normal force over its area.
double mean_pressure(const StepResult& step) {
  if (step.wall_pressure.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& [id, p] : step.wall_pressure) sum += p;
  return sum / static_cast<double>(step.wall_pressure.size());
}

/// A run to make: the solver, μ, friction model and contact geometry.
struct Plan {
  std::string solver;
  double mu;
  FrictionModel model;
  bool frictionless;
  ContactGeometryModel geometry;
};

/// Whether the reference runs on `scene`: not when it has more than `limit` fibres (0: no limit).
bool within(const Scene& scene, int limit) {
  return limit == 0 || scene.fibres.size() <= static_cast<std::size_t>(limit);
}

/// Both solvers frictionless in the scene's contact geometry and in the other; with the scene's
/// μ > 0 also both with Coulomb friction and the iterative solver with the seed's rule. The
/// reference only on scenes within `reference_fibres`, with friction within
/// `frictional_reference_fibres`.
std::vector<Plan> plans_of(const Scene& scene, const CompactionStudyOptions& options) {
  const ContactGeometryModel own = scene.contact.geometry;
  const ContactGeometryModel other = in_other_geometry(scene).contact.geometry;
  const bool reference = within(scene, options.reference_fibres);
  const double mu = scene.contact.friction;
  std::vector<Plan> plans = {{"iterative", 0.0, FrictionModel::coulomb, true, own}};
  if (reference) plans.push_back({"fem", 0.0, FrictionModel::coulomb, true, own});
  if (mu > 0.0) {
    plans.push_back({"iterative", mu, FrictionModel::coulomb, false, own});
    plans.push_back({"iterative", mu, FrictionModel::seed, false, own});
    if (reference && within(scene, options.frictional_reference_fibres))
      plans.push_back({"fem", mu, FrictionModel::coulomb, false, own});
  }
  plans.push_back({"iterative", 0.0, FrictionModel::coulomb, true, other});
  if (reference) plans.push_back({"fem", 0.0, FrictionModel::coulomb, true, other});
  return plans;
}

CompactionRun planned_run(const Plan& plan) {
  CompactionRun run;
  run.solver = plan.solver;
  run.mu = plan.mu;
  run.friction_model = plan.frictionless ? "none" : to_string(plan.model);
  run.geometry = to_string(plan.geometry);
  return run;
}

/// The load path's steps of a result.
std::vector<CompactionPoint> points_of(const Result& result) {
  std::vector<CompactionPoint> points;
  for (std::size_t k = 0; k < result.steps.size(); ++k) {
    const StepResult& st = result.steps[k];
    CompactionPoint p;
    p.step = static_cast<int>(k) + 1;
    p.compaction = st.compaction;
    p.load_factor = st.load_factor;
    p.fibre_volume_fraction = st.fibre_volume_fraction;
    p.pressure = mean_pressure(st);
    p.strain_energy = st.strain_energy;
    p.contacts_per_fibre = st.contacts_per_fibre;
    p.iterations = st.iterations;
    p.geometric_updates = st.geometric_updates;
    p.fixed_point_updates = st.fixed_point_updates;
    p.stick_residual = st.stick_residual;
    p.slip_residual = st.slip_residual;
    p.time_s = st.wall_time_s;
    p.status = to_string(st.status);
    points.push_back(p);
  }
  return points;
}

void fit(CompactionRun& run, double modulus) {
  std::vector<double> vf, p;
  for (const CompactionPoint& q : run.points)
    if (q.status == "converged" && q.pressure > 0.0) {
      vf.push_back(q.fibre_volume_fraction);
      p.push_back(q.pressure);
    }
  run.van_wyk = fit_power_law(vf, p, modulus, 3.0);
  run.toll = fit_toll(vf, p, modulus);
}

/// Runs `plan` on the scene's load path, keeps its last state (and, for the iterative solver, the
/// states at `options.sections`: the path up to that step, again) in the scene's folder `dir`
/// (named `slug` in the study's folder), and fits its curve.
CompactionRun run_plan(const Scene& scene, const Plan& plan, const CompactionStudyOptions& options,
                       const Solvers& solvers, double modulus, const fs::path& dir,
                       const std::string& slug) {
  CompactionRun run = planned_run(plan);
  Scene s = scene;
  s.contact.friction = plan.mu;
  s.contact.friction_model = plan.model;
  s.contact.geometry = plan.geometry;
  auto solve = [&](const Scene& x) {
    return plan.solver == "fem" ? solvers.reference_slices(x) : solvers.iterative(x);
  };
  const Result result = solve(s);
  run.rule = result.rule;
  run.status = to_string(result.status);
  run.message = result.message;
  run.time_s = result.wall_time_s;
  run.points = points_of(result);
  const int last = static_cast<int>(result.steps.size());
  const std::string file = run.label() + ".step" + std::to_string(last) + ".result.json";
  write_result((dir / file).string(), result);
  run.sections.emplace_back(last, slug + "/" + file);
  for (int k : options.sections) {
    if (k < 1 || k >= last || plan.solver != "iterative") continue;
    Scene partial = s;
    partial.steps.resize(static_cast<std::size_t>(k));
    const std::string name = run.label() + ".step" + std::to_string(k) + ".result.json";
    write_result((dir / name).string(), solve(partial));
    run.sections.emplace_back(k, slug + "/" + name);
  }
  fit(run, modulus);
  return run;
}

/// The iterative runs against the reference of the same μ (Coulomb's law, exactly).
std::vector<CompactionAgreement> agreements_of(const std::vector<CompactionRun>& runs) {
  std::vector<CompactionAgreement> out;
  for (const CompactionRun& it : runs) {
    if (it.solver != "iterative") continue;
    for (const CompactionRun& ref : runs)
      if (ref.solver == "fem" && ref.mu == it.mu && ref.geometry == it.geometry)
        out.push_back(agreement_of(it, ref));
  }
  return out;
}

/// The data: the study's JSON, the fits, the curves as CSV.
void write_compaction_study(const std::vector<CompactionStudyScene>& studies,
                            const std::string& folder) {
  const fs::path dir(folder);
  json all = json::array(), fits = json::array();
  std::vector<std::vector<std::string>> rows;
  for (const CompactionStudyScene& s : studies) {
    all.push_back(to_json(s));
    json scene_fits = json::array();
    for (const CompactionRun& r : s.runs) {
      scene_fits.push_back({{"solver", r.solver},
                            {"mu", r.mu},
                            {"friction_model", r.friction_model},
                            {"geometry", r.geometry},
                            {"van_wyk", to_json(r.van_wyk, false)},
                            {"toll", to_json(r.toll, true)}});
      for (const CompactionPoint& p : r.points)
        rows.push_back({s.scene, r.solver, std::to_string(p.step), cell(p.fibre_volume_fraction),
                        cell(p.pressure), cell(p.strain_energy), cell(p.contacts_per_fibre),
                        cell(r.mu), r.friction_model, p.status, r.geometry});
    }
    fits.push_back(
        {{"scene", s.scene}, {"youngs_modulus", s.youngs_modulus}, {"fits", scene_fits}});
  }
  write_file_atomically((dir / "compaction_study.json").string(), all.dump(1) + "\n");
  write_file_atomically((dir / "compaction_fit.json").string(),
                        json({{"scenes", fits}}).dump(1) + "\n");
  write_csv((dir / "compaction.csv").string(),
            {"scene", "solver", "step", "fibre_volume_fraction", "pressure_MPa", "strain_energy",
             "contacts_per_fibre", "mu", "friction_model", "status", "geometry"},
            rows);
}

}  // namespace

std::vector<CompactionStudyScene> run_compaction_study(const std::vector<Scene>& input,
                                                       const CompactionStudyOptions& options,
                                                       const Solvers& solvers,
                                                       const std::string& folder) {
  const std::vector<Scene> scenes = stepped_scenes(input, options);
  StudyStore store(folder, "compaction_study");
  std::size_t total = 0;
  for (const Scene& s : scenes) total += plans_of(s, options).size();
  StudyProgress progress("compaction study", total, options.quiet);
  std::size_t index = 0;
  std::vector<CompactionStudyScene> out;
  for (const Scene& scene : scenes) {
    CompactionStudyScene study;
    study.scene = scene.name;
    const std::string slug = file_name_slug(scene.name);
    const fs::path dir = fs::path(folder) / slug;
    fs::create_directories(dir);
    study.scene_file = slug + "/scene.json";
    write_scene((dir / "scene.json").string(), scene);
    for (const FibreSpec& f : scene.fibres)
      study.youngs_modulus += f.youngs_modulus / static_cast<double>(scene.fibres.size());
    for (const Plan& plan : plans_of(scene, options)) {
      const CompactionRun planned = planned_run(plan);
      const std::string key = scene.name + "/" + planned.label();
      if (store.has(key)) {
        progress.skip();
        study.runs.push_back(store.get(key).get<CompactionRun>());
        ++index;
        continue;
      }
      progress.start(index++, scene.name + ", " + planned.solver + ", mu " +
                                  std::to_string(plan.mu) + " " + planned.friction_model);
      study.runs.push_back(
          run_plan(scene, plan, options, solvers, study.youngs_modulus, dir, slug));
      store.add(key, to_json(study.runs.back()));
    }
    study.agreement = agreements_of(study.runs);
    out.push_back(study);
  }
  write_compaction_study(out, folder);
  return out;
}

}  // namespace fibrecheck
