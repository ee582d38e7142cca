#include "tolerance_study_record.h"

#include "json_number.h"

namespace fibrecheck {

using nlohmann::json;

json to_json(const TolerancePoint& p) {
  json j = to_json(p.errors);
  j.update({{"method", p.method},
            {"parameter", p.parameter},
            {"slices", p.slices},
            {"time_s", p.time_s},
            {"iterations", p.iterations},
            {"status", p.status},
            {"pareto", p.pareto}});
  if (p.method != "reference") {
    j["error_estimate"] = to_json(p.estimate);
    j["effectivity"] = to_json(p.effectivity);
  }
  return j;
}

void from_json(const json& j, TolerancePoint& p) {
  p.method = j.at("method");
  p.parameter = j.at("parameter");
  p.slices = j.at("slices");
  p.time_s = j.at("time_s");
  p.iterations = j.at("iterations");
  p.status = j.at("status");
  p.errors = j.get<Errors>();
  const Errors none{NAN, NAN, NAN};
  p.estimate = j.contains("error_estimate") ? j.at("error_estimate").get<Errors>() : none;
  p.effectivity = j.contains("effectivity") ? j.at("effectivity").get<Errors>() : none;
  p.pareto = j.at("pareto");
}

json to_json(const SpeedUp& u) {
  return {{"error_level", u.error_level},
          {"iterative_time_s", number_or_null(u.iterative_time_s)},
          {"iterative_method", u.iterative_method},
          {"reference_time_s", number_or_null(u.reference_time_s)},
          {"speedup", number_or_null(u.speedup())}};
}

void from_json(const json& j, SpeedUp& u) {
  u.error_level = j.at("error_level");
  u.iterative_time_s = number_at(j, "iterative_time_s");
  u.iterative_method = j.at("iterative_method");
  u.reference_time_s = number_at(j, "reference_time_s");
}

json to_json(const ToleranceStudyScene& s) {
  json points = json::array(), speedups = json::array();
  for (const TolerancePoint& p : s.points) points.push_back(to_json(p));
  for (const SpeedUp& u : s.speedups) speedups.push_back(to_json(u));
  return {{"scene", s.scene},
          {"ground_truth", s.truth},
          {"truth_error_estimate", s.truth_error_estimate},
          {"points", points},
          {"speedups", speedups}};
}

void from_json(const json& j, ToleranceStudyScene& s) {
  s.scene = j.at("scene");
  s.truth = j.at("ground_truth");
  s.truth_error_estimate = j.at("truth_error_estimate");
  s.points = j.at("points").get<std::vector<TolerancePoint>>();
  s.speedups = j.at("speedups").get<std::vector<SpeedUp>>();
}

}  // namespace fibrecheck
