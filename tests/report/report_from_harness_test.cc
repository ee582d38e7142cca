// The report from the harness's own records: a small real run of every study — a comparison of
// two crossing fibres, a slice study of the parallel fibres, a tolerance and a stability study of
// the crossing (and one scene of the extreme catalogue), a compaction study of a generated 7-fibre
// tow with friction, a friction study of a 7-fibre tow, and a scale study of a 7-fibre tow run as
// processes of the fibrecheck program — read back by the report. The iterative solver stands in for
// the reference, so that this builds without the finite-element stack. A field the harness writes
// under a name the report does not read makes the report refuse the data; the tables carry the
// numbers the studies returned.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "atomic_file.h"
#include "compaction_study.h"
#include "comparison.h"
#include "friction_study.h"
#include "input_error.h"
#include "iterative_solver.h"
#include "report_data.h"
#include "report_writer.h"
#include "scale_study_record.h"
#include "slice_study.h"
#include "slurp.h"
#include "stability_study.h"
#include "tables.h"
#include "tolerance_study.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = FIBRECHECK_SCENES_DIR;

Result iterative(const Scene& scene) {
  return solve_iteratively(scene, SolverOptions::from_scene(scene));
}

/// The stand-in reference: the iterative solver as the scene says.
Result reference(const Scene& scene) {
  Result r = iterative(scene);
  r.solver = "fem";
  return r;
}

Solvers stand_in_solvers() {
  Solvers s;
  s.iterative = iterative;
  s.reference_slices = reference;
  s.reference_continuous = reference;
  s.reference_refined = [](const Scene& scene, int K) {
    Scene refined = scene;
    refined.contact.slices = scene.contact.slices << K;
    return reference(refined);
  };
  return s;
}

/// What the studies returned, for the tables to be checked against.
struct HarnessRun {
  std::vector<SliceStudyScene> slices;
  std::vector<ToleranceStudyScene> tolerance;
  std::vector<CompactionStudyScene> compaction;
  std::vector<FrictionPoint> friction;
  ScaleStudy scale;
};

/// Every study, small, into `folder`.
HarnessRun run_harness(const fs::path& folder) {
  const Solvers solvers = stand_in_solvers();
  const Scene crossing = read_scene(kScenes + "/two_fibres_crossing.json");
  write_comparison((folder / "compare" / crossing.name).string(), crossing,
                   compare_scene(crossing, solvers));
  HarnessRun run;
  SliceStudyOptions slices;
  slices.slices = {2, 4, 8};
  slices.quiet = true;
  run.slices = run_slice_study({read_scene(kScenes + "/parallel_fibres.json")}, slices, solvers,
                               (folder / "study" / "slices").string());
  ToleranceStudyOptions tolerance;
  tolerance.tolerances = {1e-3, 1e-5};
  tolerance.slice_factors = {1};
  tolerance.refinements = {0};
  tolerance.quiet = true;
  run.tolerance = run_tolerance_study({crossing}, tolerance, solvers,
                                      (folder / "study" / "tolerance").string());
  StabilityStudyOptions stability;
  stability.fractions = {0.5, 1.5};
  stability.stiffness_ratios = {1, 1e3};
  stability.max_iterations = 2000;
  stability.quiet = true;
  run_stability_study({crossing, read_scene(kScenes + "/extreme/stiffness_ratio_1e9.json")},
                      stability, solvers, (folder / "study" / "stability").string());
  TowOptions tow;
  tow.fibres = 7, tow.slices = 10, tow.seed = 2, tow.volume_fraction = 0.35;
  tow.steps = 3, tow.compaction = 0.75, tow.friction = 0.2;
  CompactionStudyOptions compaction;
  compaction.sections = {1};
  compaction.quiet = true;
  run.compaction = run_compaction_study({generate_tow(tow)}, compaction, solvers,
                                        (folder / "study" / "compaction").string());
  FrictionStudyOptions friction;
  friction.fibres = {7}, friction.mu = {0.2}, friction.compactions = {0.9};
  friction.slices = 10, friction.max_iterations = 20000, friction.quiet = true;
  run.friction = run_friction_study(friction, iterative, (folder / "study" / "friction").string());
  const fs::path scale = folder / "study" / "scale";
  const std::string command = std::string("'") + FIBRECHECK_BINARY +
                              "' study scale --fibres 7 --slices 10 --rules accelerated "
                              "--reference-fibres 0 --peer-fibres 0 --processes 1 -q --out '" +
                              scale.string() + "'";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(scale / "scale_study.json");
  run.scale = nlohmann::json::parse(in).get<ScaleStudy>();
  return run;
}

