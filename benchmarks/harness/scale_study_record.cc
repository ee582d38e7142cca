#include "scale_study_record.h"

#include "json_number.h"

namespace fibrecheck {

using nlohmann::json;

json to_json(const ScalePoint& p) {
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
          {"peak_proportional_memory_mb", p.peak_proportional_memory_mb},
          {"agreement", p.agreement}};
}

void from_json(const json& j, ScalePoint& p) {
  p.fibres = j.at("fibres");
  p.slices = j.at("slices");
  p.solver = j.at("solver");
  p.method = j.at("method");
  p.processes = j.at("processes");
  p.status = j.at("status");
  p.candidates = j.at("candidates");
  p.active = j.at("active");
  p.iterations = j.at("iterations");
  p.unknowns = j.at("unknowns");
  p.time_s = j.at("time_s");
  p.process_time_s = j.at("process_time_s");
  p.peak_memory_mb = j.at("peak_memory_mb");
  p.peak_proportional_memory_mb = j.value("peak_proportional_memory_mb", 0.0);
  p.agreement = j.at("agreement");
}

json to_json(const ScaleExponent& e) {
  return {{"solver", e.solver},
          {"method", e.method},
          {"processes", e.processes},
          {"sizes", e.sizes},
          {"time", number_or_null(e.time)},
          {"memory", number_or_null(e.memory)}};
}

void from_json(const json& j, ScaleExponent& e) {
  e.solver = j.at("solver");
  e.method = j.at("method");
  e.processes = j.value("processes", 1);
  e.sizes = j.at("sizes");
  e.time = number_at(j, "time");
  e.memory = number_at(j, "memory");
}

json to_json(const ScaleStudy& s) {
  json points = json::array(), exponents = json::array();
  for (const ScalePoint& p : s.points) points.push_back(to_json(p));
  for (const ScaleExponent& e : s.exponents) exponents.push_back(to_json(e));
  json j = {{"study", "scale"},
            {"slices", s.slices},
            {"seed", s.seed},
            {"points", points},
            {"exponents", exponents}};
  j["program_floor_memory_mb"] = s.program_floor_memory_mb;
  return j;
}

bool is_scale_study(const json& j) {
  return j.is_object() && j.value("study", "") == "scale";
}

void from_json(const json& j, ScaleStudy& s) {
  s.slices = j.at("slices");
  s.seed = j.at("seed");
  s.program_floor_memory_mb = j.value("program_floor_memory_mb", 0.0);
  s.points = j.at("points").get<std::vector<ScalePoint>>();
  s.exponents = j.at("exponents").get<std::vector<ScaleExponent>>();
}

}  // namespace fibrecheck
