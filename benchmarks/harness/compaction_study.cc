#include "compaction_study.h"

#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "atomic_file.h"
#include "csv_file.h"
#include "input_error.h"
#include "study_store.h"

namespace fibrecheck {

namespace {

using nlohmann::json;

std::string slug(const std::string& name) {
  return file_name_slug(name);
}

json number_or_null(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}
double number_from(const json& j) {
  return j.is_number() ? j.get<double>() : NAN;
}

json fit_json(const PowerLawFit& f, bool with_n) {
  json j = {{"k", number_or_null(f.k)},
            {"vf0", number_or_null(f.vf0)},
            {"r2", number_or_null(f.r2)},
            {"points", f.points}};
  if (with_n) j["n"] = number_or_null(f.n);
  return j;
}

PowerLawFit fit_from(const json& j) {
  PowerLawFit f;
  f.k = number_from(j.at("k"));
  f.vf0 = number_from(j.at("vf0"));
  f.r2 = number_from(j.at("r2"));
  f.n = j.contains("n") ? number_from(j.at("n")) : 3.0;
  f.points = j.at("points").get<int>();
  f.valid = std::isfinite(f.k);
  return f;
}

/// The mean pressure on the walls (MPa): each wall's normal force over its area.
double mean_pressure(const StepResult& step) {
  if (step.wall_pressure.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& [id, p] : step.wall_pressure) sum += p;
  return sum / static_cast<double>(step.wall_pressure.size());
}

json run_json(const CompactionRun& r) {
  json points = json::array();
  for (const CompactionPoint& p : r.points)
    points.push_back({{"step", p.step},
                      {"compaction", p.compaction},
                      {"load_factor", p.load_factor},
                      {"fibre_volume_fraction", p.fibre_volume_fraction},
                      {"pressure_MPa", p.pressure},
                      {"strain_energy", p.strain_energy},
                      {"contacts_per_fibre", p.contacts_per_fibre},
                      {"iterations", p.iterations},
                      {"wall_time_s", p.time_s},
                      {"status", p.status}});
  json sections = json::array();
  for (const auto& [step, file] : r.sections)
    sections.push_back({{"step", step}, {"result", file}});
  return {{"solver", r.solver},
          {"rule", r.rule},
          {"mu", r.mu},
          {"friction_model", r.friction_model},
          {"status", r.status},
          {"message", r.message},
          {"wall_time_s", r.time_s},
          {"points", points},
          {"sections", sections},
          {"van_wyk", fit_json(r.van_wyk, false)},
          {"toll", fit_json(r.toll, true)}};
}

CompactionRun run_from(const json& j) {
  CompactionRun r;
  r.solver = j.at("solver");
  r.rule = j.at("rule");
  r.mu = j.at("mu");
  r.friction_model = j.at("friction_model");
  r.status = j.at("status");
  r.message = j.value("message", "");
  r.time_s = j.at("wall_time_s");
  for (const json& p : j.at("points")) {
    CompactionPoint q;
    q.step = p.at("step");
    q.compaction = p.at("compaction");
    q.load_factor = p.at("load_factor");
    q.fibre_volume_fraction = p.at("fibre_volume_fraction");
    q.pressure = p.at("pressure_MPa");
    q.strain_energy = p.at("strain_energy");
    q.contacts_per_fibre = p.at("contacts_per_fibre");
    q.iterations = p.at("iterations");
    q.time_s = p.at("wall_time_s");
    q.status = p.at("status");
    r.points.push_back(q);
  }
  for (const json& s : j.value("sections", json::array()))
    r.sections.emplace_back(s.at("step").get<int>(), s.at("result").get<std::string>());
  r.van_wyk = fit_from(j.at("van_wyk"));
  r.toll = fit_from(j.at("toll"));
  return r;
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

CompactionAgreement agree(const CompactionRun& iterative, const CompactionRun& reference) {
  CompactionAgreement a;
  a.mu = iterative.mu;
  a.friction_model = iterative.friction_model;
  a.against = reference.friction_model;
  double largest_p = 0.0, largest_u = 0.0;
  for (const CompactionPoint& q : reference.points)
    if (q.status == "converged") {
      largest_p = std::max(largest_p, q.pressure);
      largest_u = std::max(largest_u, q.strain_energy);
    }
  double dp = 0.0, du = 0.0;
  for (const CompactionPoint& q : reference.points)
    for (const CompactionPoint& i : iterative.points)
      if (i.step == q.step && i.status == "converged" && q.status == "converged") {
        dp = std::max(dp, std::fabs(i.pressure - q.pressure));
        du = std::max(du, std::fabs(i.strain_energy - q.strain_energy));
        ++a.steps;
      }
  if (a.steps > 0) {
    a.pressure_error = largest_p > 0.0 ? dp / largest_p : NAN;
    a.energy_error = largest_u > 0.0 ? du / largest_u : NAN;
  }
  return a;
}

}  // namespace

std::string CompactionRun::label() const {
  std::ostringstream out;
  out << solver << "_mu" << mu << "_" << friction_model;
  return slug(out.str());
}

PowerLawFit fit_power_law(const std::vector<double>& vf, const std::vector<double>& pressure,
                          double modulus, double n) {
  PowerLawFit f;
  f.n = n;
  f.points = static_cast<int>(vf.size());
  if (vf.size() < 2 || !(modulus > 0.0)) return f;
  const double m = static_cast<double>(vf.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0, mean_p = 0;
  for (std::size_t i = 0; i < vf.size(); ++i) {
    const double x = std::pow(vf[i], n), y = pressure[i] / modulus;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    mean_p += pressure[i] / m;
  }
  const double det = m * sxx - sx * sx;
  if (!(std::fabs(det) > 1e-300)) return f;
  const double a = (m * sxy - sx * sy) / det, b = (sy - a * sx) / m;
  double residual = 0.0, total = 0.0;
  for (std::size_t i = 0; i < vf.size(); ++i) {
    const double predicted = modulus * (a * std::pow(vf[i], n) + b);
    residual += (pressure[i] - predicted) * (pressure[i] - predicted);
    total += (pressure[i] - mean_p) * (pressure[i] - mean_p);
  }
  f.valid = true;
  f.k = a;
  f.vf0 = (a != 0.0 && -b / a > 0.0) ? std::pow(-b / a, 1.0 / n) : NAN;
  f.r2 = total > 0.0 ? 1.0 - residual / total : NAN;
  return f;
}

PowerLawFit fit_toll(const std::vector<double>& vf, const std::vector<double>& pressure,
                     double modulus) {
  PowerLawFit best;
  best.points = static_cast<int>(vf.size());
  if (vf.size() < 3) return best;
  for (int i = 100; i <= 3000; ++i) {
    const PowerLawFit f = fit_power_law(vf, pressure, modulus, 0.01 * i);
    if (f.valid && std::isfinite(f.r2) && (!best.valid || f.r2 > best.r2)) best = f;
  }
  return best;
}

std::vector<CompactionStudyScene> run_compaction_study(const std::vector<Scene>& input,
                                                       const CompactionStudyOptions& options,
                                                       const Solvers& solvers,
                                                       const std::string& folder) {
  // Check every scene before anything runs.
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
  StudyStore store(folder, "compaction_study");
  struct Plan {
    std::string solver;
    double mu;
    FrictionModel model;
    bool frictionless;
  };
  std::size_t total = 0;
  for (const Scene& s : scenes) total += s.contact.friction > 0.0 ? 5 : 2;
  StudyProgress progress("compaction study", total, options.quiet);
  std::size_t index = 0;
  std::vector<CompactionStudyScene> out;
  for (const Scene& scene : scenes) {
    CompactionStudyScene study;
    study.scene = scene.name;
    const std::filesystem::path dir = std::filesystem::path(folder) / slug(scene.name);
    std::filesystem::create_directories(dir);
    study.scene_file = slug(scene.name) + "/scene.json";
    write_scene((dir / "scene.json").string(), scene);
    for (const FibreSpec& f : scene.fibres)
      study.youngs_modulus += f.youngs_modulus / static_cast<double>(scene.fibres.size());
    std::vector<Plan> plans = {{"iterative", 0.0, FrictionModel::coulomb, true},
                               {"fem", 0.0, FrictionModel::coulomb, true}};
    const double mu = scene.contact.friction;
    if (mu > 0.0) {
      plans.push_back({"iterative", mu, FrictionModel::coulomb, false});
      plans.push_back({"iterative", mu, FrictionModel::seed, false});
      plans.push_back({"fem", mu, FrictionModel::coulomb, false});
    }
    for (const Plan& plan : plans) {
      CompactionRun run;
      run.solver = plan.solver;
      run.mu = plan.mu;
      run.friction_model = plan.frictionless ? "none" : to_string(plan.model);
      const std::string key = scene.name + "/" + run.label();
      if (store.has(key)) {
        progress.skip();
        study.runs.push_back(run_from(store.get(key)));
        ++index;
        continue;
      }
      progress.start(index++, scene.name + ", " + run.solver + ", mu " + std::to_string(plan.mu) +
                                  " " + run.friction_model);
      Scene s = scene;
      s.contact.friction = plan.mu;
      s.contact.friction_model = plan.model;
      auto solve = [&](const Scene& x) {
        return plan.solver == "fem" ? solvers.reference_slices(x) : solvers.iterative(x);
      };
      const Result result = solve(s);
      run.rule = result.rule;
      run.status = to_string(result.status);
      run.message = result.message;
      run.time_s = result.wall_time_s;
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
        p.time_s = st.wall_time_s;
        p.status = to_string(st.status);
        run.points.push_back(p);
      }
      const int last = static_cast<int>(result.steps.size());
      const std::string file = run.label() + ".step" + std::to_string(last) + ".result.json";
      write_result((dir / file).string(), result);
      run.sections.emplace_back(last, slug(scene.name) + "/" + file);
      // Earlier states for the pictures (the iterative solver's, which the report draws): the
      // path up to that step, again.
      for (int k : options.sections) {
        if (k < 1 || k >= last || plan.solver != "iterative") continue;
        Scene partial = s;
        partial.steps.resize(static_cast<std::size_t>(k));
        const std::string name = run.label() + ".step" + std::to_string(k) + ".result.json";
        write_result((dir / name).string(), solve(partial));
        run.sections.emplace_back(k, slug(scene.name) + "/" + name);
      }
      fit(run, study.youngs_modulus);
      store.add(key, run_json(run));
      study.runs.push_back(run);
    }
    // The iterative runs against the reference of the same μ (Coulomb's law, exactly).
    for (const CompactionRun& it : study.runs) {
      if (it.solver != "iterative") continue;
      for (const CompactionRun& ref : study.runs)
        if (ref.solver == "fem" && ref.mu == it.mu) study.agreement.push_back(agree(it, ref));
    }
    out.push_back(study);
  }

  // The data: the study's JSON, the curves as CSV, the fits.
  const std::filesystem::path dir(folder);
  json all = json::array(), fits = json::array();
  std::vector<std::vector<std::string>> rows;
  for (const CompactionStudyScene& s : out) {
    all.push_back(to_json(s));
    json scene_fits = json::array();
    for (const CompactionRun& r : s.runs) {
      scene_fits.push_back({{"solver", r.solver},
                            {"mu", r.mu},
                            {"friction_model", r.friction_model},
                            {"van_wyk", fit_json(r.van_wyk, false)},
                            {"toll", fit_json(r.toll, true)}});
      for (const CompactionPoint& p : r.points)
        rows.push_back({s.scene, r.solver, std::to_string(p.step), cell(p.fibre_volume_fraction),
                        cell(p.pressure), cell(p.strain_energy), cell(p.contacts_per_fibre),
                        cell(r.mu), r.friction_model, p.status});
    }
    fits.push_back(
        {{"scene", s.scene}, {"youngs_modulus", s.youngs_modulus}, {"fits", scene_fits}});
  }
  write_file_atomically((dir / "compaction_study.json").string(), all.dump(1) + "\n");
  write_file_atomically((dir / "compaction_fit.json").string(),
                        json({{"scenes", fits}}).dump(1) + "\n");
  write_csv((dir / "compaction.csv").string(),
            {"scene", "solver", "step", "fibre_volume_fraction", "pressure_MPa", "strain_energy",
             "contacts_per_fibre", "mu", "friction_model", "status"},
            rows);
  return out;
}

nlohmann::json to_json(const CompactionStudyScene& scene) {
  json runs = json::array(), agreement = json::array();
  for (const CompactionRun& r : scene.runs) runs.push_back(run_json(r));
  for (const CompactionAgreement& a : scene.agreement)
    agreement.push_back({{"mu", a.mu},
                         {"friction_model", a.friction_model},
                         {"against", a.against},
                         {"pressure_error", number_or_null(a.pressure_error)},
                         {"energy_error", number_or_null(a.energy_error)},
                         {"steps", a.steps}});
  return {{"scene", scene.scene},
          {"scene_file", scene.scene_file},
          {"youngs_modulus", scene.youngs_modulus},
          {"runs", runs},
          {"agreement", agreement}};
}

}  // namespace fibrecheck
