#include "slice_study_record.h"

#include "json_number.h"

namespace fibrecheck {

using nlohmann::json;

json to_json(const SliceStudyPoint& p) {
  json j = to_json(p.errors);
  j.update({{"slices", p.slices},
            {"iterative_time_s", p.time_s},
            {"iterations", p.iterations},
            {"status", p.status}});
  return j;
}

void from_json(const json& j, SliceStudyPoint& p) {
  p.slices = j.at("slices");
  p.time_s = j.at("iterative_time_s");
  p.iterations = j.at("iterations");
  p.status = j.at("status");
  p.errors = j.get<Errors>();
}

json to_json(const SliceStudyScene& s) {
  json points = json::array();
  for (const SliceStudyPoint& p : s.points) points.push_back(to_json(p));
  return {{"scene", s.scene},
          {"rule", s.rule},
          {"overlap_tolerance", s.tolerance},
          {"truth_time_s", s.truth_time_s},
          {"truth_error_estimate", s.truth_error_estimate},
          {"order", to_json(s.order)},
          {"points", points}};
}

void from_json(const json& j, SliceStudyScene& s) {
  s.scene = j.at("scene");
  s.rule = j.at("rule");
  s.tolerance = j.at("overlap_tolerance");
  s.truth_time_s = j.at("truth_time_s");
  s.truth_error_estimate = j.at("truth_error_estimate");
  s.points = j.at("points").get<std::vector<SliceStudyPoint>>();
  s.order = j.at("order").get<Errors>();
}

}  // namespace fibrecheck
