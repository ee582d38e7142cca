// The expected outcome of a catalogue scene: read strictly, and a result judged by it.

#include "expected_outcome.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "input_error.h"

namespace fibrecheck {
namespace {

using nlohmann::json;

const json kExpected = json::parse(R"json({
  "closed_form": "P = d/(C_A + C_B)",
  "status": {"iterative": "converged", "reference": "converged"},
  "forces": [{"fibres": ["A", "B"], "total_force": 2.0, "relative_tolerance": 1e-3}],
  "deflections": [{"fibre": "A", "position": 0.5, "displacement": [0, 0, -4],
                   "relative_tolerance": 1e-3}]
})json");

Result result(double force, double deflection) {
  Result r;
  r.status = Status::converged;
  ContactResult c;
  c.fibres = {"B", "A"};  // either order
  c.total_force = force;
  r.contacts.push_back(c);
  FibreResult f;
  f.id = "A";
  f.displacement = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, deflection),
                    Eigen::Vector3d::Zero()};
  r.fibres.push_back(f);
  return r;
}

TEST(ExpectedOutcome, JudgesForcesAndDeflectionsByTheirTolerances) {
  const ExpectedOutcome e = read_expected_outcome(kExpected, "scene.json");
  const OutcomeCheck good = check_outcome(e, result(2.001, -4.002), "iterative");
  EXPECT_TRUE(good.passed());
  EXPECT_NEAR(good.error, 5e-4, 1e-12);  // worst of 0.001/2 and 0.002/4
  const OutcomeCheck bad = check_outcome(e, result(2.01, -4.0), "iterative");
  ASSERT_EQ(bad.failures.size(), 1u);
  EXPECT_NE(bad.failures[0].find("force between A and B"), std::string::npos);
  EXPECT_NEAR(bad.error, 5e-3, 1e-12);
}

TEST(ExpectedOutcome, AnotherStatusFailsAndItsNumbersAreNotJudged) {
  ExpectedOutcome e = read_expected_outcome(kExpected, "scene.json");
  Result r = result(0.0, 0.0);
  r.status = Status::diverged;
  const OutcomeCheck check = check_outcome(e, r, "reference");
  ASSERT_EQ(check.failures.size(), 1u);
  EXPECT_NE(check.failures[0].find("status diverged, expected converged"), std::string::npos);
  e.status["reference"] = "diverged";
  EXPECT_TRUE(check_outcome(e, r, "reference").passed());
  EXPECT_EQ(expected_status(e, "iterative"), "converged");
}

TEST(ExpectedOutcome, ReadingRejectsWhatItCannotJudge) {
  for (const char* text :
       {R"({"status": {"iterative": "fine"}})", R"({"status": {"fem": "converged"}})",
        R"({"forces": [{"fibres": ["A"], "total_force": 1}]})",
        R"({"forces": [{"fibres": ["A", "B"], "total_force": -1}]})",
        R"({"deflections": [{"fibre": "A", "position": 2, "displacement": [0, 0, 1]}]})",
        R"({"comment": "unknown keys are errors"})"})
    EXPECT_THROW(read_expected_outcome(json::parse(text), "scene.json"), InputError) << text;
  // A scene beyond a solver's reach is a status, not bad input.
  EXPECT_THROW(read_expected_outcome(json::parse(R"({"status": {"reference": "refused"}})"),
                                     "scene.json"),
               InputError);
  const ExpectedOutcome e = read_expected_outcome(
      json::parse(R"({"status": {"reference": "beyond_reach"}})"), "scene.json");
  EXPECT_EQ(expected_status(e, "reference"), "beyond_reach");
  // What is written reads back the same.
  const ExpectedOutcome full = read_expected_outcome(kExpected, "scene.json");
  EXPECT_EQ(to_json(full), kExpected);
}

}  // namespace
}  // namespace fibrecheck