// The progress lines count every run the tolerance study makes (rules at each tolerance, the
// force-criterion runs, the reference, the ground truth): the last is "point N of N", and no
// "to go" is estimated past the total.
TEST(ToleranceStudyProgress, CountsEveryRunItMakes) {
  const fs::path folder =
      fs::path(::testing::TempDir()) / ("tolerance_progress_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  ToleranceStudyOptions tolerance;
  tolerance.tolerances = {1e-3};
  tolerance.slice_factors = {1};
  tolerance.refinements = {0};
  tolerance.quiet = false;
  ::testing::internal::CaptureStderr();
  run_tolerance_study({read_scene(kScenes + "/two_fibres_crossing.json")}, tolerance,
                      stand_in_solvers(), folder.string());
  const std::string lines = ::testing::internal::GetCapturedStderr();
  fs::remove_all(folder);
  const std::size_t expected = 1 + (tolerance.seed_fractions.size() + 2) +
                               tolerance.force_tolerances.size() + tolerance.refinements.size();
  std::istringstream in(lines);
  std::size_t last = 0;
  for (std::string line; std::getline(in, line);) {
    std::size_t point = 0, total = 0;
    if (std::sscanf(line.c_str(), "  tolerance study: point %zu of %zu", &point, &total) != 2)
      continue;
    EXPECT_EQ(total, expected) << line;
    EXPECT_LE(point, total) << line;
    last = point;
  }
  EXPECT_EQ(last, expected) << lines;
}

class ReportFromHarness : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // Its own folder: ctest runs each test of the suite as a process of its own, side by side.
    folder_ =
        new fs::path(::testing::TempDir() + "report_from_harness_" + std::to_string(::getpid()));
    fs::remove_all(*folder_);
    run_ = new HarnessRun(run_harness(*folder_ / "data"));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete run_;
    delete folder_;
  }
  static fs::path* folder_;
  static HarnessRun* run_;
};

fs::path* ReportFromHarness::folder_ = nullptr;
HarnessRun* ReportFromHarness::run_ = nullptr;

TEST_F(ReportFromHarness, EveryStudyIsReadAndReported) {
  const ReportData data = read_report_data({(*folder_ / "data").string()});
  EXPECT_EQ(data.comparisons.size(), 1u);
  EXPECT_EQ(data.slice_studies.size(), 1u);
  EXPECT_EQ(data.tolerance_studies.size(), 1u);
  EXPECT_EQ(data.stability_studies.size(), 2u);
  EXPECT_EQ(data.compaction_studies.size(), 1u);
  EXPECT_EQ(data.friction_study.size(), 2u);
  ASSERT_EQ(data.scale_studies.size(), 1u);
  const fs::path out = *folder_ / "report";
  const ReportSummary summary = write_report(data, out.string());
  // Comparison, slices, speed-up, tolerance outcomes, effectivity, step sweep, stiffness,
  // catalogue, compaction fits, agreement, points, cost and Coulomb's law per step, the friction
  // rules, scale.
  EXPECT_EQ(summary.tables, 15);
  EXPECT_TRUE(summary.missing.empty()) << summary.missing.front();
  const std::string md = slurp(out / "report.md");
  for (const char* section :
       {"## Accuracy on each scene",
        "## Accuracy against the number of "
        "slices",
        "## Accuracy against run time", "## Error estimates", "## Stability of the force update",
        "## Compaction", "## The seed's friction rule", "## Scale"})
    EXPECT_NE(md.find(section), std::string::npos) << section;
  // The figures of the compaction study, its kept state at step 3 included (at step 1 no contact
  // force crosses the mid-length section: a picture of circles only is left out), and of the
  // scale study.
  const std::string tow = file_name_slug(run_->compaction.at(0).scene);
  EXPECT_FALSE(fs::exists(out / "figures" / ("compaction_section_" + tow + "_step1.png")));
  for (const std::string& figure : std::vector<std::string>{
           "compaction_" + tow, "compaction_energy_" + tow, "compaction_section_" + tow + "_step3",
           "scale_time", "slices_parallel_fibres", "error_vs_time_two_fibres_crossing",
           "stability_two_fibres_crossing", "friction_seed_rule_7"})
    EXPECT_TRUE(fs::exists(out / "figures" / (figure + ".png"))) << figure;
}

