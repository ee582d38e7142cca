// Reading and validating scenes (DESIGN §4, §8): defaults in one place, every bad input a single
// InputError naming the file, the field and the reason.
#include "scene.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "input_error.h"

namespace fibrecheck {
namespace {

using nlohmann::json;

json minimal() {
  return json::parse(R"({"fibres": [
      {"id": "A", "start": [0,0,0], "end": [1,0,0], "radius": 0.01, "youngs_modulus": 80000},
      {"id": "B", "start": [0.5,-0.5,0.019], "end": [0.5,0.5,0.019], "radius": 0.01, "youngs_modulus": 80000}]})");
}

/// Expects scene_from_json to reject `doc` with an InputError naming `field` and containing `why`.
void expect_rejected(const json& doc, const std::string& field, const std::string& why) {
  try {
    scene_from_json(doc, "bad.json");
    ADD_FAILURE() << "accepted; expected an error on " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(e.reason().find(why), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.json: " + field), std::string::npos);
  }
}

TEST(Scene, EveryFieldButFibresHasADefault) {
  const Scene s = scene_from_json(minimal(), "scenes/minimal.json");
  const Scene d;
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.fibres.size(), 2u);
  EXPECT_TRUE(s.loads.empty());
  EXPECT_TRUE(s.walls.empty());
  EXPECT_EQ(s.contact.slices, d.contact.slices);
  EXPECT_EQ(s.contact.axis, d.contact.axis);
  EXPECT_EQ(s.solver.rule, UpdateRule::accelerated);
  EXPECT_FALSE(s.solver.c.has_value());
  EXPECT_DOUBLE_EQ(s.overlap_tolerance(), 1e-5 * 0.01);  // 1e-5 of the smallest radius
  EXPECT_EQ(s.solver.max_iterations, d.solver.max_iterations);
  EXPECT_EQ(s.output.samples, d.output.samples);
}

TEST(Scene, HelpListsEveryFieldWithItsDefault) {
  const std::string help = scene_format_help();
  const json full = scene_to_json(Scene{});
  for (auto it = full.begin(); it != full.end(); ++it) {
    EXPECT_NE(help.find(it.key()), std::string::npos) << it.key();
    if (it->is_object()) {
      for (auto jt = it->begin(); jt != it->end(); ++jt)
        EXPECT_NE(help.find(jt.key()), std::string::npos) << it.key() << "." << jt.key();
    }
  }
  EXPECT_NE(help.find("default: 50"), std::string::npos);
  EXPECT_NE(help.find("default: 100000"), std::string::npos);
}

TEST(Scene, WrittenSceneReadsBackTheSame) {
  json doc = minimal();
  doc["loads"] =
      json::parse(R"([{"fibre": "A", "kind": "distributed", "force_per_length": [0,0,-1e-4]},
                                 {"fibre": "B", "position": 0.25, "force": [0,0,1e-5]}])");
  doc["walls"] = json::parse(R"([{"id": "floor", "point": [0,0,-1], "normal": [0,0,2]}])");
  doc["solver"] = json::parse(R"({"rule": "seed", "c": 0.01, "overlap_tolerance": 1e-9})");
  const Scene s = scene_from_json(doc, "x.json");
  EXPECT_NEAR(s.walls[0].normal.norm(), 1.0, 1e-15);
  const Scene back = scene_from_json(scene_to_json(s), "x.json");
  EXPECT_EQ(scene_to_json(back), scene_to_json(s));
  EXPECT_EQ(back.loads[1].position, 0.25);
  EXPECT_EQ(*back.solver.c, 0.01);
}

TEST(SceneBadInput, UnknownKeysAreErrorsAtEveryLevel) {
  json top = minimal();
  top["fibers"] = json::array();
  expect_rejected(top, "fibers", "unknown key");
  json fibre = minimal();
  fibre["fibres"][1]["radious"] = 0.01;
  expect_rejected(fibre, "fibres[1].radious", "unknown key");
  json solver = minimal();
  solver["solver"] = {{"overlap_tolerence", 1e-7}};
  expect_rejected(solver, "solver.overlap_tolerence", "unknown key");
}

TEST(SceneBadInput, WrongTypes) {
  json doc = minimal();
  doc["fibres"][0]["radius"] = "0.01";
  expect_rejected(doc, "fibres[0].radius", "must be a number");
  doc = minimal();
  doc["fibres"][0]["start"] = {0, 0};
  expect_rejected(doc, "fibres[0].start", "three numbers");
  doc = minimal();
  doc["fibres"] = {{"id", "A"}};
  expect_rejected(doc, "fibres", "must be an array");
  doc = minimal();
  doc["contact"] = {{"slices", 2.5}};
  expect_rejected(doc, "contact.slices", "whole number");
  expect_rejected(json::array(), "", "JSON object");
}

