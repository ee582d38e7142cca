// The report's LaTeX: every symbol and number of its texts typeset (no raw UTF-8 reaches LaTeX,
// so pdflatex cannot stop on one), text columns flush left and numbers flush right, and the
// fixture's report.tex compiled by pdflatex and lualatex without an error, an overfull box
// wider than 1 pt or an undefined citation or reference.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "report_data.h"
#include "report_writer.h"
#include "slurp.h"
#include "tables.h"

namespace fibrecheck {
namespace {

namespace fs = std::filesystem;

bool is_ascii(const std::string& text) {
  for (char c : text)
    if (static_cast<unsigned char>(c) >= 0x80) return false;
  return true;
}

TEST(ReportLatex, EverySymbolOfTheReportsSourcesIsSetAsLatex) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(FIBRECHECK_REPORT_SOURCES)) {
    if (entry.path().extension() != ".cc") continue;
    ++files;
    const std::string source = slurp(entry.path());
    const std::string latex = latex_escape(source);
    EXPECT_TRUE(is_ascii(latex)) << entry.path() << " has a character latex_escape leaves as is";
  }
  EXPECT_GT(files, 5);
}

TEST(ReportLatex, NumbersInScientificNotationAreTypeset) {
  EXPECT_EQ(latex_escape("4.85e-08"), "\\ensuremath{4.85\\times10^{-8}}");
  EXPECT_EQ(latex_escape("error 1.20e+03 N"), "error \\ensuremath{1.20\\times10^{3}} N");
  EXPECT_EQ(latex_escape("0.00e+00"), "0");
  // Part of a name, not a number: only the underscores are escaped.
  EXPECT_EQ(latex_escape("parallel_turned_1e-7rad"), "parallel\\_turned\\_1e-7rad");
  EXPECT_EQ(latex_escape("tow_1e-3"), "tow\\_1e-3");
}

TEST(ReportLatex, MathGoesThroughAndCitationsCite) {
  EXPECT_EQ(latex_text("the update $P' = P + c\\,d$ of [@sherburn2007], 50% of it"),
            "the update $P' = P + c\\,d$ of \\cite{sherburn2007}, 50\\% of it");
  EXPECT_EQ(latex_text("a lone $ sign"), "a lone \\$ sign");
}

TEST(ReportLatex, TextColumnsLeftNumbersRight) {
  Table t;
  t.label = "t";
  t.caption = "c";
  t.header = {"Scene", "Rule", "Force", "Time (s)"};
  t.rows = {{"a_b", "auto", "1.00e-03", "12.5"}, {"c", "seed", "–", "7"}};
  const std::string tex = latex(t);
  EXPECT_NE(tex.find("\\begin{tabular}{llrr}"), std::string::npos) << tex;
  EXPECT_NE(tex.find("max width=\\linewidth"), std::string::npos) << tex;
  EXPECT_NE(markdown(t, 1).find("| --- | --- | ---: | ---: |"), std::string::npos);
}

// Counts from 10 000 up have their digits grouped in threes by a thin space, set as "\," in
// LaTeX; such a column is still numeric, flush right.
TEST(ReportLatex, LargeCountsAreGroupedInThrees) {
  EXPECT_EQ(count(0), "0");
  EXPECT_EQ(count(3370), "3370");
  EXPECT_EQ(count(12105), "12\u2009105");
  EXPECT_EQ(count(366784), "366\u2009784");
  EXPECT_EQ(count(1066717), "1\u2009066\u2009717");
  EXPECT_EQ(latex_escape(count(366784) + " (242.4 s)"), "366\\,784 (242.4 s)");
  Table t;
  t.label = "t";
  t.caption = "c";
  t.header = {"Fibres", "Iterations"};
  t.rows = {{count(12000), count(752254)}, {count(100), count(8183)}};
  EXPECT_NE(latex(t).find("\\begin{tabular}{rr}"), std::string::npos) << latex(t);
}

/// The log's complaints: overfull boxes wider than 1 pt, undefined citations and references.
std::vector<std::string> complaints(const std::string& log) {
  std::vector<std::string> found;
  const std::regex overfull(R"(Overfull \\[hv]box \(([0-9.]+)pt too (wide|high)\))");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), overfull);
       it != std::sregex_iterator(); ++it)
    if (std::stod((*it)[1]) > 1.0) found.push_back(it->str());
  for (const char* what : {"Citation `", "Reference `", "undefined references"})
    if (log.find(what) != std::string::npos) found.push_back(what);
  return found;
}

TEST(ReportLatex, TheFixturesReportCompilesCleanly) {
  const fs::path out = ::testing::TempDir() + "report_latex";
  fs::remove_all(out);
  write_report(read_report_data({FIBRECHECK_REPORT_FIXTURE}), out.string());
  for (const std::string engine : {"pdflatex", "lualatex"}) {
    const std::string run = "cd '" + out.string() + "' && " + engine +
                            " -interaction=nonstopmode -halt-on-error report.tex > " + engine +
                            ".out 2>&1";
    // Twice: the second run resolves the citations and references the first wrote down.
    ASSERT_EQ(std::system(run.c_str()), 0) << engine << ": see " << (out / (engine + ".out"));
    ASSERT_EQ(std::system(run.c_str()), 0) << engine << ": see " << (out / (engine + ".out"));
    EXPECT_GT(fs::file_size(out / "report.pdf"), 10000u);
    const std::vector<std::string> found = complaints(slurp(out / "report.log"));
    EXPECT_TRUE(found.empty()) << engine << ": " << found.front();
  }
}

}  // namespace
}  // namespace fibrecheck
