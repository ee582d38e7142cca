#include "tolerance_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.h"
#include "study_store.h"

namespace fibrecheck {

namespace {

/// The fastest of up to three runs when one takes under half a second: a short run's time is
/// mostly noise on a shared machine.
Result timed(const std::function<Result()>& run) {
  Result best = run();
  for (int repeat = 1; repeat < 3 && best.wall_time_s < 0.5; ++repeat) {
    Result again = run();
    if (again.wall_time_s < best.wall_time_s) best = std::move(again);
  }
  return best;
}

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

}  // namespace

void pareto_and_speedups(ToleranceStudyScene& s, const std::vector<double>& levels) {
  std::map<std::string, std::vector<TolerancePoint*>> by_method;
  for (TolerancePoint& p : s.points) by_method[p.method].push_back(&p);
  for (auto& [method, points] : by_method) {
    std::sort(points.begin(), points.end(), [](const TolerancePoint* a, const TolerancePoint* b) {
      return a->time_s < b->time_s;
    });
    double best = INFINITY;
    for (TolerancePoint* p : points) {
      p->pareto = p->status == "converged" && p->errors.worst() < best;
      if (p->pareto) best = p->errors.worst();
    }
  }
  s.speedups.clear();
  for (double level : levels) {
    SpeedUp up;
    up.error_level = level;
    for (const TolerancePoint& p : s.points) {
      if (p.status != "converged" || !(p.errors.worst() <= level)) continue;
      const bool reference = p.method == "reference";
      double& time = reference ? up.reference_time_s : up.iterative_time_s;
      if (std::isnan(time) || p.time_s < time) {
        time = p.time_s;
        if (!reference) up.iterative_method = p.method;
      }
    }
    s.speedups.push_back(up);
  }
}

std::vector<ToleranceStudyScene> run_tolerance_study(const std::vector<Scene>& scenes,
                                                     const ToleranceStudyOptions& options,
                                                     const Solvers& solvers,
                                                     const std::string& folder) {
  StudyStore store(folder, "tolerance_study");
  const std::size_t rules = options.seed_fractions.size() + 2;
  StudyProgress progress(
      "tolerance study",
      scenes.size() * (1 + rules * options.tolerances.size() * options.slice_factors.size() +
                       options.refinements.size()),
      options.quiet);
  std::vector<ToleranceStudyScene> out;
  std::size_t index = 0;
  for (const Scene& scene : scenes) {
    progress.start(index++, scene.name + ": ground truth");
    const bool continuous = needs_continuous_reference(scene) && !options.against_slices;
    const Result truth =
        continuous ? stored_ground_truth(scene, solvers, folder) : solvers.reference_slices(scene);
    ToleranceStudyScene study;
    study.scene = scene.name;
    study.truth = continuous ? "reference_continuous" : "reference_slices";
    if (truth.finite_elements)
      study.truth_error_estimate = truth.finite_elements->line_force_error_estimate;
    double radius = INFINITY;
    for (const FibreSpec& f : scene.fibres) radius = std::min(radius, f.radius);
    const double c_limit = options.seed_fractions.empty() ? NAN : seed_stable_limit(scene, solvers);
    struct Rule {
      std::string label;
      UpdateRule rule;
      double c;
    };
    std::vector<Rule> list;
    for (double f : options.seed_fractions)
      list.push_back({"seed " + number_text(f), UpdateRule::seed, f * c_limit});
    list.push_back({"auto", UpdateRule::automatic, NAN});
    list.push_back({"accelerated", UpdateRule::accelerated, NAN});
    auto record = [&](const std::string& key, const std::string& method, double parameter,
                      int slices, const Result& run) {
      nlohmann::json point = to_json(measure_errors(run, truth, scene.name).errors);
      point.update({{"scene", scene.name},
                    {"method", method},
                    {"parameter", parameter},
                    {"slices", slices},
                    {"time_s", run.wall_time_s},
                    {"iterations", run.iterations},
                    {"status", to_string(run.status)}});
      store.add(key, point);
    };
    const std::vector<int> factors =
        options.against_slices ? std::vector<int>{1} : options.slice_factors;
    for (const Rule& rule : list)
      for (int factor : factors)
        for (double t : options.tolerances) {
          const double td = t * radius;
          const int n = scene.contact.slices * factor;
          const std::string key =
              scene.name + "/" + rule.label + "/" + number_text(td) + "/" + std::to_string(n);
          if (store.has(key)) {
            progress.skip();
            ++index;
            continue;
          }
          progress.start(index++, scene.name + ", " + rule.label + ", t_d = " + number_text(td) +
                                      " mm, " + std::to_string(n) + " slices");
          Scene s = scene;
          s.contact.slices = n;
          s.solver.rule = rule.rule;
          // The seed's limit is that of D½WD½, whose line part hardly depends on n (W grows
          // with the slices as D shrinks): the same fractions of one limit.
          if (rule.rule == UpdateRule::seed) s.solver.c = rule.c;
          s.solver.overlap_tolerance = td;
          s.solver.energy_tolerance = 0.0;
          s.solver.max_iterations = options.max_iterations;
          record(key, rule.label, td, n, timed([&] { return solvers.iterative(s); }));
        }
    for (int K : options.refinements) {
      if (!continuous && K != options.refinements.front()) {
        ++index;
        continue;
      }
      const std::string key = scene.name + "/reference/" + std::to_string(K);
      if (store.has(key)) {
        progress.skip();
        ++index;
        continue;
      }
      progress.start(index++, scene.name + ", reference" +
                                  (continuous ? ", refinement " + std::to_string(K) : ""));
      record(key, "reference", K, scene.contact.slices << K, timed([&] {
               return continuous ? solvers.reference_refined(scene, K)
                                 : solvers.reference_slices(scene);
             }));
    }
    for (const nlohmann::json& p : store.points()) {
      if (p["scene"] != scene.name) continue;
      TolerancePoint point;
      point.method = p["method"];
      point.parameter = p["parameter"];
      point.slices = p.value("slices", 0);
      point.time_s = p["time_s"];
      point.iterations = p["iterations"];
      point.status = p["status"];
      point.errors = {p["deflection_error"], p["force_error"], p["energy_error"]};
      study.points.push_back(point);
    }
    pareto_and_speedups(study, options.error_levels);
    out.push_back(study);
  }
  nlohmann::json all = nlohmann::json::array();
  std::vector<std::vector<std::string>> rows, speed;
  for (const ToleranceStudyScene& s : out) {
    all.push_back(to_json(s));
    for (const TolerancePoint& p : s.points)
      rows.push_back({s.scene, p.method, cell(p.parameter), std::to_string(p.slices),
                      cell(p.time_s), std::to_string(p.iterations), p.status,
                      cell(p.errors.deflection), cell(p.errors.force), cell(p.errors.energy),
                      p.pareto ? "1" : "0"});
    for (const SpeedUp& u : s.speedups)
      speed.push_back({s.scene, cell(u.error_level), cell(u.iterative_time_s),
                       cell(u.reference_time_s), cell(u.speedup())});
  }
  const std::filesystem::path dir(folder);
  write_file_atomically((dir / "tolerance_study.json").string(), all.dump(1) + "\n");
  write_csv((dir / "tolerance_study.csv").string(),
            {"scene", "method", "parameter", "slices", "time_s", "iterations", "status",
             "deflection_error", "force_error", "energy_error", "pareto"},
            rows);
  write_csv((dir / "speedup.csv").string(),
            {"scene", "error_level", "iterative_time_s", "reference_time_s", "speedup"}, speed);
  return out;
}

nlohmann::json to_json(const ToleranceStudyScene& s) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  nlohmann::json points = nlohmann::json::array(), speedups = nlohmann::json::array();
  for (const TolerancePoint& p : s.points) {
    nlohmann::json j = to_json(p.errors);
    j.update({{"method", p.method},
              {"parameter", p.parameter},
              {"slices", p.slices},
              {"time_s", p.time_s},
              {"iterations", p.iterations},
              {"status", p.status},
              {"pareto", p.pareto}});
    points.push_back(j);
  }
  for (const SpeedUp& u : s.speedups)
    speedups.push_back({{"error_level", u.error_level},
                        {"iterative_time_s", number(u.iterative_time_s)},
                        {"iterative_method", u.iterative_method},
                        {"reference_time_s", number(u.reference_time_s)},
                        {"speedup", number(u.speedup())}});
  return {{"scene", s.scene},
          {"ground_truth", s.truth},
          {"truth_error_estimate", s.truth_error_estimate},
          {"points", points},
          {"speedups", speedups}};
}

}  // namespace fibrecheck
