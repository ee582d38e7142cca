#include "stability_study.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "atomic_file.h"
#include "csv_file.h"
#include "expected_outcome.h"
#include "input_error.h"
#include "study_store.h"

namespace fibrecheck {

namespace {

using nlohmann::json;

Scene stiffer(const Scene& scene, double ratio) {
  Scene s = scene;
  for (std::size_t i = 1; i < s.fibres.size(); i += 2) s.fibres[i].youngs_modulus *= ratio;
  s.name = scene.name + " x" + key_number(ratio);
  return s;
}

// The journal's lines keep the names they were first written with: a step's c/c_crit is its
// `fraction`, and a stiffness point's ratio and method are in its key only.

json journal_line(const StepPoint& p) {
  json j = to_json(p);
  j["fraction"] = j.at("c_over_c_crit");
  j.erase("c_over_c_crit");
  return j;
}

StepPoint step_from_journal(json j) {
  j["c_over_c_crit"] = j.at("fraction");
  return j.get<StepPoint>();
}

json journal_line(const StiffnessPoint& p) {
  json j = to_json(p);
  j.erase("stiffness_ratio");
  j.erase("method");
  return j;
}

StiffnessPoint stiffness_from_journal(json j, double ratio, const std::string& method) {
  j["stiffness_ratio"] = ratio;
  j["method"] = method;
  return j.get<StiffnessPoint>();
}

/// One solver on a catalogue scene, judged against what the scene expects.
CataloguePoint catalogue_run(const Scene& scene, const std::string& solver,
                             const Solvers& solvers) {
  CataloguePoint point;
  point.solver = solver;
  point.expected_status = expected_status(*scene.expected, solver);
  Result r;
  try {
    r = solver == "iterative" ? solvers.iterative(scene) : solvers.reference_slices(scene);
  } catch (const InputError& e) {
    point.status = "refused";  // a catalogue scene is never bad input: a failure
    point.failures = e.what();
    return point;
  }
  const OutcomeCheck check = check_outcome(*scene.expected, r, solver);
  point.rule = r.rule;
  point.status = to_string(r.status);
  point.iterations = r.iterations;
  point.time_s = r.wall_time_s;
  point.error = check.error;
  for (const std::string& f : check.failures)
    point.failures += (point.failures.empty() ? "" : "; ") + f;
  return point;
}

/// The rules of the stiffness sweep (the seed at half its limit).
struct Rule {
  std::string label;
  UpdateRule rule;
};
const Rule kStiffnessRules[] = {Rule{"seed 0.5", UpdateRule::seed},
                                Rule{"auto", UpdateRule::automatic},
                                Rule{"accelerated", UpdateRule::accelerated}};

/// The study's runs, each kept in its journal as it finishes (a run already there is not run
/// again).
class StabilityRuns {
 public:
  StabilityRuns(const StabilityStudyOptions& options, const Solvers& solvers, StudyStore& store,
                StudyProgress& progress)
      : options_(options), solvers_(solvers), store_(store), progress_(progress) {}

  StabilityStudyScene run(const Scene& scene) {
    StabilityStudyScene study;
    study.scene = scene.name;
    if (scene.expected) {
      for (const char* solver : {"iterative", "reference"})
        study.catalogue.push_back(
            point(scene.name + "/catalogue/" + solver, scene.name + ", " + solver, [&] {
              return to_json(catalogue_run(scene, solver, solvers_));
            }).get<CataloguePoint>());
      return study;
    }
    study.c_crit = seed_stable_limit(scene, solvers_);
    for (double f : options_.fractions) study.steps.push_back(step(scene, f, study.c_crit));
    for (double ratio : options_.stiffness_ratios) stiffness(scene, ratio, study.stiffness);
    return study;
  }

 private:
  /// The rule seed at c = f c_crit.
  StepPoint step(const Scene& scene, double f, double c_crit) {
    return step_from_journal(point(
        scene.name + "/c/" + key_number(f), scene.name + ", c = " + key_number(f) + " c_crit", [&] {
          Scene s = scene;
          s.solver.rule = UpdateRule::seed;
          s.solver.c = f * c_crit;
          s.solver.energy_tolerance = 0.0;
          s.solver.force_tolerance = 0.0;  // the seed's method as it stands
          s.solver.max_iterations = options_.max_iterations;
          const Result r = solvers_.iterative(s);
          return journal_line(StepPoint{f, f * c_crit, r.iterations, to_string(r.status),
                                        to_string(r.criterion), r.wall_time_s});
        }));
  }

  /// The reference and every rule at one stiffness ratio, each rule against the reference.
  void stiffness(const Scene& scene, double ratio, std::vector<StiffnessPoint>& into) {
    const Scene s = stiffer(scene, ratio);
    std::optional<Result> reference;
    auto truth = [&]() -> const Result& {
      if (!reference) reference = solvers_.reference_slices(s);
      return *reference;
    };
    const std::string base = scene.name + "/stiffness/" + key_number(ratio) + "/";
    into.push_back(stiffness_from_journal(
        point(base + "reference", s.name + ", reference",
              [&] { return journal_line(measured(ratio, "reference", truth(), Errors{})); }),
        ratio, "reference"));
    for (const Rule& rule : kStiffnessRules)
      into.push_back(stiffness_from_journal(
          point(base + rule.label, s.name + ", " + rule.label,
                [&] {
                  Scene t = s;
                  t.solver.rule = rule.rule;
                  if (rule.rule == UpdateRule::seed)
                    t.solver.c = 0.5 * seed_stable_limit(s, solvers_);
                  t.solver.max_iterations = options_.max_iterations;
                  const Result r = solvers_.iterative(t);
                  return journal_line(measured(ratio, rule.label, r,
                                               truth().status == Status::converged
                                                   ? measure_errors(r, truth(), s.name).errors
                                                   : Errors{NAN, NAN, NAN}));
                }),
          ratio, rule.label));
  }

  static StiffnessPoint measured(double ratio, const std::string& method, const Result& r,
                                 const Errors& errors) {
    return {ratio, method, r.iterations, to_string(r.status), r.wall_time_s, errors};
  }

  /// The journal's line of `key`: there already, or computed and kept.
  const json& point(const std::string& key, const std::string& what,
                    const std::function<json()>& compute) {
    if (store_.has(key)) {
      progress_.skip();
    } else {
      progress_.start(index_, what);
      store_.add(key, compute());
    }
    ++index_;
    return store_.get(key);
  }

  const StabilityStudyOptions& options_;
  const Solvers& solvers_;
  StudyStore& store_;
  StudyProgress& progress_;
  std::size_t index_ = 0;
};

void write_stability_study(const std::vector<StabilityStudyScene>& studies,
                           const std::string& folder) {
  json all = json::array();
  std::vector<std::vector<std::string>> steps, stiffness, catalogue;
  for (const StabilityStudyScene& s : studies) {
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
  StabilityRuns runs(options, solvers, store, progress);
  std::vector<StabilityStudyScene> out;
  for (const Scene& scene : scenes) out.push_back(runs.run(scene));
  write_stability_study(out, folder);
  return out;
}

}  // namespace fibrecheck
