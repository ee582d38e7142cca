#include "stability_study_record.h"

#include "json_number.h"

namespace fibrecheck {

using nlohmann::json;

json to_json(const StepPoint& p) {
  return {{"c_over_c_crit", p.fraction}, {"c", p.c},
          {"iterations", p.iterations},  {"status", p.status},
          {"criterion", p.criterion},    {"time_s", p.time_s}};
}

void from_json(const json& j, StepPoint& p) {
  p.fraction = j.at("c_over_c_crit");
  p.c = j.at("c");
  p.iterations = j.at("iterations");
  p.status = j.at("status");
  p.criterion = j.at("criterion");
  p.time_s = j.at("time_s");
}

json to_json(const StiffnessPoint& p) {
  json j = to_json(p.errors);
  j.update({{"stiffness_ratio", p.ratio},
            {"method", p.method},
            {"iterations", p.iterations},
            {"status", p.status},
            {"time_s", p.time_s}});
  return j;
}

void from_json(const json& j, StiffnessPoint& p) {
  p.ratio = j.at("stiffness_ratio");
  p.method = j.at("method");
  p.iterations = j.at("iterations");
  p.status = j.at("status");
  p.time_s = j.at("time_s");
  p.errors = j.get<Errors>();
}

json to_json(const CataloguePoint& p) {
  return {{"solver", p.solver},
          {"rule", p.rule},
          {"status", p.status},
          {"expected_status", p.expected_status},
          {"iterations", p.iterations},
          {"time_s", p.time_s},
          {"error", number_or_null(p.error)},
          {"failures", p.failures}};
}

void from_json(const json& j, CataloguePoint& p) {
  p.solver = j.at("solver");
  p.rule = j.at("rule");
  p.status = j.at("status");
  p.expected_status = j.at("expected_status");
  p.iterations = j.at("iterations");
  p.time_s = j.at("time_s");
  p.error = number_at(j, "error");
  p.failures = j.at("failures");
}

json to_json(const StabilityStudyScene& s) {
  json steps = json::array(), stiffness = json::array(), catalogue = json::array();
  for (const StepPoint& p : s.steps) steps.push_back(to_json(p));
  for (const StiffnessPoint& p : s.stiffness) stiffness.push_back(to_json(p));
  for (const CataloguePoint& p : s.catalogue) catalogue.push_back(to_json(p));
  json j = {{"scene", s.scene}, {"c_crit", s.c_crit}, {"steps", steps}, {"stiffness", stiffness}};
  if (!s.catalogue.empty()) j["catalogue"] = catalogue;
  return j;
}

void from_json(const json& j, StabilityStudyScene& s) {
  s.scene = j.at("scene");
  s.c_crit = j.at("c_crit");
  s.steps = j.at("steps").get<std::vector<StepPoint>>();
  s.stiffness = j.at("stiffness").get<std::vector<StiffnessPoint>>();
  if (j.contains("catalogue")) s.catalogue = j.at("catalogue").get<std::vector<CataloguePoint>>();
}

}  // namespace fibrecheck
