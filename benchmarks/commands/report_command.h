#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// `fibrecheck report DIR... --out FOLDER`: the report of the harness's data found below the
/// folders (compare and study output): report.md, report.tex, tables/, figures/, data/.
struct ReportArguments {
  std::vector<std::string> folders;
  std::string out = "report/out";
  bool quiet = false;
};

CLI::App* add_report_command(CLI::App& app, ReportArguments& args);

/// 0 with every figure drawn; 3 when the tables came out but figures could not be drawn.
int run_report(const ReportArguments& args);

}  // namespace fibrecheck
