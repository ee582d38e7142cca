#include "compaction_study_record.h"

#include <algorithm>
#include <sstream>

#include "atomic_file.h"
#include "json_number.h"

namespace fibrecheck {

using nlohmann::json;

std::string CompactionRun::label() const {
  std::ostringstream out;
  out << solver << "_mu" << mu << "_" << friction_model;
  if (geometry == "linearised") out << "_linearised";
  return file_name_slug(out.str());
}

std::vector<StepDifference> step_differences(const CompactionRun& iterative,
                                             const CompactionRun& reference) {
  std::vector<StepDifference> out;
  for (const CompactionPoint& q : reference.points)
    for (const CompactionPoint& i : iterative.points)
      if (i.step == q.step && i.status == "converged" && q.status == "converged")
        out.push_back({q.step, q.fibre_volume_fraction, q.pressure,
                       std::fabs(i.pressure - q.pressure),
                       std::fabs(i.strain_energy - q.strain_energy)});
  return out;
}

double largest_pressure(const CompactionRun& run) {
  double largest = 0.0;
  for (const CompactionPoint& q : run.points)
    if (q.status == "converged") largest = std::max(largest, q.pressure);
  return largest;
}

double largest_strain_energy(const CompactionRun& run) {
  double largest = 0.0;
  for (const CompactionPoint& q : run.points)
    if (q.status == "converged") largest = std::max(largest, q.strain_energy);
  return largest;
}

CompactionAgreement agreement_of(const CompactionRun& iterative, const CompactionRun& reference) {
  CompactionAgreement a;
  a.mu = iterative.mu;
  a.friction_model = iterative.friction_model;
  a.against = reference.friction_model;
  a.geometry = iterative.geometry;
  const double largest_p = largest_pressure(reference),
               largest_u = largest_strain_energy(reference);
  double dp = 0.0, du = 0.0;
  for (const StepDifference& d : step_differences(iterative, reference)) {
    dp = std::max(dp, d.pressure);
    du = std::max(du, d.strain_energy);
    ++a.steps;
  }
  if (a.steps > 0) {
    a.pressure_error = largest_p > 0.0 ? dp / largest_p : NAN;
    a.energy_error = largest_u > 0.0 ? du / largest_u : NAN;
  }
  return a;
}

json to_json(const CompactionPoint& p) {
  return {{"step", p.step},
          {"compaction", p.compaction},
          {"load_factor", p.load_factor},
          {"fibre_volume_fraction", p.fibre_volume_fraction},
          {"pressure_MPa", p.pressure},
          {"strain_energy", p.strain_energy},
          {"contacts_per_fibre", p.contacts_per_fibre},
          {"iterations", p.iterations},
          {"geometric_updates", p.geometric_updates},
          {"fixed_point_updates", p.fixed_point_updates},
          {"stick_residual", number_or_null(p.stick_residual)},
          {"slip_residual", number_or_null(p.slip_residual)},
          {"wall_time_s", p.time_s},
          {"status", p.status}};
}

void from_json(const json& j, CompactionPoint& p) {
  p.step = j.at("step");
  p.compaction = j.at("compaction");
  p.load_factor = j.at("load_factor");
  p.fibre_volume_fraction = j.at("fibre_volume_fraction");
  p.pressure = j.at("pressure_MPa");
  p.strain_energy = j.at("strain_energy");
  p.contacts_per_fibre = j.at("contacts_per_fibre");
  p.iterations = j.at("iterations");
  p.geometric_updates = j.value("geometric_updates", 0L);  // 0 in records kept before them
  p.fixed_point_updates = j.value("fixed_point_updates", 0L);
  // NaN in records kept before them.
  p.stick_residual = j.contains("stick_residual") ? number_from(j["stick_residual"]) : NAN;
  p.slip_residual = j.contains("slip_residual") ? number_from(j["slip_residual"]) : NAN;
  p.time_s = j.at("wall_time_s");
  p.status = j.at("status");
}

json to_json(const CompactionRun& r) {
  json points = json::array(), sections = json::array();
  for (const CompactionPoint& p : r.points) points.push_back(to_json(p));
  for (const auto& [step, file] : r.sections)
    sections.push_back({{"step", step}, {"result", file}});
  return {{"solver", r.solver},
          {"rule", r.rule},
          {"mu", r.mu},
          {"friction_model", r.friction_model},
          {"geometry", r.geometry},
          {"status", r.status},
          {"message", r.message},
          {"wall_time_s", r.time_s},
          {"points", points},
          {"sections", sections},
          {"van_wyk", to_json(r.van_wyk, false)},
          {"toll", to_json(r.toll, true)}};
}

void from_json(const json& j, CompactionRun& r) {
  r.solver = j.at("solver");
  r.rule = j.at("rule");
  r.mu = j.at("mu");
  r.friction_model = j.at("friction_model");
  r.geometry = j.value("geometry", std::string("linearised"));
  r.status = j.at("status");
  r.message = j.at("message");
  r.time_s = j.at("wall_time_s");
  r.points = j.at("points").get<std::vector<CompactionPoint>>();
  r.sections.clear();
  for (const json& s : j.at("sections"))
    r.sections.emplace_back(s.at("step").get<int>(), s.at("result").get<std::string>());
  r.van_wyk = j.at("van_wyk").get<PowerLawFit>();
  r.toll = j.at("toll").get<PowerLawFit>();
}

json to_json(const CompactionAgreement& a) {
  return {{"mu", a.mu},
          {"friction_model", a.friction_model},
          {"against", a.against},
          {"geometry", a.geometry},
          {"pressure_error", number_or_null(a.pressure_error)},
          {"energy_error", number_or_null(a.energy_error)},
          {"steps", a.steps}};
}

void from_json(const json& j, CompactionAgreement& a) {
  a.mu = j.at("mu");
  a.friction_model = j.at("friction_model");
  a.against = j.at("against");
  a.geometry = j.value("geometry", std::string("linearised"));
  a.pressure_error = number_at(j, "pressure_error");
  a.energy_error = number_at(j, "energy_error");
  a.steps = j.at("steps");
}

json to_json(const CompactionStudyScene& s) {
  json runs = json::array(), agreement = json::array();
  for (const CompactionRun& r : s.runs) runs.push_back(to_json(r));
  for (const CompactionAgreement& a : s.agreement) agreement.push_back(to_json(a));
  return {{"scene", s.scene},
          {"scene_file", s.scene_file},
          {"youngs_modulus", s.youngs_modulus},
          {"runs", runs},
          {"agreement", agreement}};
}

void from_json(const json& j, CompactionStudyScene& s) {
  s.scene = j.at("scene");
  s.scene_file = j.at("scene_file");
  s.youngs_modulus = j.at("youngs_modulus");
  s.runs = j.at("runs").get<std::vector<CompactionRun>>();
  s.agreement = j.at("agreement").get<std::vector<CompactionAgreement>>();
}

}  // namespace fibrecheck
