#include "scale_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

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

void check_options(const ScaleStudyOptions& o) {
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
}

/// Every tow size of the study, ascending, each once.
std::vector<int> sizes_of(const ScaleStudyOptions& o) {
  std::vector<int> sizes = o.fibres;
  sizes.insert(sizes.end(), o.reference_fibres.begin(), o.reference_fibres.end());
  std::sort(sizes.begin(), sizes.end());
  sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
  for (int n : sizes)
    if (n < 1) throw InputError("command line", "--fibres", "every size must be at least 1");
  return sizes;
}

bool has(const std::vector<int>& list, int n) {
  return std::find(list.begin(), list.end(), n) != list.end();
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

/// One Siconos answer of the peer's output as a point (its process's time and memory are the
/// whole run's: one process solved them all).
ScalePoint peer_point(const json& answers, const json& a, const ProgramRun& r) {
  ScalePoint p;
  p.solver = "siconos";
  p.method = a.value("solver", "");
  // Judged by the answer's own residual (fibrecheck-siconos' "converged"); an answer Siconos
  // calls solved that does not solve the problem is a wrong answer, not a cap.
  p.status = a.value("converged", false)                ? "converged"
             : a.value("siconos_says_converged", false) ? "diverged"
                                                        : "max_iterations";
  p.iterations = a.value("iterations", 0L);
  p.time_s = a.value("time_s", 0.0);
  p.process_time_s = r.wall_time_s;
  p.peak_memory_mb = r.peak_memory_mb;
  p.peak_proportional_memory_mb = r.peak_proportional_memory_mb;
  p.candidates = answers.value("contacts", 0L);
  // Frictionless (one unknown per contact): the pushing contacts of its answer.
  if (answers.value("unknowns", 0L) == p.candidates) {
    const std::vector<double> reaction = a.value("reaction", std::vector<double>{});
    double largest = 0.0;
    for (double x : reaction) largest = std::max(largest, x);
    for (double x : reaction) p.active += x > 1e-9 * largest ? 1 : 0;
  }
  if (a.contains("against_reference")) p.agreement = a["against_reference"].value("relative", -1.0);
  return p;
}

/// The study's runs on each size, every one its own process, each point kept in the journal as
/// it finishes (a point already there is not run again).
class ScaleRuns {
 public:
  ScaleRuns(const ScaleStudyOptions& o, const ProgramRunner& run, const std::string& folder,
            StudyStore& store, StudyProgress& progress, ScaleStudy& study)
      : o_(o), run_(run), folder_(folder), store_(store), progress_(progress), study_(study) {}

  /// The tow of `n` fibres (generated once), then its iterative, reference and peer points.
  void size(int n) {
    name_ = "tow_" + std::to_string(n);
    scene_ = (fs::path(folder_) / "scenes" / (name_ + ".json")).string();
    problem_ = (fs::path(folder_) / "problems" / (name_ + ".problem.json")).string();
    if (!fs::exists(scene_)) {
      TowOptions tow;
      tow.fibres = n;
      tow.slices = o_.slices;
      tow.seed = o_.seed;
      write_scene(scene_, generate_tow(tow));
    }
    if (has(o_.fibres, n))
      for (const std::string& rule : o_.rules) iterative(n, rule);
    // The reference on one process and on `processes`: what the processes share out.
    if (has(o_.reference_fibres, n)) {
      if (most_processes() > 1) reference(n, 1);
      reference(n, most_processes());
    }
    if (has(o_.peer_fibres, n)) peer(n);
  }

 private:
  void iterative(int n, const std::string& rule) {
    const std::string key = name_ + "/iterative/" + rule;
    if (!start(key, "iterative, rule " + rule)) return;
    ScalePoint p = point(n, "iterative", rule);
    const std::string out = result_file(rule);
    std::vector<std::string> command = {o_.program, "solve", scene_, "--rule",
                                        rule,       "--out", out,    "-q"};
    if (rule == "seed") {
      std::ostringstream c;
      c.precision(17);
      c << o_.seed_c;
      command.insert(command.end(), {"--c", c.str()});
    }
    solve(p, command, out);
    keep(key, p);
  }

  /// The reference on `processes` (under mpiexec when more than one), exporting its contact
  /// problem for the peer from the run on the most processes.
  void reference(int n, int processes) {
    const std::string key = name_ + "/fem/" + std::to_string(processes);
    if (!start(key, "reference on " + std::to_string(processes) + " process" +
                        (processes == 1 ? "" : "es")))
      return;
    ScalePoint p = point(n, "fem", "active_set");
    p.processes = processes;
    const std::string out = result_file("fem");
    std::vector<std::string> command;
    if (p.processes > 1) command = {o_.mpiexec, "-np", std::to_string(p.processes)};
    for (const std::string& a :
         {o_.program, std::string("fem"), scene_, std::string("--out"), out, std::string("-q")})
      command.push_back(a);
    if (has(o_.peer_fibres, n) && processes == most_processes()) {
      command.push_back("--export-contact-problem");
      command.push_back(problem_);
    }
    solve(p, command, out);
    keep(key, p);
  }

  /// Siconos on the reference's exported problem: one point per Siconos solver, all from one run.
  void peer(int n) {
    const std::string key = name_ + "/siconos";
    if (!start(key, "Siconos on the reference's problem")) return;
    const std::string out = (fs::path(folder_) / "results" / (name_ + ".siconos.json")).string();
    std::vector<std::string> command = {o_.peer_program, problem_, "--out", out, "-q"};
    std::string solvers;
    for (const std::string& s : o_.peer_solvers) solvers += (solvers.empty() ? "" : ",") + s;
    if (!solvers.empty()) command.insert(command.end(), {"--solvers", solvers});
    const ProgramRun r = fs::exists(problem_) ? run_(command) : ProgramRun{};
    json answers;
    if (fs::exists(out)) std::ifstream(out) >> answers;
    const json list = answers.value("answers", json::array());
    if (list.empty()) {
      ScalePoint p = point(n, "siconos", "none");
      p.status = fs::exists(problem_) ? failed_status(r) : "no problem (the reference failed)";
      keep(key, p);
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
      ScalePoint p = peer_point(answers, list[k], r);
      p.fibres = n, p.slices = o_.slices;
      keep(key + (k == 0 ? "" : "/" + p.method), p);
    }
  }

  /// The reference's largest process count: `processes` under mpiexec, else one.
  int most_processes() const { return o_.mpiexec.empty() ? 1 : o_.processes; }

  ScalePoint point(int n, const std::string& solver, const std::string& method) const {
    ScalePoint p;
    p.fibres = n, p.slices = o_.slices, p.solver = solver, p.method = method;
    return p;
  }

  std::string result_file(const std::string& what) const {
    return (fs::path(folder_) / "results" / (name_ + "." + what + ".result.json")).string();
  }

  /// False when the point is in the journal already (it joins the study); else announces it.
  bool start(const std::string& key, const std::string& what) {
    if (store_.has(key)) {
      progress_.skip();
      study_.points.push_back(store_.get(key).get<ScalePoint>());
      ++index_;
      return false;
    }
    progress_.start(index_++, name_ + ", " + what);
    return true;
  }

  void keep(const std::string& key, ScalePoint p) {
    store_.add(key, to_json(p));
    study_.points.push_back(std::move(p));
  }

  /// A solver's run: its process's figures, then its result file's (or why there is none).
  void solve(ScalePoint& p, const std::vector<std::string>& command, const std::string& out) {
    const ProgramRun r = run_(command);
    p.process_time_s = r.wall_time_s;
    p.peak_memory_mb = r.peak_memory_mb;
    p.peak_proportional_memory_mb = r.peak_proportional_memory_mb;
    if ((r.exit_code == 0 || r.exit_code == 3) && fs::exists(out))
      take_result(p, out);
    else
      p.status = failed_status(r);
  }

  const ScaleStudyOptions& o_;
  const ProgramRunner& run_;
  const std::string& folder_;
  StudyStore& store_;
  StudyProgress& progress_;
  ScaleStudy& study_;
  std::size_t index_ = 0;
  std::string name_, scene_, problem_;  ///< of the size being run
};

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double d = n * sxx - sx * sx;
  return d != 0.0 ? (n * sxy - sx * sy) / d : NAN;
}

