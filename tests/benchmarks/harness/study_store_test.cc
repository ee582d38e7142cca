// A study's points are kept as they finish: a store opened again holds the points written before,
// a line cut short by an interrupted run is dropped (and computed again), and the CSV writer
// writes its header and rows.
#include "study_store.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fibrecheck {
namespace {

// One folder per test: ctest runs the tests of this file as separate processes, side by side.
std::string folder() {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  return ::testing::TempDir() + "study_store_" + test + "/";
}

TEST(StudyStore, AnInterruptedStudyComputesOnlyTheRest) {
  std::filesystem::remove_all(folder());
  int computed = 0;
  auto run = [&](int points, int stop_after) {
    StudyStore store(folder(), "demo");
    for (int i = 0; i < points && (stop_after < 0 || i < stop_after); ++i) {
      const std::string key = "p" + std::to_string(i);
      if (store.has(key)) continue;
      ++computed;
      store.add(key, {{"value", i * i}});
    }
  };
  run(5, 3);  // interrupted after three points
  EXPECT_EQ(computed, 3);
  // And a half-written line at the end, as a kill during a write would leave.
  std::ofstream(folder() + "demo.points.jsonl", std::ios::app) << "{\"key\": \"p3\", \"val";
  run(5, -1);
  EXPECT_EQ(computed, 5);  // only p3 and p4 were computed again
  StudyStore store(folder(), "demo");
  ASSERT_EQ(store.points().size(), 5u);
  EXPECT_EQ(store.get("p4")["value"], 16);
  EXPECT_EQ(store.get("p2")["value"], 4);
}

TEST(StudyStore, CsvHasTheHeaderAndOneRowAPoint) {
  std::filesystem::remove_all(folder());
  write_csv(folder() + "t.csv", {"scene", "x"}, {{"a", cell(0.5)}, {"b", cell(NAN)}});
  std::stringstream text;
  text << std::ifstream(folder() + "t.csv").rdbuf();
  EXPECT_EQ(text.str(), "scene,x\na,0.5\nb,\n");
}

}  // namespace
}  // namespace fibrecheck
