#include "comparison_record.h"

#include <cmath>

namespace fibrecheck {

using nlohmann::json;

json to_json(const RunSummary& r) {
  return {{"solver", r.solver},
          {"rule", r.rule},
          {"status", r.status},
          {"criterion", r.criterion},
          {"iterations", r.iterations},
          {"wall_time_s", r.wall_time_s},
          {"c", r.c},
          {"c_stable_limit", r.c_stable_limit}};
}

void from_json(const json& j, RunSummary& r) {
  r.solver = j.at("solver");
  r.rule = j.at("rule");
  r.status = j.at("status");
  r.criterion = j.at("criterion");
  r.iterations = j.at("iterations");
  r.wall_time_s = j.at("wall_time_s");
  r.c = j.at("c");
  r.c_stable_limit = j.at("c_stable_limit");
}

json to_json(const ComparisonRecord& r) {
  json j;
  j["scene"] = r.scene;
  j["comparable"] = r.comparable;
  if (!r.comparable) j["not_comparable"] = r.reason;
  j["runs"] = json::object();
  for (const auto& [label, run] : r.runs) j["runs"][label] = to_json(run);
  j["rule"] = r.rule;
  j["c"] = r.c;
  j["ground_truth"] = r.ground_truth;
  j["ground_truth_error_estimate"] = r.truth_error_estimate;
  j["geometry"] = r.geometry_model;
  if (r.comparable) {
    j.update(to_json(r.total));
    j["iteration_error"] = to_json(r.iteration);
    j["slicing_error"] = to_json(r.slicing);
    j["agreement_error"] = to_json(r.agreement);
    j["geometry_error"] = to_json(r.geometry);
    j["error_estimate"] = to_json(r.estimate);
    j["effectivity"] = to_json(r.effectivity);
    j["pairs"] = json::array();
    for (const PairError& p : r.pairs) {
      json row = to_json(p);
      row["force_user"] = row["force_run"];
      row.erase("force_run");
      j["pairs"].push_back(row);
    }
  }
  j["files"] = json::object();
  for (const auto& [label, file] : r.files) j["files"][label] = file;
  return j;
}

void from_json(const json& j, ComparisonRecord& r) {
  r.scene = j.at("scene");
  r.comparable = j.at("comparable");
  if (!r.comparable) r.reason = j.at("not_comparable");
  r.runs = j.at("runs").get<std::map<std::string, RunSummary>>();
  r.rule = j.at("rule");
  r.c = j.at("c");
  r.ground_truth = j.at("ground_truth");
  r.truth_error_estimate = j.at("ground_truth_error_estimate");
  r.geometry_model = j.value("geometry", std::string("linearised"));
  if (r.comparable) {
    r.total = j.get<Errors>();
    r.iteration = j.at("iteration_error").get<Errors>();
    r.slicing = j.at("slicing_error").get<Errors>();
    r.agreement = j.at("agreement_error").get<Errors>();
    r.geometry =
        j.contains("geometry_error") ? j.at("geometry_error").get<Errors>() : Errors{NAN, NAN, NAN};
    const Errors none{NAN, NAN, NAN};
    r.estimate = j.contains("error_estimate") ? j.at("error_estimate").get<Errors>() : none;
    r.effectivity = j.contains("effectivity") ? j.at("effectivity").get<Errors>() : none;
    r.pairs.clear();
    for (json row : j.at("pairs")) {
      row["force_run"] = row.at("force_user");
      r.pairs.push_back(row.get<PairError>());
    }
  }
  r.files = j.at("files").get<std::map<std::string, std::string>>();
}

}  // namespace fibrecheck
