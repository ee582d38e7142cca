#include "compare_command.h"

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "comparison.h"
#include "exit_codes.h"
#include "input_error.h"
#include "result.h"
#include "scene.h"
#include "solvers.h"
#ifdef FIBRECHECK_WITH_FEM
#include "mpi_session.h"
#endif

namespace fibrecheck {

namespace {

int compare_stored(const CompareArguments& args) {
  const Result run = read_result(args.run), truth = read_result(args.truth);
  if (run.scene != truth.scene)
    throw InputError(args.run, "scene",
                     "is " + run.scene + ", but " + args.truth + " is of " + truth.scene);
  const ErrorReport report = measure_errors(run, truth, args.run + " against " + args.truth);
  nlohmann::json j = to_json(report.errors);
  j["scene"] = run.scene;
  j["run"] = args.run;
  j["truth"] = args.truth;
  j["pairs"] = nlohmann::json::array();
  for (const PairError& p : report.pairs) j["pairs"].push_back(to_json(p));
  if (!args.out.empty()) write_file_atomically(args.out, j.dump(1) + "\n");
  if (!args.quiet)
    std::printf("%s against %s: deflection error %.3e, force error %.3e, energy error %.3e\n",
                args.run.c_str(), args.truth.c_str(), report.errors.deflection, report.errors.force,
                report.errors.energy);
  return kExitConverged;
}

}  // namespace

int run_compare(const CompareArguments& args) {
  if (!args.run.empty() || !args.truth.empty()) {
    if (args.run.empty() || args.truth.empty())
      throw InputError("command line", args.run.empty() ? "--run" : "--truth",
                       "--run and --truth go together");
    if (!args.scenes.empty())
      throw InputError("command line", "scenes", "give scenes or --run/--truth, not both");
    return compare_stored(args);
  }
  if (args.scenes.empty()) throw InputError("command line", "", "no scene file given (see --help)");
  if (args.out.empty()) throw InputError("command line", "--out", "names the output folder");
  const std::vector<Scene> scenes = read_scenes(args.scenes);
  if (!have_reference())
    throw InputError("command line", "",
                     "comparing scenes runs the reference: it needs the build with "
                     "-DFIBRECHECK_WITH_FEM=ON (compare --run/--truth works without)");
#ifdef FIBRECHECK_WITH_FEM
  const MpiSession mpi;
#endif
  const Solvers solvers = make_solvers(args.quiet);
  std::vector<Comparison> comparisons;
  int code = kExitConverged;
  for (const Scene& scene : scenes) {
    if (!args.quiet) std::cerr << "compare " << scene.name << " (" << scene.source << ")\n";
    const Comparison c = compare_scene(scene, solvers, [&](const std::string& line) {
      if (!args.quiet) std::cerr << "  " << line << "\n";
    });
    write_comparison((std::filesystem::path(args.out) / scene.name).string(), scene, c);
    if (!c.comparable) code = kExitUnsolved;
    comparisons.push_back(c);
  }
  if (!args.quiet) std::cout << comparison_table(comparisons);
  return code;
}

CLI::App* add_compare_command(CLI::App& app, CompareArguments& args) {
  CLI::App* compare = app.add_subcommand(
      "compare", "Run both solvers on scenes and measure the iterative method's error");
  compare->add_option("scenes", args.scenes, "Scene files (JSON)");
  compare->add_option("--out", args.out,
                      "Output folder (one subfolder per scene), or with --run/--truth a JSON file");
  compare->add_option("--run", args.run, "A stored result to measure");
  compare->add_option("--truth", args.truth, "The stored result to measure it against");
  compare->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  return compare;
}

}  // namespace fibrecheck
