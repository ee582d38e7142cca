#include "stability_study.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.h"
#include "expected_outcome.h"
#include "input_error.h"
#include "study_store.h"

namespace fibrecheck {

namespace {

std::string text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

Scene stiffer(const Scene& scene, double ratio) {
  Scene s = scene;
  for (std::size_t i = 1; i < s.fibres.size(); i += 2) s.fibres[i].youngs_modulus *= ratio;
  s.name = scene.name + " x" + text(ratio);
  return s;
}

}  // namespace

std::vector<StabilityStudyScene> run_stability_study(const std::vector<Scene>& scenes,
                                                     const StabilityStudyOptions& options,
                                                     const Solvers& solvers,
                                                     const std::string& folder) {
  StudyStore store(folder, "stability_study");
  std::size_t points = 0;
  for (const Scene& scene : scenes)
    points += scene.expected ? 2 : options.fractions.size() + 4 * options.stiffness_ratios.size();
  StudyProgress progress("stability study", points, options.quiet);
  std::vector<StabilityStudyScene> out;
  std::size_t index = 0;
  auto run_point = [&](const std::string& key, const std::string& what,
                       const std::function<nlohmann::json()>& compute) -> const nlohmann::json& {
    if (store.has(key)) {
      progress.skip();
    } else {
      progress.start(index, what);
      store.add(key, compute());
    }
    ++index;
    return store.get(key);
  };
  for (const Scene& scene : scenes) {
    StabilityStudyScene study;
    study.scene = scene.name;
    if (scene.expected) {
      for (const char* solver : {"iterative", "reference"}) {
        const nlohmann::json& p =
            run_point(scene.name + "/catalogue/" + solver, scene.name + ", " + solver, [&] {
              CataloguePoint point;
              point.solver = solver;
              point.expected_status = expected_status(*scene.expected, solver);
              Result r;
              try {
                r = point.solver == "iterative" ? solvers.iterative(scene)
                                                : solvers.reference_slices(scene);
              } catch (const InputError& e) {
                point.status = "refused";  // beyond the solver's reach, said as bad input
                if (point.expected_status != "refused") point.failures = e.what();
                return to_json(point);
              }
              const OutcomeCheck check = check_outcome(*scene.expected, r, solver);
              point.rule = r.rule;
              point.status = to_string(r.status);
              point.iterations = r.iterations;
              point.time_s = r.wall_time_s;
              point.error = check.error;
              for (const std::string& f : check.failures)
                point.failures += (point.failures.empty() ? "" : "; ") + f;
              return to_json(point);
            });
        study.catalogue.push_back(catalogue_point(p));
      }
      out.push_back(study);
      continue;
    }
    study.c_crit = seed_stable_limit(scene, solvers);
    for (double f : options.fractions) {
      const nlohmann::json& p =
          run_point(scene.name + "/c/" + text(f), scene.name + ", c = " + text(f) + " c_crit", [&] {
            Scene s = scene;
            s.solver.rule = UpdateRule::seed;
            s.solver.c = f * study.c_crit;
            s.solver.energy_tolerance = 0.0;
            s.solver.max_iterations = options.max_iterations;
            const Result r = solvers.iterative(s);
            return nlohmann::json{{"fraction", f},
                                  {"c", f * study.c_crit},
                                  {"iterations", r.iterations},
                                  {"status", to_string(r.status)},
                                  {"criterion", to_string(r.criterion)},
                                  {"time_s", r.wall_time_s}};
          });
      study.steps.push_back(
          {p["fraction"], p["c"], p["iterations"], p["status"], p["criterion"], p["time_s"]});
    }
    for (double ratio : options.stiffness_ratios) {
      const Scene s = stiffer(scene, ratio);
      std::optional<Result> reference;
      auto truth = [&]() -> const Result& {
        if (!reference) reference = solvers.reference_slices(s);
        return *reference;
      };
      const std::string base = scene.name + "/stiffness/" + text(ratio) + "/";
      const nlohmann::json& ref = run_point(base + "reference", s.name + ", reference", [&] {
        const Result& r = truth();
        nlohmann::json j = to_json(Errors{});
        j.update({{"iterations", r.iterations},
                  {"status", to_string(r.status)},
                  {"time_s", r.wall_time_s}});
        return j;
      });
      study.stiffness.push_back(
          {ratio, "reference", ref["iterations"], ref["status"], ref["time_s"], Errors{}});
      struct Rule {
        std::string label;
        UpdateRule rule;
      };
      for (const Rule& rule :
           {Rule{"seed 0.5", UpdateRule::seed}, Rule{"auto", UpdateRule::automatic},
            Rule{"accelerated", UpdateRule::accelerated}}) {
        const nlohmann::json& p = run_point(base + rule.label, s.name + ", " + rule.label, [&] {
          Scene t = s;
          t.solver.rule = rule.rule;
          if (rule.rule == UpdateRule::seed) t.solver.c = 0.5 * seed_stable_limit(s, solvers);
          t.solver.max_iterations = options.max_iterations;
          const Result r = solvers.iterative(t);
          nlohmann::json j = to_json(truth().status == Status::converged
                                         ? measure_errors(r, truth(), s.name).errors
                                         : Errors{NAN, NAN, NAN});
          j.update({{"iterations", r.iterations},
                    {"status", to_string(r.status)},
                    {"time_s", r.wall_time_s}});
          return j;
        });
        auto value = [](const nlohmann::json& x) { return x.is_number() ? x.get<double>() : NAN; };
        study.stiffness.push_back(
            {ratio,
             rule.label,
             p["iterations"],
             p["status"],
             p["time_s"],
             {value(p["deflection_error"]), value(p["force_error"]), value(p["energy_error"])}});
      }
    }
    out.push_back(study);
  }
  nlohmann::json all = nlohmann::json::array();
  std::vector<std::vector<std::string>> steps, stiffness, catalogue;
  for (const StabilityStudyScene& s : out) {
    all.push_back(to_json(s));
    for (const StepPoint& p : s.steps)
      steps.push_back({s.scene, cell(p.fraction), cell(p.c), std::to_string(p.iterations), p.status,
                       p.criterion, cell(p.time_s)});
    for (const StiffnessPoint& p : s.stiffness)
      stiffness.push_back({s.scene, cell(p.ratio), p.method, std::to_string(p.iterations), p.status,
                           cell(p.time_s), cell(p.errors.deflection), cell(p.errors.force),
                           cell(p.errors.energy)});
    for (const CataloguePoint& p : s.catalogue)
      catalogue.push_back({s.scene, p.solver, p.rule, p.expected_status, p.status,
                           std::to_string(p.iterations), cell(p.time_s), cell(p.error),
                           p.failures.empty() ? "yes" : "no"});
  }
  const std::filesystem::path dir(folder);
  write_file_atomically((dir / "stability_study.json").string(), all.dump(1) + "\n");
  write_csv((dir / "step_sweep.csv").string(),
            {"scene", "c_over_c_crit", "c", "iterations", "status", "criterion", "time_s"}, steps);
  write_csv((dir / "stiffness_sweep.csv").string(),
            {"scene", "stiffness_ratio", "method", "iterations", "status", "time_s",
             "deflection_error", "force_error", "energy_error"},
            stiffness);
  if (!catalogue.empty())
    write_csv((dir / "catalogue.csv").string(),
              {"scene", "solver", "rule", "expected_status", "status", "iterations", "time_s",
               "error", "as_expected"},
              catalogue);
  return out;
}

nlohmann::json to_json(const CataloguePoint& p) {
  return {{"solver", p.solver},
          {"rule", p.rule},
          {"status", p.status},
          {"expected_status", p.expected_status},
          {"iterations", p.iterations},
          {"time_s", p.time_s},
          {"error", std::isfinite(p.error) ? nlohmann::json(p.error) : nlohmann::json()},
          {"failures", p.failures}};
}

CataloguePoint catalogue_point(const nlohmann::json& j) {
  CataloguePoint p;
  p.solver = j.value("solver", "");
  p.rule = j.value("rule", "");
  p.status = j.value("status", "");
  p.expected_status = j.value("expected_status", "");
  p.iterations = j.value("iterations", 0L);
  p.time_s = j.value("time_s", 0.0);
  p.error = j.contains("error") && j["error"].is_number() ? j["error"].get<double>() : NAN;
  p.failures = j.value("failures", "");
  return p;
}

nlohmann::json to_json(const StabilityStudyScene& s) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  nlohmann::json steps = nlohmann::json::array(), stiffness = nlohmann::json::array();
  for (const StepPoint& p : s.steps)
    steps.push_back({{"c_over_c_crit", p.fraction},
                     {"c", p.c},
                     {"iterations", p.iterations},
                     {"status", p.status},
                     {"criterion", p.criterion},
                     {"time_s", p.time_s}});
  for (const StiffnessPoint& p : s.stiffness)
    stiffness.push_back({{"stiffness_ratio", p.ratio},
                         {"method", p.method},
                         {"iterations", p.iterations},
                         {"status", p.status},
                         {"time_s", p.time_s},
                         {"deflection_error", number(p.errors.deflection)},
                         {"force_error", number(p.errors.force)},
                         {"energy_error", number(p.errors.energy)}});
  nlohmann::json catalogue = nlohmann::json::array();
  for (const CataloguePoint& p : s.catalogue) catalogue.push_back(to_json(p));
  nlohmann::json j = {
      {"scene", s.scene}, {"c_crit", s.c_crit}, {"steps", steps}, {"stiffness", stiffness}};
  if (!s.catalogue.empty()) j["catalogue"] = catalogue;
  return j;
}

}  // namespace fibrecheck
