#include "scale_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.h"
#include "csv_file.h"
#include "input_error.h"
#include "result.h"
#include "scene.h"
#include "study_store.h"
#include "tow_generator.h"

namespace fibrecheck {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

json point_json(const ScalePoint& p) {
  return {{"fibres", p.fibres},
          {"slices", p.slices},
          {"solver", p.solver},
          {"method", p.method},
          {"processes", p.processes},
          {"status", p.status},
          {"candidates", p.candidates},
          {"active", p.active},
          {"iterations", p.iterations},
          {"unknowns", p.unknowns},
          {"time_s", p.time_s},
          {"process_time_s", p.process_time_s},
          {"ms_per_iteration", p.ms_per_iteration()},
          {"peak_memory_mb", p.peak_memory_mb},
          {"agreement", p.agreement}};
}

ScalePoint point_from_json(const json& j) {
  ScalePoint p;
  p.fibres = j.value("fibres", 0);
  p.slices = j.value("slices", 0);
  p.solver = j.value("solver", "");
  p.method = j.value("method", "");
  p.processes = j.value("processes", 1);
  p.status = j.value("status", "");
  p.candidates = j.value("candidates", 0L);
  p.active = j.value("active", 0L);
  p.iterations = j.value("iterations", 0L);
  p.unknowns = j.value("unknowns", 0L);
  p.time_s = j.value("time_s", 0.0);
  p.process_time_s = j.value("process_time_s", 0.0);
  p.peak_memory_mb = j.value("peak_memory_mb", 0.0);
  p.agreement = j.value("agreement", -1.0);
  return p;
}

/// The points of a result file: status, iterations, time, candidates and pushing points.
void take_result(ScalePoint& p, const std::string& file) {
  const Result r = read_result(file);
  p.status = to_string(r.status);
  p.iterations = r.iterations;
  p.time_s = r.wall_time_s;
  p.candidates = r.candidates;
  // Pushing: a force above 1e-9 of the largest (an iterate's or a pivot's round-off is not a
  // contact).
  double largest = 0.0;
  for (const ContactResult& c : r.contacts)
    for (const ContactPoint& q : c.points) largest = std::max(largest, q.force.norm());
  p.active = 0;
  for (const ContactResult& c : r.contacts)
    for (const ContactPoint& q : c.points) p.active += q.force.norm() > 1e-9 * largest ? 1 : 0;
  if (r.finite_elements) p.unknowns = r.finite_elements->unknowns;
}

/// The status of a run that wrote nothing: what its exit code says.
std::string failed_status(const ProgramRun& run) {
  return run.exit_code == 3 ? "unsolved" : "failed (exit " + std::to_string(run.exit_code) + ")";
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double d = n * sxx - sx * sx;
  return d != 0.0 ? (n * sxy - sx * sy) / d : NAN;
}

}  // namespace