TEST(SceneBadInput, NonPositiveRadiusOrModulus) {
  for (double bad : {0.0, -0.01}) {
    json doc = minimal();
    doc["fibres"][1]["radius"] = bad;
    expect_rejected(doc, "fibres[1].radius", "must be positive");
    doc = minimal();
    doc["fibres"][0]["youngs_modulus"] = bad;
    expect_rejected(doc, "fibres[0].youngs_modulus", "must be positive");
  }
}

TEST(SceneBadInput, ZeroLengthAndDuplicateFibres) {
  json doc = minimal();
  doc["fibres"][0]["end"] = {0, 0, 0};
  expect_rejected(doc, "fibres[0].end", "zero-length");
  doc = minimal();
  doc["fibres"][1]["id"] = "A";
  expect_rejected(doc, "fibres[1].id", "duplicate");
  doc = minimal();
  doc["fibres"] = json::array();
  expect_rejected(doc, "fibres", "at least one");
}

TEST(SceneBadInput, LoadsOnMissingFibresOrOutsideTheFibre) {
  json doc = minimal();
  doc["loads"] = json::parse(R"([{"fibre": "C", "force": [0,0,1]}])");
  expect_rejected(doc, "loads[0].fibre", "no fibre with id");
  for (double bad : {-0.1, 1.5}) {
    doc["loads"] = json::parse(R"([{"fibre": "A", "force": [0,0,1]}])");
    doc["loads"][0]["position"] = bad;
    expect_rejected(doc, "loads[0].position", "[0, 1]");
  }
  doc["loads"] = json::parse(R"([{"fibre": "A", "kind": "twisting", "force": [0,0,1]}])");
  expect_rejected(doc, "loads[0].kind", "point");
  doc["loads"] = json::parse(R"([{"fibre": "A", "kind": "distributed", "force": [0,0,1]}])");
  expect_rejected(doc, "loads[0].force_per_length", "required");
}

TEST(SceneBadInput, SolverAndContactSettings) {
  json doc = minimal();
  doc["contact"] = {{"slices", 0}};
  expect_rejected(doc, "contact.slices", "from 1");
  doc["contact"] = {{"axis", {0, 0, 0}}};
  expect_rejected(doc, "contact.axis", "zero vector");
  doc["contact"] = {{"friction", -0.2}};
  expect_rejected(doc, "contact.friction", "negative");
  doc = minimal();
  doc["solver"] = {{"overlap_tolerance", -1e-7}};
  expect_rejected(doc, "solver.overlap_tolerance", "positive");
  doc["solver"] = {{"energy_tolerance", -1.0}};
  expect_rejected(doc, "solver.energy_tolerance", "negative");
  doc["solver"] = {{"rule", "fast"}};
  expect_rejected(doc, "solver.rule", "\"seed\"");
  doc["solver"] = {{"rule", "seed"}};
  expect_rejected(doc, "solver.c", "required");
  doc["solver"] = {{"max_iterations", 0}};
  expect_rejected(doc, "solver.max_iterations", "at least 1");
  doc = minimal();
  doc["walls"] = json::parse(R"([{"id": "A", "point": [0,0,0], "normal": [0,0,1]}])");
  expect_rejected(doc, "walls[0].id", "duplicate");
  doc["walls"] = json::parse(R"([{"id": "w", "point": [0,0,0], "normal": [0,0,0]}])");
  expect_rejected(doc, "walls[0].normal", "zero vector");
}

class SceneFile : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path) << text;
    return path;
  }
  /// The field must start with `field` (the parser names the innermost value it was reading).
  void expect_file_rejected(const std::string& path, const std::string& field,
                            const std::string& why) {
    try {
      read_scene(path);
      ADD_FAILURE() << "accepted " << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.field().substr(0, field.size()), field) << e.what();
      EXPECT_NE(e.reason().find(why), std::string::npos) << e.what();
    }
  }
};

TEST_F(SceneFile, MalformedTruncatedMissingAndOverflowing) {
  expect_file_rejected(write("malformed.json", "{\"fibres\": [}"), "fibres", "malformed JSON");
  expect_file_rejected(write("truncated.json", minimal().dump().substr(0, 60)), "fibres[0]",
                       "malformed JSON");
  expect_file_rejected(::testing::TempDir() + "does_not_exist.json", "", "no such file");
  std::string text = minimal().dump();
  text.replace(text.find("0.01"), 4, "1e999");
  expect_file_rejected(write("overflow.json", text), "fibres[0].radius", "overflow");
  expect_file_rejected(write("nan.json", "{\"fibres\": [{\"id\": \"A\", \"radius\": NaN}]}"),
                       "fibres[0].radius", "malformed JSON");
}

TEST_F(SceneFile, CommittedScenesAreValid) {
  for (const char* name :
       {"two_fibres_crossing", "parallel_fibres", "small_tow_19", "compaction_test"}) {
    const Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/" + name + ".json");
    EXPECT_EQ(s.name, name);
  }
}

}  // namespace
}  // namespace fibrecheck