TEST_F(ReportFromHarness, TheTablesHoldWhatTheStudiesReturned) {
  const fs::path out = *folder_ / "report_tables";
  write_report(read_report_data({(*folder_ / "data").string()}), out.string());
  const std::string md = slurp(out / "report.md");
  const SliceStudyPoint& p = run_->slices.at(0).points.at(1);
  EXPECT_NE(
      md.find("| parallel_fibres | 4 | " + sci(p.errors.deflection) + " | " + sci(p.errors.force) +
              " | " + sci(p.errors.energy) + " | " + count(p.iterations) + " |"),
      std::string::npos);
  const SpeedUp& u = run_->tolerance.at(0).speedups.at(0);
  EXPECT_NE(md.find("| two_fibres_crossing | " + sci(u.error_level) + " | " +
                    (u.iterative_method.empty() ? "–" : u.iterative_method) + " |"),
            std::string::npos);
  for (const CompactionRun& r : run_->compaction.at(0).runs) {
    int steps = 0;
    for (const CompactionPoint& q : r.points) steps += q.status == "converged" ? 1 : 0;
    EXPECT_NE(md.find(" | " + r.status + " | " + std::to_string(steps) + "/" +
                      std::to_string(r.points.size()) + " | "),
              std::string::npos)
        << r.label();
  }
  // The points the curves are drawn from: the last step's pressure of every run, in one row.
  const CompactionStudyScene& tow = run_->compaction.at(0);
  const CompactionPoint& first = tow.runs.front().points.back();
  std::string row = "| " + std::to_string(first.step) + " | " + fixed3(first.fibre_volume_fraction);
  for (const CompactionRun& r : tow.runs) {
    ASSERT_EQ(r.points.size(), tow.runs.front().points.size()) << r.label();
    const CompactionPoint& q = r.points.back();
    row += " | " + (q.status == "converged" ? sci(q.pressure) : q.status);
  }
  EXPECT_NE(md.find(row + " |"), std::string::npos) << row;
  // Coulomb's law on the last step's answer, per run with Coulomb friction, in one row.
  row = "| " + std::to_string(first.step) + " | " + fixed3(first.fibre_volume_fraction);
  for (const CompactionRun& r : tow.runs) {
    if (r.friction_model != "coulomb") continue;
    const CompactionPoint& q = r.points.back();
    row += " | " + std::string(q.status == "converged" ? "" : q.status + ": ") +
           sci(q.stick_residual) + " / " + sci(q.slip_residual);
  }
  EXPECT_NE(md.find(row + " |"), std::string::npos) << row;
  EXPECT_NE(md.find("| iterative, μ = 0.2 (Coulomb) | "), std::string::npos);
  EXPECT_NE(md.find("| iterative, μ = 0.2 (seed rule) | "), std::string::npos);
  // The friction study's row: both runs of the tow side by side.
  ASSERT_EQ(run_->friction.size(), 2u);
  const FrictionPoint& seed = run_->friction.at(0);
  const FrictionPoint& coulomb = run_->friction.at(1);
  auto outcome = [](const FrictionPoint& p) {
    return p.status == "converged" || p.status == p.criterion ? p.status
                                                              : p.status + " (" + p.criterion + ")";
  };
  EXPECT_NE(
      md.find("| 7 | 0.900 | " + fixed3(seed.fibre_volume_fraction) + " | 0.200 | " +
              outcome(seed) + " | " + std::to_string(seed.iterations) + " | " + outcome(coulomb) +
              " | " + std::to_string(coulomb.iterations) + " | " + sci(seed.stick_residual) + " |"),
      std::string::npos);
  ASSERT_EQ(run_->scale.points.size(), 1u);
  const ScalePoint& s = run_->scale.points.at(0);
  EXPECT_NE(md.find("| 7 | iterative, " + s.method + " | " + s.status + " | " +
                    std::to_string(s.candidates) + " | " + std::to_string(s.active) + " | " +
                    std::to_string(s.iterations) + " |"),
            std::string::npos);
}

