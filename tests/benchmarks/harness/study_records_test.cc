// The records the harness writes and the report reads: each study's JSON keeps the field names
// outside tools read (the lists below are those names), a number that is not one (NaN) is written
// as null and read back as NaN, and a record read back from its JSON is the record written.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "compaction_study_record.h"
#include "comparison_record.h"
#include "json_number.h"
#include "scale_study_record.h"
#include "slice_study_record.h"
#include "stability_study_record.h"
#include "tolerance_study_record.h"

namespace fibrecheck {
namespace {

std::set<std::string> keys(const nlohmann::json& j) {
  std::set<std::string> out;
  for (auto it = j.begin(); it != j.end(); ++it) out.insert(it.key());
  return out;
}

using Keys = std::set<std::string>;

TEST(StudyRecords, NaNIsWrittenAsNullAndReadBackAsNaN) {
  EXPECT_TRUE(number_or_null(NAN).is_null());
  EXPECT_TRUE(number_or_null(INFINITY).is_null());
  EXPECT_EQ(number_or_null(0.25), nlohmann::json(0.25));
  EXPECT_TRUE(std::isnan(number_from(nlohmann::json(nullptr))));
  EXPECT_EQ(number_from(nlohmann::json(3)), 3.0);
  EXPECT_THROW(number_at(nlohmann::json::object(), "missing"), nlohmann::json::out_of_range);
}

TEST(StudyRecords, TheSliceStudyKeepsItsFieldNames) {
  SliceStudyScene s;
  s.scene = "parallel_fibres";
  s.rule = "accelerated";
  s.tolerance = 1e-12;
  s.points.push_back({8, 0.003, 865, "converged", {6.5e-5, 2.7e-2, 1.4e-5}});
  s.order = {3.6, NAN, 3.4};
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(keys(j), (Keys{"scene", "rule", "overlap_tolerance", "truth_time_s",
                           "truth_error_estimate", "order", "points"}));
  EXPECT_EQ(keys(j["points"][0]), (Keys{"slices", "iterative_time_s", "iterations", "status",
                                        "deflection_error", "force_error", "energy_error"}));
  EXPECT_TRUE(j["order"]["force_error"].is_null());
  const SliceStudyScene back = j.get<SliceStudyScene>();
  EXPECT_EQ(back.points.at(0).iterations, 865);
  EXPECT_EQ(back.points.at(0).errors.force, 2.7e-2);
  EXPECT_TRUE(std::isnan(back.order.force));
  EXPECT_EQ(back.order.energy, 3.4);
}

TEST(StudyRecords, TheToleranceStudyKeepsItsFieldNames) {
  ToleranceStudyScene s;
  s.scene = "small_tow_19";
  s.truth = "reference_continuous";
  s.points.push_back({"auto", 1e-5, 50, 0.1, 5898, "converged", {1e-3, 2e-3, 3e-3}, true});
  SpeedUp u;
  u.error_level = 1e-3;
  u.reference_time_s = 0.76;
  s.speedups.push_back(u);  // no iterative run reached it
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(keys(j), (Keys{"scene", "ground_truth", "truth_error_estimate", "points", "speedups"}));
  EXPECT_EQ(keys(j["points"][0]),
            (Keys{"method", "parameter", "slices", "time_s", "iterations", "status", "pareto",
                  "error_estimate", "effectivity",
                  "deflection_error", "force_error", "energy_error"}));
  EXPECT_EQ(keys(j["speedups"][0]), (Keys{"error_level", "iterative_time_s", "iterative_method",
                                          "reference_time_s", "speedup"}));
  EXPECT_TRUE(j["speedups"][0]["speedup"].is_null());
  const ToleranceStudyScene back = j.get<ToleranceStudyScene>();
  EXPECT_TRUE(back.points.at(0).pareto);
  EXPECT_EQ(back.truth, "reference_continuous");
  EXPECT_TRUE(std::isnan(back.speedups.at(0).iterative_time_s));
}

TEST(StudyRecords, TheStabilityStudyKeepsItsFieldNames) {
  StabilityStudyScene s;
  s.scene = "two_fibres_crossing";
  s.c_crit = 0.03;
  s.steps.push_back({0.5, 0.015, 40, "converged", "contact", 1e-4});
  s.stiffness.push_back({1e3, "auto", 12, "converged", 1e-4, {NAN, NAN, NAN}});
  nlohmann::json j = to_json(s);
  EXPECT_EQ(keys(j), (Keys{"scene", "c_crit", "steps", "stiffness"}));
  EXPECT_EQ(keys(j["steps"][0]),
            (Keys{"c_over_c_crit", "c", "iterations", "status", "criterion", "time_s"}));
  EXPECT_EQ(keys(j["stiffness"][0]),
            (Keys{"stiffness_ratio", "method", "iterations", "status", "time_s", "deflection_error",
                  "force_error", "energy_error"}));
  EXPECT_TRUE(j["stiffness"][0]["force_error"].is_null());
  StabilityStudyScene catalogue;
  catalogue.scene = "coincident_same_supports";
  catalogue.catalogue.push_back({"reference", "", "converged", "unresolvable", 1, 0.03, NAN,
                                 "status converged, expected unresolvable"});
  const nlohmann::json c = to_json(catalogue);
  EXPECT_EQ(keys(c["catalogue"][0]), (Keys{"solver", "rule", "status", "expected_status",
                                           "iterations", "time_s", "error", "failures"}));
  EXPECT_EQ(j.get<StabilityStudyScene>().steps.at(0).fraction, 0.5);
  EXPECT_TRUE(std::isnan(j.get<StabilityStudyScene>().stiffness.at(0).errors.energy));
  EXPECT_EQ(c.get<StabilityStudyScene>().catalogue.at(0).expected_status, "unresolvable");
}

TEST(StudyRecords, TheCompactionStudyKeepsItsFieldNames) {
  CompactionRun r;
  r.solver = "iterative";
  r.rule = "accelerated";
  r.mu = 0.2;
  r.friction_model = "coulomb";
  r.status = "converged";
  r.points.push_back(
      {1, 0.9, 1.0, 0.43, 1e-3, 2e-6, 3.5, 0.01, 120, 7, 3, "converged", 4e-9, 5e-9});
  r.sections.emplace_back(1, "tow/iterative_mu0_2_coulomb.step1.result.json");
  r.van_wyk = fit_power_law({0.42, 0.45}, {1e-3, 2e-3}, 80000, 3.0);
  CompactionStudyScene s;
  s.scene = "tow";
  s.scene_file = "tow/scene.json";
  s.youngs_modulus = 80000;
  s.runs = {r};
  s.agreement.push_back({0.2, "coulomb", "coulomb", 1e-3, NAN, 1});
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(keys(j), (Keys{"scene", "scene_file", "youngs_modulus", "runs", "agreement"}));
  const nlohmann::json& run = j["runs"][0];
  EXPECT_EQ(keys(run),
            (Keys{"solver", "rule", "mu", "friction_model", "geometry", "status", "message",
                  "wall_time_s", "points", "sections", "van_wyk", "toll"}));
  EXPECT_EQ(keys(run["points"][0]),
            (Keys{"step", "compaction", "load_factor", "fibre_volume_fraction", "pressure_MPa",
                  "strain_energy", "contacts_per_fibre", "iterations", "geometric_updates",
                  "fixed_point_updates", "stick_residual", "slip_residual", "wall_time_s",
                  "status"}));
  EXPECT_EQ(keys(run["van_wyk"]), (Keys{"k", "vf0", "r2", "points"}));
  EXPECT_EQ(keys(run["toll"]), (Keys{"k", "vf0", "r2", "points", "n"}));
  EXPECT_EQ(keys(j["agreement"][0]),
            (Keys{"mu", "friction_model", "against", "geometry", "pressure_error", "energy_error",
                  "steps"}));
  const CompactionStudyScene back = j.get<CompactionStudyScene>();
  EXPECT_EQ(back.runs.at(0).label(), "iterative_mu0_2_coulomb");
  EXPECT_EQ(back.runs.at(0).sections, r.sections);
  EXPECT_EQ(back.runs.at(0).points.at(0).stick_residual, 4e-9);
  EXPECT_EQ(back.runs.at(0).points.at(0).slip_residual, 5e-9);
  nlohmann::json older = j;  // a record kept before Coulomb's residuals were
  older["runs"][0]["points"][0].erase("stick_residual");
  older["runs"][0]["points"][0].erase("slip_residual");
  EXPECT_TRUE(std::isnan(older.get<CompactionStudyScene>().runs.at(0).points.at(0).stick_residual));
  EXPECT_EQ(back.runs.at(0).van_wyk.k, r.van_wyk.k);
  EXPECT_EQ(back.runs.at(0).van_wyk.n, 3.0);
  EXPECT_FALSE(back.runs.at(0).toll.valid);
  EXPECT_TRUE(std::isnan(back.agreement.at(0).energy_error));
}

TEST(StudyRecords, TheScaleStudyKeepsItsFieldNames) {
  ScaleStudy s;
  s.slices = 10;
  s.seed = 3;
  s.program_floor_memory_mb = 157.25;
  ScalePoint p;
  p.fibres = 7, p.slices = 10, p.solver = "iterative", p.method = "accelerated";
  p.status = "converged", p.iterations = 40, p.time_s = 0.002;
  s.points = {p};
  s.exponents.push_back({"iterative", "accelerated", 1, 2, 1.2, NAN});
  const nlohmann::json j = to_json(s);
  EXPECT_TRUE(is_scale_study(j));
  EXPECT_EQ(keys(j),
            (Keys{"study", "slices", "seed", "program_floor_memory_mb", "points", "exponents"}));
  EXPECT_EQ(keys(j["points"][0]),
            (Keys{"fibres", "slices", "solver", "method", "processes", "status", "candidates",
                  "active", "iterations", "unknowns", "time_s", "process_time_s",
                  "ms_per_iteration", "peak_memory_mb", "peak_proportional_memory_mb",
                  "agreement"}));
  EXPECT_EQ(keys(j["exponents"][0]),
            (Keys{"solver", "method", "processes", "sizes", "time", "memory"}));
  const ScaleStudy back = j.get<ScaleStudy>();
  EXPECT_EQ(back.points.at(0).ms_per_iteration(), p.ms_per_iteration());
  EXPECT_TRUE(std::isnan(back.exponents.at(0).memory));
  EXPECT_EQ(back.program_floor_memory_mb, 157.25);
  // A study recorded before the floor was measured reads as not measured.
  nlohmann::json older = j;
  older.erase("program_floor_memory_mb");
  EXPECT_EQ(older.get<ScaleStudy>().program_floor_memory_mb, 0.0);
  EXPECT_FALSE(is_scale_study(nlohmann::json::array()));
}

TEST(StudyRecords, TheComparisonKeepsItsFieldNames) {
  ComparisonRecord r;
  r.scene = "two_fibres_crossing";
  r.runs["user"] = {"iterative", "auto", "converged", "contact", 3, 1e-4, 0.015, 0.03};
  r.runs["reference_slices"] = {"fem", "active_set", "converged", "active_set", 1, 0.01, 0, 0};
  r.rule = "auto";
  r.ground_truth = "reference_slices";
  r.total = {2.4e-9, 2.4e-11, 2.4e-11};
  r.geometry = {0.05, 0.16, 0.02};
  PairError pair;
  pair.kind = "point";
  pair.fibres = {"A", "B"};
  pair.force_run = 1.5e-5;
  r.pairs = {pair};
  r.files = {{"user", "user.result.json"}};
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(keys(j), (Keys{"scene", "comparable", "runs", "rule", "c", "ground_truth",
                           "ground_truth_error_estimate", "geometry", "deflection_error",
                           "force_error", "energy_error", "iteration_error", "slicing_error",
                           "agreement_error", "geometry_error", "error_estimate", "effectivity",
                           "pairs", "files"}));
  EXPECT_EQ(keys(j["runs"]["user"]), (Keys{"solver", "rule", "status", "criterion", "iterations",
                                           "wall_time_s", "c", "c_stable_limit"}));
  EXPECT_EQ(keys(j["pairs"][0]), (Keys{"kind", "fibres", "force_user", "force_truth", "error"}));
  const ComparisonRecord back = j.get<ComparisonRecord>();
  EXPECT_EQ(back.pairs.at(0).force_run, 1.5e-5);
  EXPECT_EQ(back.runs.at("user").iterations, 3);
  EXPECT_EQ(back.total.deflection, 2.4e-9);
  EXPECT_EQ(back.geometry.force, 0.16);
  EXPECT_EQ(back.geometry_model, "deformed");
  ComparisonRecord refused = r;
  refused.comparable = false;
  refused.reason = "the reference on slices ended diverged";
  const nlohmann::json k = to_json(refused);
  EXPECT_FALSE(k.contains("deflection_error"));
  EXPECT_EQ(k.get<ComparisonRecord>().reason, refused.reason);
}

}  // namespace
}  // namespace fibrecheck