/// The program's peak resident memory when it only starts: what the libraries it maps cost every
/// process, whatever it solves. 0 when the program is not there to run.
double program_floor(const ScaleStudyOptions& o, const ProgramRunner& run) {
  if (o.program.empty()) return 0.0;
  const ProgramRun r = run({o.program, "--help"});
  return r.exit_code == 0 ? r.peak_memory_mb : 0.0;
}

/// Exponents over the converged sizes of each solver, method and process count.
std::vector<ScaleExponent> exponents_of(const std::vector<ScalePoint>& points) {
  std::vector<std::tuple<std::string, std::string, int>> series;
  for (const ScalePoint& p : points)
    if (std::find(series.begin(), series.end(), std::make_tuple(p.solver, p.method, p.processes)) ==
        series.end())
      series.emplace_back(p.solver, p.method, p.processes);
  std::vector<ScaleExponent> exponents;
  for (const auto& [solver, method, processes] : series) {
    std::vector<double> x, t, m;
    for (const ScalePoint& p : points)
      if (p.solver == solver && p.method == method && p.processes == processes &&
          p.status == "converged" && p.time_s > 0.0) {
        x.push_back(std::log(static_cast<double>(p.fibres)));
        t.push_back(std::log(p.time_s));
        m.push_back(std::log(std::max(p.peak_memory_mb, 1e-3)));
      }
    if (x.size() < 2) continue;
    exponents.push_back(
        {solver, method, processes, static_cast<int>(x.size()), slope(x, t), slope(x, m)});
  }
  return exponents;
}

