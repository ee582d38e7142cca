// Results round-trip through JSON and are written atomically.
#include "result.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "input_error.h"
#include "iterative_solver.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

TEST(Result, RoundTripKeepsEveryField) {
  Scene s = testing::crossing(0.4, 0.5, 1e-3);
  s.output.samples = 7;
  const Result r = solve_iteratively(s, SolverOptions::from_scene(s));
  const std::string path = ::testing::TempDir() + "round_trip.result.json";
  write_result(path, r);
  const Result back = read_result(path);
  EXPECT_EQ(result_to_json(back), result_to_json(r));
  EXPECT_EQ(back.status, Status::converged);
  EXPECT_EQ(back.fibres.size(), 2u);
  EXPECT_EQ(back.fibres[0].displacement.size(), 7u);
  EXPECT_EQ(back.contacts.at(0).fibres[0], "A");
  EXPECT_EQ(back.contacts.at(0).points.at(0).force, r.contacts.at(0).points.at(0).force);
  // The schema's names (DESIGN §5) are the ones written.
  const nlohmann::json j = result_to_json(r);
  for (const char* key :
       {"status", "criterion", "iterations", "wall_time_s", "strain_energy", "strain_energy_exact",
        "max_overlap", "stages", "fibres", "contacts", "walls", "history"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j["contacts"][0].contains("total_force"));
  EXPECT_TRUE(j["contacts"][0]["points"][0].contains("position"));
}

// A load path's steps keep their own counts of updates, and the result its exact answers; results
// written before the counts were kept read as 0.
TEST(Result, StepsKeepTheirUpdatesAndOlderStepsReadAsZero) {
  Result r;
  r.scene = "path";
  StepResult step;
  step.compaction = 0.9;
  step.wall_pressure = {{"top", 1e-3}};
  step.iterations = 120;
  step.geometric_updates = 7;
  step.fixed_point_updates = 3;
  step.stick_residual = 2.5e-9;
  step.slip_residual = 1.5e-18;
  r.steps = {step, step};
  r.steps[1].geometric_updates = 11;
  r.exact_answers = 2;
  const std::string path = ::testing::TempDir() + "steps.result.json";
  write_result(path, r);
  const Result back = read_result(path);
  EXPECT_EQ(back.exact_answers, 2);
  ASSERT_EQ(back.steps.size(), 2u);
  EXPECT_EQ(back.steps[0].geometric_updates, 7);
  EXPECT_EQ(back.steps[1].geometric_updates, 11);
  EXPECT_EQ(back.steps[1].fixed_point_updates, 3);
  EXPECT_EQ(back.steps[1].stick_residual, 2.5e-9);
  EXPECT_EQ(back.steps[1].slip_residual, 1.5e-18);
  nlohmann::json older = result_to_json(r);
  for (nlohmann::json& e : older["steps"]) {
    ASSERT_TRUE(e.contains("geometric_updates") && e.contains("fixed_point_updates"));
    e.erase("geometric_updates");
    e.erase("fixed_point_updates");
    e.erase("stick_residual");
    e.erase("slip_residual");
  }
  ASSERT_TRUE(older.contains("exact_answers"));
  older.erase("exact_answers");
  const Result old = result_from_json(older, "older.result.json");
  EXPECT_EQ(old.exact_answers, 0);
  EXPECT_EQ(old.steps.at(1).geometric_updates, 0);
  EXPECT_EQ(old.steps.at(1).fixed_point_updates, 0);
  EXPECT_EQ(old.steps.at(1).stick_residual, 0.0);
  EXPECT_EQ(old.steps.at(1).iterations, 120);
}

TEST(Result, AtomicWriteLeavesNoTemporaryAndReplacesWhole) {
  const std::string folder = ::testing::TempDir() + "atomic/";
  std::filesystem::remove_all(folder);
  Result r;
  r.scene = "x";
  r.status = Status::converged;
  write_result(folder + "r.json", r);
  r.status = Status::diverged;
  write_result(folder + "r.json", r);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "r.json");
  }
  EXPECT_EQ(files, 1);
  EXPECT_EQ(read_result(folder + "r.json").status, Status::diverged);
}

TEST(Result, ReadingSomethingElseIsAnInputError) {
  const std::string path = ::testing::TempDir() + "not_a_result.json";
  std::ofstream(path) << "{\"scene\": 3}";
  EXPECT_THROW(read_result(path), InputError);
}

}  // namespace
}  // namespace fibrecheck