TEST_F(ReportFromHarness, ARecordWithoutAFieldTheHarnessWritesIsRefused) {
  // The compaction study's points without their pressure: not the harness's any more.
  const fs::path copy = *folder_ / "renamed";
  fs::remove_all(copy);
  fs::create_directories(copy);
  const fs::path file = *folder_ / "data" / "study" / "compaction" / "compaction_study.json";
  nlohmann::json j = nlohmann::json::parse(slurp(file));
  for (nlohmann::json& run : j[0]["runs"])
    for (nlohmann::json& point : run["points"]) {
      point["pressure"] = point["pressure_MPa"];
      point.erase("pressure_MPa");
    }
  std::ofstream(copy / "compaction_study.json") << j.dump(1);
  try {
    read_report_data({copy.string()});
    ADD_FAILURE() << "a record without pressure_MPa was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pressure_MPa"), std::string::npos) << e.what();
  }
}

// A kept state is drawn whatever its step's end: where the step did not converge, the caption of
// its cross-section says so and names the status (a frictional run can stop at its cap with the
// state it stopped in kept).
TEST_F(ReportFromHarness, ACrossSectionOfAStepThatDidNotConvergeSaysSo) {
  const fs::path copy = *folder_ / "stopped";
  fs::remove_all(copy);
  fs::copy(*folder_ / "data", copy, fs::copy_options::recursive);
  const CompactionStudyScene& tow = run_->compaction.at(0);
  std::string title;
  for (const CompactionRun& r : tow.runs)
    for (const auto& [step, file] : r.sections)
      if (step == 3 && r.solver == "iterative" && r.friction_model == "coulomb") {
        const fs::path kept = copy / "study" / "compaction" / file;
        nlohmann::json j = nlohmann::json::parse(slurp(kept));
        ASSERT_EQ(j["status"], "converged");
        j["status"] = "max_iterations";
        std::ofstream(kept) << j.dump(1);
        title = "A cross-section of " + tow.scene + " at step 3";
      }
  ASSERT_FALSE(title.empty());
  const fs::path out = *folder_ / "report_stopped";
  write_report(read_report_data({copy.string()}), out.string());
  const std::string md = slurp(out / "report.md");
  const std::size_t at = md.find(title);
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(md.substr(at, 300).find("the step did not converge (max_iterations)"),
            std::string::npos)
      << md.substr(at, 300);
  const fs::path converged = *folder_ / "report_converged";
  write_report(read_report_data({(*folder_ / "data").string()}), converged.string());
  const std::string as_run = slurp(converged / "report.md");
  ASSERT_NE(as_run.find(title), std::string::npos);
  EXPECT_EQ(as_run.find("; the step did not converge ("), std::string::npos);
}

}  // namespace
}  // namespace fibrecheck