void write_scale_study(const ScaleStudy& study, const std::string& folder) {
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
                    text(p.process_time_s), text(p.agreement),
                    text(p.peak_proportional_memory_mb)});
  write_csv((fs::path(folder) / "scale.csv").string(),
            {"fibres", "slices", "solver", "method", "processes", "status", "candidates", "active",
             "iterations", "time_s", "ms_per_iteration", "peak_memory_mb", "unknowns",
             "process_time_s", "agreement", "peak_proportional_memory_mb"},
            rows);
  write_file_atomically((fs::path(folder) / "scale_study.json").string(),
                        to_json(study).dump(1) + "\n");
}

}  // namespace

ScaleStudy run_scale_study(const ScaleStudyOptions& o, const ProgramRunner& run,
                           const std::string& folder) {
  check_options(o);
  const std::vector<int> sizes = sizes_of(o);
  for (const char* sub : {"scenes", "results", "problems"})
    fs::create_directories(fs::path(folder) / sub);
  StudyStore store(folder, "scale_study");
  std::size_t total = 0;
  for (int n : sizes)
    total += (has(o.fibres, n) ? o.rules.size() : 0) + (has(o.reference_fibres, n) ? 1 : 0) +
             (has(o.peer_fibres, n) ? 1 : 0);
  StudyProgress progress("scale study", total, o.quiet);
  ScaleStudy study;
  study.slices = o.slices;
  study.seed = o.seed;
  study.program_floor_memory_mb = program_floor(o, run);
  ScaleRuns runs(o, run, folder, store, progress, study);
  for (int n : sizes) runs.size(n);
  study.exponents = exponents_of(study.points);
  write_scale_study(study, folder);
  return study;
}

}  // namespace fibrecheck
