// The report from a small committed fixture of harness data (a comparison of two crossing fibres
// and one slice, tolerance and stability study): the files exist, the tables hold the fixture's
// numbers, the figures are non-empty PNG files, the LaTeX tables are well-formed, and without
// gnuplot the tables still come out with a message saying what is missing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "input_error.h"
#include "report_data.h"
#include "report_writer.h"
#include "scale_study_record.h"
#include "slurp.h"

namespace fibrecheck {
namespace {

namespace fs = std::filesystem;

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

const std::string kFixture = FIBRECHECK_REPORT_FIXTURE;

/// The report.md `write_report` makes of `data` in a fresh folder `name`, without gnuplot (the
/// tables alone).
std::string markdown_without_figures(const ReportData& data, const std::string& name) {
  const fs::path out = ::testing::TempDir() + name;
  fs::remove_all(out);
  setenv("FIBRECHECK_GNUPLOT", "/nonexistent/gnuplot", 1);
  write_report(data, out.string());
  unsetenv("FIBRECHECK_GNUPLOT");
  return slurp(out / "report.md");
}

TEST(Report, FromTheFixture) {
  const fs::path out = ::testing::TempDir() + "report_fixture";
  fs::remove_all(out);
  const ReportData data = read_report_data({kFixture});
  EXPECT_EQ(data.comparisons.size(), 1u);
  EXPECT_EQ(data.slice_studies.size(), 1u);
  const ReportSummary summary = write_report(data, out.string());
  EXPECT_EQ(summary.tables, 7);
  EXPECT_TRUE(summary.missing.empty()) << summary.missing.front();
  EXPECT_GE(summary.figures, 5);
  const std::string md = slurp(out / "report.md");
  // The fixture's numbers: the slice study's 8-slice force error 0.02698, the speed-up 22.34 at
  // 1 %, the crossing's force error 2.37e-11.
  EXPECT_NE(md.find("| parallel_fibres | 8 | 6.52e-05 | 2.70e-02 | 1.38e-05 | 865 |"),
            std::string::npos);
  EXPECT_NE(md.find("| small_tow_19 | 1.00e-02 | accelerated | 0.03402 | 0.76 | 22.34 |"),
            std::string::npos);
  EXPECT_NE(md.find("| two_fibres_crossing | auto | 2.36e-09 | 2.37e-11 |"), std::string::npos);
  // The extreme catalogue's stability table: a run as expected, and one that is not, with why.
  EXPECT_NE(md.find("| stiffness_ratio_1e9 | iterative (accelerated) | converged | converged | 2 | "
                    "8.2e-05 | 6.23e-15 | yes |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| coincident_same_supports | reference | unresolvable | converged | 1 | "
                    "0.0306 | – | no: status converged, expected unresolvable |"),
            std::string::npos);
  // The tolerance study's outcomes: each method's runs counted by status, as the data say.
  for (const ToleranceStudyScene& s : data.tolerance_studies)
    for (const std::string method : {"seed 0.9", "auto", "accelerated"}) {
      int runs = 0, converged = 0, diverged = 0;
      for (const TolerancePoint& p : s.points) {
        if (p.method != method) continue;
        ++runs;
        converged += p.status == "converged";
        diverged += p.status == "diverged";
      }
      if (runs == 0) continue;
      EXPECT_NE(md.find("| " + s.scene + " | " + method + " | " + std::to_string(runs) + " | " +
                        std::to_string(converged) + " | " + std::to_string(diverged) + " | " +
                        std::to_string(runs - converged - diverged) + " | "),
                std::string::npos)
          << method;
    }
  // The key findings open the report, before its first section.
  EXPECT_LT(md.find("## Key findings"), md.find("## Accuracy on each scene"));
  EXPECT_EQ(count(md, "**Table "), summary.tables);
  EXPECT_EQ(count(md, "**Figure "), summary.figures);
  // Figures: PNG files with their signature, and SVG beside them.
  int pngs = 0;
  for (const auto& entry : fs::directory_iterator(out / "figures")) {
    if (entry.path().extension() != ".png") continue;
    ++pngs;
    EXPECT_GT(fs::file_size(entry.path()), 1000u) << entry.path();
    EXPECT_EQ(slurp(entry.path()).substr(1, 3), "PNG") << entry.path();
    fs::path svg = entry.path();
    EXPECT_TRUE(fs::exists(svg.replace_extension(".svg"))) << svg;
  }
  EXPECT_EQ(pngs, summary.figures);
  // LaTeX: every table a balanced table/tabular with booktabs rules; the document inputs them.
  int tables = 0;
  for (const auto& entry : fs::directory_iterator(out / "tables")) {
    const std::string tex = slurp(entry.path());
    ++tables;
    EXPECT_EQ(count(tex, "\\begin{table}"), 1) << entry.path();
    EXPECT_EQ(count(tex, "\\end{table}"), 1) << entry.path();
    EXPECT_EQ(count(tex, "\\begin{tabular}"), count(tex, "\\end{tabular}")) << entry.path();
    EXPECT_EQ(count(tex, "\\toprule"), 1);
    EXPECT_EQ(count(tex, "\\bottomrule"), 1);
    EXPECT_EQ(count(tex, "{"), count(tex, "}") - count(tex, "\\}") + count(tex, "\\{"))
        << entry.path();
    EXPECT_EQ(tex.find("_"),
              tex.find("\\_") == std::string::npos ? std::string::npos : tex.find("\\_") + 1)
        << "an unescaped underscore in " << entry.path();
  }
  EXPECT_EQ(tables, summary.tables);
  const std::string document = slurp(out / "report.tex");
  EXPECT_EQ(count(document, "\\input{tables/"), summary.tables);
  EXPECT_EQ(count(document, "\\includegraphics"), summary.figures);
  // The data.
  EXPECT_EQ(slurp(out / "data" / "slice_study.csv")
                .find("scene,slices,iterative_time_s,deflection_error,force_error,energy_error\n"),
            0u);
  EXPECT_EQ(slurp(out / "data" / "speedup.csv")
                .find("scene,error_level,iterative_time_s,reference_time_s,speedup\n"),
            0u);
}

TEST(Report, WithoutGnuplotTheTablesStillComeOut) {
  const fs::path out = ::testing::TempDir() + "report_no_gnuplot";
  fs::remove_all(out);
  setenv("FIBRECHECK_GNUPLOT", "/nonexistent/gnuplot", 1);
  const ReportSummary summary = write_report(read_report_data({kFixture}), out.string());
  unsetenv("FIBRECHECK_GNUPLOT");
  EXPECT_EQ(summary.tables, 7);
  EXPECT_EQ(summary.figures, 0);
  ASSERT_FALSE(summary.missing.empty());
  EXPECT_NE(summary.missing.front().find("gnuplot"), std::string::npos) << summary.missing.front();
  EXPECT_NE(slurp(out / "report.md").find("Figures not drawn"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "tables" / "comparison.tex"));
}

// The scale section's ratio of the reference's memory on two processes over one, three ways:
// resident 275 / 400 = 0.69, proportional 200 / 380 = 0.53, and resident above the program's own
// floor of 150 MB, (275 − 150) / (400 − 150) = 0.50.
TEST(Report, TheScaleSectionSaysWhatTwoProcessesHoldAboveTheProgramsFloor) {
  ScaleStudy study;
  study.slices = 100, study.seed = 3, study.program_floor_memory_mb = 150.0;
  for (const int processes : {1, 2}) {
    ScalePoint p;
    p.fibres = 300, p.slices = 100, p.solver = "fem", p.method = "active_set";
    p.processes = processes, p.status = "converged", p.iterations = 2, p.time_s = 10.0;
    p.peak_memory_mb = processes == 1 ? 400.0 : 275.0;
    p.peak_proportional_memory_mb = processes == 1 ? 380.0 : 200.0;
    study.points.push_back(p);
  }
  ReportData data;
  data.scale_studies = {study};
  const std::string md = markdown_without_figures(data, "report_scale_floor");
  EXPECT_NE(md.find("resident / proportional / resident above the 150 MB the program holds when "
                    "it only starts and prints its help: 300 fibres, 2 processes: 0.69 / 0.53 / "
                    "0.50."),
            std::string::npos)
      << md;
}

// The compaction section's cost table gives each step's updates of the normals and of the Tresca
// radii beside its iterations, and only where the record counted them.
TEST(Report, TheCompactionCostTableCountsTheUpdatesOfEachStep) {
  CompactionRun run;
  run.solver = "iterative", run.rule = "accelerated", run.mu = 0.2;
  run.friction_model = "coulomb", run.status = "converged";
  for (int step : {1, 2}) {
    CompactionPoint p;
    p.step = step, p.compaction = 1.0 - 0.1 * step, p.fibre_volume_fraction = 0.4 + 0.1 * step;
    p.pressure = 1e-3 * step, p.iterations = 1000 * step, p.time_s = 2.5, p.status = "converged";
    if (step == 2) p.geometric_updates = 7, p.fixed_point_updates = 3;
    run.points.push_back(p);
  }
  StoredCompactionStudy stored;
  stored.study.scene = "tow", stored.study.youngs_modulus = 80000, stored.study.runs = {run};
  ReportData data;
  data.compaction_studies = {stored};
  const std::string md = markdown_without_figures(data, "report_compaction_cost");
  EXPECT_NE(md.find("| 1 | 0.500 | 1000 (2.5 s) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 2 | 0.600 | 2000 (2.5 s) / 7, 3 |"), std::string::npos) << md;
}

// The compaction section gives Coulomb's law on each step's answer for the runs with Coulomb
// friction only, on the steps where contacts carry force, with the status of a step that did not
// converge before what its state left.
TEST(Report, TheCompactionSectionGivesCoulombsResidualsOfEachStep) {
  CompactionStudyScene study;
  study.scene = "tow", study.youngs_modulus = 80000;
  for (const char* model : {"none", "coulomb"}) {
    CompactionRun run;
    run.solver = "iterative", run.rule = "accelerated", run.status = "converged";
    run.friction_model = model, run.mu = std::string(model) == "none" ? 0.0 : 0.2;
    for (int step : {1, 2, 3}) {  // step 1: no contact carries force yet
      CompactionPoint p;
      p.step = step, p.compaction = 1.0 - 0.1 * step, p.fibre_volume_fraction = 0.4 + 0.1 * step;
      p.pressure = 1e-3 * step, p.iterations = 1000, p.time_s = 1.0;
      p.contacts_per_fibre = step == 1 ? 0.0 : 2.0;
      p.status = step == 3 && run.mu > 0.0 ? "max_iterations" : "converged";
      if (run.mu > 0.0) p.stick_residual = 3e-9 * step, p.slip_residual = 4e-9 * step;
      run.points.push_back(p);
    }
    study.runs.push_back(run);
  }
  StoredCompactionStudy stored;
  stored.study = study;
  ReportData data;
  data.compaction_studies = {stored};
  const std::string md = markdown_without_figures(data, "report_compaction_coulomb");
  EXPECT_NE(md.find("| Step | Vf | it. μ 0.2 Coulomb |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| 1 | 0.500 | 3.00e-09"), std::string::npos) << md;
  EXPECT_NE(md.find("| 2 | 0.600 | 6.00e-09 / 8.00e-09 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 3 | 0.700 | max_iterations: 9.00e-09 / 1.20e-08 |"), std::string::npos)
      << md;
  study.runs.pop_back();
  data.compaction_studies.front().study = study;
  EXPECT_EQ(markdown_without_figures(data, "report_compaction_frictionless")
                .find("Coulomb's law on the answer of each step"),
            std::string::npos);
}

TEST(Report, AFolderThatDoesNotExistIsBadInput) {
  EXPECT_THROW(read_report_data({"/nonexistent/folder"}), InputError);
}

}  // namespace
}  // namespace fibrecheck