ScaleStudy run_scale_study(const ScaleStudyOptions& o, const ProgramRunner& run,
                           const std::string& folder) {
  if (o.fibres.empty() && o.reference_fibres.empty())
    throw InputError("command line", "--fibres", "no tow sizes given");
  for (int n : o.peer_fibres)
    if (std::find(o.reference_fibres.begin(), o.reference_fibres.end(), n) ==
        o.reference_fibres.end())
      throw InputError("command line", "--peer-fibres",
                       "the peer solves the reference's problem: every size in --peer-fibres "
                       "must be in --reference-fibres too (" +
                           std::to_string(n) + " is not)");
  if (std::find(o.rules.begin(), o.rules.end(), "seed") != o.rules.end() && !(o.seed_c > 0.0))
    throw InputError("command line", "--seed-c",
                     "the seed rule needs its step c (N/mm): give --seed-c, or leave seed out of "
                     "--rules");
  if (!o.peer_fibres.empty() && o.peer_program.empty())
    throw InputError("command line", "--peer-fibres",
                     "this build has no fibrecheck-siconos (Debian: libsiconos-numerics-dev)");
  std::vector<int> sizes = o.fibres;
  sizes.insert(sizes.end(), o.reference_fibres.begin(), o.reference_fibres.end());
  std::sort(sizes.begin(), sizes.end());
  sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
  for (int n : sizes)
    if (n < 1) throw InputError("command line", "--fibres", "every size must be at least 1");

  for (const char* sub : {"scenes", "results", "problems"})
    fs::create_directories(fs::path(folder) / sub);
  StudyStore store(folder, "scale_study");
  auto has = [](const std::vector<int>& list, int n) {
    return std::find(list.begin(), list.end(), n) != list.end();
  };
  std::size_t total = 0;
  for (int n : sizes)
    total += (has(o.fibres, n) ? o.rules.size() : 0) + (has(o.reference_fibres, n) ? 1 : 0) +
             (has(o.peer_fibres, n) ? 1 : 0);
  StudyProgress progress("scale study", total, o.quiet);
  ScaleStudy study;
  std::size_t index = 0;
  for (int n : sizes) {
    const std::string name = "tow_" + std::to_string(n);
    const std::string scene = (fs::path(folder) / "scenes" / (name + ".json")).string();
    if (!fs::exists(scene)) {
      TowOptions tow;
      tow.fibres = n;
      tow.slices = o.slices;
      tow.seed = o.seed;
      write_scene(scene, generate_tow(tow));
    }
    auto result_file = [&](const std::string& what) {
      return (fs::path(folder) / "results" / (name + "." + what + ".result.json")).string();
    };
    auto keep = [&](const std::string& key, ScalePoint p) {
      store.add(key, point_json(p));
      study.points.push_back(std::move(p));
    };
    // A solver's run: its process's figures, then its result file's (or why there is none).
    auto solve = [&](ScalePoint& p, const std::vector<std::string>& command,
                     const std::string& out) {
      const ProgramRun r = run(command);
      p.process_time_s = r.wall_time_s;
      p.peak_memory_mb = r.peak_memory_mb;
      if ((r.exit_code == 0 || r.exit_code == 3) && fs::exists(out))
        take_result(p, out);
      else
        p.status = failed_status(r);
    };
    auto start = [&](const std::string& key, const std::string& what) {
      if (store.has(key)) {
        progress.skip();
        study.points.push_back(point_from_json(store.get(key)));
        ++index;
        return false;
      }
      progress.start(index++, name + ", " + what);
      return true;
    };
    if (has(o.fibres, n))
      for (const std::string& rule : o.rules) {
        const std::string key = name + "/iterative/" + rule;
        if (!start(key, "iterative, rule " + rule)) continue;
        ScalePoint p;
        p.fibres = n, p.slices = o.slices, p.solver = "iterative", p.method = rule;
        const std::string out = result_file(rule);
        std::vector<std::string> command = {o.program, "solve", scene, "--rule",
                                            rule,      "--out", out,   "-q"};
        if (rule == "seed") {
          std::ostringstream c;
          c.precision(17);
          c << o.seed_c;
          command.insert(command.end(), {"--c", c.str()});
        }
        solve(p, command, out);
        keep(key, p);
      }
    const std::string problem = (fs::path(folder) / "problems" / (name + ".problem.json")).string();
    if (has(o.reference_fibres, n)) {
      const std::string key = name + "/fem/" + std::to_string(o.processes);
      if (start(key, "reference on " + std::to_string(o.processes) + " processes")) {
        ScalePoint p;
        p.fibres = n, p.slices = o.slices, p.solver = "fem", p.method = "active_set";
        p.processes = o.mpiexec.empty() ? 1 : o.processes;
        const std::string out = result_file("fem");
        std::vector<std::string> command;
        if (p.processes > 1) command = {o.mpiexec, "-np", std::to_string(p.processes)};
        for (const std::string& a :
             {o.program, std::string("fem"), scene, std::string("--out"), out, std::string("-q")})
          command.push_back(a);
        if (has(o.peer_fibres, n)) {
          command.push_back("--export-contact-problem");
          command.push_back(problem);
        }
        solve(p, command, out);
        keep(key, p);
      }
    }
    if (has(o.peer_fibres, n)) {
      const std::string key = name + "/siconos";
      if (start(key, "Siconos on the reference's problem")) {
        const std::string out = (fs::path(folder) / "results" / (name + ".siconos.json")).string();
        std::vector<std::string> command = {o.peer_program, problem, "--out", out, "-q"};
        std::string solvers;
        for (const std::string& s : o.peer_solvers) solvers += (solvers.empty() ? "" : ",") + s;
        if (!solvers.empty()) command.insert(command.end(), {"--solvers", solvers});
        const ProgramRun r = fs::exists(problem) ? run(command) : ProgramRun{};
        // One point per Siconos solver, all from this one run (its peak memory is the largest).
        json answers;
        if (fs::exists(out)) std::ifstream(out) >> answers;
        const json list = answers.value("answers", json::array());
        if (list.empty()) {
          ScalePoint p;
          p.fibres = n, p.slices = o.slices, p.solver = "siconos", p.method = "none";
          p.status = fs::exists(problem) ? failed_status(r) : "no problem (the reference failed)";
          keep(key, p);
        }
        for (std::size_t k = 0; k < list.size(); ++k) {
          const json& a = list[k];
          ScalePoint p;
          p.fibres = n, p.slices = o.slices, p.solver = "siconos";
          p.method = a.value("solver", "");
          // Judged by the answer's own residual (fibrecheck-siconos' "converged"); an answer
          // Siconos calls solved that does not solve the problem is a wrong answer, not a cap.
          p.status = a.value("converged", false)              ? "converged"
                     : a.value("siconos_says_converged", false) ? "diverged"
                                                               : "max_iterations";
          p.iterations = a.value("iterations", 0L);
          p.time_s = a.value("time_s", 0.0);
          p.process_time_s = r.wall_time_s;
          p.peak_memory_mb = r.peak_memory_mb;
          p.candidates = answers.value("contacts", 0L);
          // Frictionless (one unknown per contact): the pushing contacts of its answer.
          if (answers.value("unknowns", 0L) == p.candidates) {
            const std::vector<double> reaction = a.value("reaction", std::vector<double>{});
            double largest = 0.0;
            for (double x : reaction) largest = std::max(largest, x);
            for (double x : reaction) p.active += x > 1e-9 * largest ? 1 : 0;
          }
          if (a.contains("against_reference"))
            p.agreement = a["against_reference"].value("relative", -1.0);
          keep(key + (k == 0 ? "" : "/" + p.method), p);
        }
      }
    }
  }
  // Exponents over the converged sizes of each solver and method.
  std::vector<std::pair<std::string, std::string>> series;
  for (const ScalePoint& p : study.points)
    if (std::find(series.begin(), series.end(), std::make_pair(p.solver, p.method)) == series.end())
      series.emplace_back(p.solver, p.method);
  for (const auto& [solver, method] : series) {
    std::vector<double> x, t, m;
    for (const ScalePoint& p : study.points)
      if (p.solver == solver && p.method == method && p.status == "converged" && p.time_s > 0.0) {
        x.push_back(std::log(static_cast<double>(p.fibres)));
        t.push_back(std::log(p.time_s));
        m.push_back(std::log(std::max(p.peak_memory_mb, 1e-3)));
      }
    if (x.size() < 2) continue;
    study.exponents.push_back(
        {solver, method, static_cast<int>(x.size()), slope(x, t), slope(x, m)});
  }
  std::vector<std::vector<std::string>> rows;
  auto text = [](double v) {
    std::ostringstream out;
    out.precision(6);
    out << v;
    return out.str();
  };
  for (const ScalePoint& p : study.points)
    rows.push_back({std::to_string(p.fibres), std::to_string(p.slices), p.solver, p.method,
                    std::to_string(p.processes), p.status, std::to_string(p.candidates),
                    std::to_string(p.active), std::to_string(p.iterations), text(p.time_s),
                    text(p.ms_per_iteration()), text(p.peak_memory_mb), std::to_string(p.unknowns),
                    text(p.process_time_s), text(p.agreement)});
  write_csv((fs::path(folder) / "scale.csv").string(),
            {"fibres", "slices", "solver", "method", "processes", "status", "candidates", "active",
             "iterations", "time_s", "ms_per_iteration", "peak_memory_mb", "unknowns",
             "process_time_s", "agreement"},
            rows);
  json j = {{"study", "scale"}, {"slices", o.slices}, {"seed", o.seed}};
  j["points"] = json::array();
  for (const ScalePoint& p : study.points) j["points"].push_back(point_json(p));
  j["exponents"] = json::array();
  for (const ScaleExponent& e : study.exponents)
    j["exponents"].push_back({{"solver", e.solver},
                              {"method", e.method},
                              {"sizes", e.sizes},
                              {"time", e.time},
                              {"memory", e.memory}});
  write_file_atomically((fs::path(folder) / "scale_study.json").string(), j.dump(1) + "\n");
  return study;
}

}  // namespace fibrecheck
