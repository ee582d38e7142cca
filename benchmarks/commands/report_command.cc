#include "report_command.h"

#include <iostream>

#include "exit_codes.h"
#include "input_error.h"
#include "report_data.h"
#include "report_writer.h"

namespace fibrecheck {

int run_report(const ReportArguments& args) {
  const ReportData data = read_report_data(args.folders);
  if (data.sources.empty())
    throw InputError(args.folders.front(), "",
                     "holds no compare.json or study data (run fibrecheck compare or study first)");
  const ReportSummary summary = write_report(data, args.out);
  if (!args.quiet) {
    std::cout << "report written to " << args.out
              << "/report.md (and report.tex): " << summary.tables << " tables, " << summary.figures
              << " figures, from " << data.sources.size() << " data files\n\n"
              << summary.headline;
  }
  for (const std::string& m : summary.missing)
    std::cerr << "fibrecheck report: figure not drawn: " << m << "\n";
  return summary.missing.empty() ? kExitConverged : kExitUnsolved;
}

CLI::App* add_report_command(CLI::App& app, ReportArguments& args) {
  CLI::App* report = app.add_subcommand(
      "report", "Tables and figures (Markdown, LaTeX, gnuplot) from compare and study data");
  report->add_option("folders", args.folders, "Folders holding compare and study output")
      ->required();
  report->add_option("--out", args.out, "Folder of the report")->capture_default_str();
  report->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  return report;
}

}  // namespace fibrecheck
