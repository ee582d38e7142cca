#include "solve_command.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "exit_codes.h"
#include "input_error.h"
#include "iterative_solver.h"
#include "progress_line.h"
#include "result.h"
#include "scene.h"
#include "slicing_estimate.h"
#include "vtk_writer.h"

namespace fibrecheck {

namespace {

std::string result_path_for(const SolveArguments& args, const Scene& scene) {
  if (!args.out.empty()) return args.out;
  if (!args.out_dir.empty())
    return (std::filesystem::path(args.out_dir) / (scene.name + ".result.json")).string();
  return "";
}

void print_table(const std::vector<Result>& results, const std::vector<Scene>& scenes) {
  std::printf("\n%-24s %7s %9s %-12s %-15s %10s %9s %12s %12s\n", "scene", "fibres", "contacts",
              "rule", "status", "iterations", "time_s", "energy_Nmm", "overlap_mm");
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Result& r = results[i];
    std::size_t points = 0;
    for (const ContactResult& c : r.contacts) points += c.points.size();
    std::printf("%-24s %7zu %9zu %-12s %-15s %10ld %9.3f %12.5g %12.3g\n", r.scene.c_str(),
                scenes[i].fibres.size(), points, r.rule.c_str(), to_string(r.status), r.iterations,
                r.wall_time_s, r.strain_energy_exact, r.max_overlap);
  }
}

/// The slices of the second run of a slicing estimate: as asked, else half the scene's.
int coarse_slices_for(const SolveArguments& args, const Scene& scene) {
  const int n = scene.contact.slices;
  const int m = args.coarse_slices > 0 ? args.coarse_slices : n / 2;
  if (n < 2)
    throw InputError(
        scene.source, "contact.slices",
        "a slicing estimate needs at least 2 slices (the scene has " + std::to_string(n) + ")");
  if (m >= n)
    throw InputError("command line", "--coarse-slices",
                     "must be below the scene's " + std::to_string(n) + " slices");
  return m;
}

/// The scene at `slices` slices, solved with the options of the first run.
Result solve_at(const Scene& scene, const SolverOptions& options, int slices) {
  Scene coarse = scene;
  coarse.contact.slices = slices;
  SolverOptions o = SolverOptions::from_scene(coarse);
  o.progress = options.progress;
  o.progress_interval_s = options.progress_interval_s;
  return solve_iteratively(coarse, o);
}

/// Solves the scene again at fewer slices and estimates the first run's slicing error from the
/// difference, then once more at fewer still to check the orders it assumes; a run that does not
/// converge gives no estimate (or no check), only a warning.
void estimate_slicing(const Scene& scene, const SolverOptions& options, int coarse_slices,
                      Result& result) {
  auto failed = [&result](int slices, const Result& run) {
    result.warnings.push_back("slicing estimate: the run at " + std::to_string(slices) +
                              " slices ended " + to_string(run.status) + " (" + run.message + ")");
  };
  const Result coarse = solve_at(scene, options, coarse_slices);
  if (coarse.status != Status::converged) return failed(coarse_slices, coarse);
  SlicingEstimate& e = result.slicing_estimate.emplace(
      estimate_slicing_error(result, coarse, scene.contact.slices, coarse_slices));
  const int coarser_slices =
      static_cast<int>(std::lround(double(coarse_slices) * coarse_slices / scene.contact.slices));
  if (coarser_slices < 1 || coarser_slices >= coarse_slices) return;
  const Result coarser = solve_at(scene, options, coarser_slices);
  if (coarser.status != Status::converged) return failed(coarser_slices, coarser);
  observe_slicing_orders(e, result, coarse, coarser, coarser_slices);
  if (!slicing_orders_hold(e)) {
    std::ostringstream why;
    why.precision(3);
    why << "slicing estimate uncertain: between " << coarser_slices << ", " << coarse_slices
        << " and " << scene.contact.slices << " slices the errors fall at order "
        << e.observed_force_order << " in force and " << e.observed_deflection_order
        << " in deflection, not " << e.force_order << " and " << e.deflection_order
        << " (fibres that touch along part of a line change their touching stretch with the "
           "slices)";
    result.warnings.push_back(why.str());
  }
}

}  // namespace

int run_solve(const SolveArguments& args) {
  if (args.help_scene) {
    std::cout << scene_format_help();
    return kExitConverged;
  }
  if (args.scenes.empty()) throw InputError("command line", "", "no scene file given (see --help)");
  if (args.scenes.size() > 1 && !args.out.empty())
    throw InputError("command line", "--out",
                     "names one result file; use --out-dir for several scenes");
  if (args.scenes.size() > 1 && !args.vtk.empty())
    throw InputError("command line", "--vtk", "takes one scene");
  // Read and check every scene before solving anything: bad input writes nothing.
  std::vector<Scene> scenes;
  std::vector<SolverOptions> options;
  for (const std::string& path : args.scenes) {
    Scene scene = read_scene(path);
    if (args.slices > 0) scene.contact.slices = args.slices;
    if (!args.rule.empty())
      scene.solver.rule = parse_update_rule(args.rule, "command line", "--rule");
    if (args.c > 0.0) scene.solver.c = args.c;
    validate_scene(scene);
    SolverOptions o = SolverOptions::from_scene(scene);
    std::string why;
    if (!o.is_valid(&why)) throw InputError(path, "solver", why);
    if (args.estimate_slicing) coarse_slices_for(args, scene);
    scenes.push_back(std::move(scene));
    options.push_back(std::move(o));
  }

  const bool terminal = isatty(fileno(stderr));
  int code = kExitConverged;
  std::vector<Result> results;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const Scene& scene = scenes[i];
    SolverOptions& o = options[i];
    if (!args.quiet) {
      std::cout << "scene " << scene.name << " (" << scene.source << "): " << scene.fibres.size()
                << " fibres, " << scene.loads.size() << " loads, " << scene.walls.size()
                << " walls; rule " << to_string(o.rule) << ", slices " << scene.contact.slices
                << ", overlap tolerance " << o.overlap_tolerance << " mm, max iterations "
                << o.max_iterations << std::endl;
      o.progress = progress_printer(terminal, "  ");
      o.progress_interval_s = terminal ? 0.5 : 5.0;
    }
    Result result = solve_iteratively(scene, o);
    if (args.estimate_slicing && result.status == Status::converged) {
      const int m = coarse_slices_for(args, scene);
      if (!args.quiet) {
        if (terminal) std::cerr << "\r\033[K";
        std::cout << "  estimating the slicing error: the scene again at " << m << " slices (and "
                  << std::lround(double(m) * m / scene.contact.slices) << " to check)" << std::endl;
      }
      estimate_slicing(scene, o, m, result);
    }
    if (!args.quiet && terminal) std::cerr << "\r\033[K";
    if (!args.quiet) {
      std::cout << "  rule " << result.rule << ": c = " << result.c
                << " N/mm per point contact (slices: c/n under rule seed), stable below about "
                << result.c_stable_limit << " N/mm (2/lambda_max(W)"
                << (result.rule == to_string(UpdateRule::seed)
                        ? " of D^1/2 W D^1/2, D the slice weights"
                        : "")
                << ")\n";
      std::istringstream report(brief_report(result));
      for (std::string line; std::getline(report, line);) std::cout << "  " << line << "\n";
      for (const std::string& w : result.warnings) std::cout << "  warning: " << w << "\n";
    }
    const std::string path = result_path_for(args, scene);
    if (!path.empty()) write_result(path, result);
    if (!args.vtk.empty()) write_vtk(args.vtk, scene, result);
    if (!args.quiet && !path.empty()) std::cout << "  result written to " << path << "\n";
    if (result.status != Status::converged) {
      std::cerr << "fibrecheck solve: " << scene.source << ": " << to_string(result.status) << ": "
                << result.message << "\n";
      code = kExitUnsolved;
    }
    results.push_back(std::move(result));
  }
  if (scenes.size() > 1 && !args.quiet) print_table(results, scenes);
  return code;
}

CLI::App* add_solve_command(CLI::App& app, SolveArguments& args) {
  CLI::App* solve = app.add_subcommand("solve", "Solve scenes with the iterative method");
  solve->add_option("scenes", args.scenes, "Scene files (JSON)");
  solve->add_option("--out", args.out, "Result file (JSON) for one scene");
  solve->add_option("--out-dir", args.out_dir, "Folder for SCENE_NAME.result.json files");
  solve->add_option("--slices", args.slices, "Cross-sections n (overrides contact.slices)")
      ->check(CLI::Range(1, 1000000));
  solve->add_flag("--estimate-slicing", args.estimate_slicing,
                  "Also estimate the slicing error, from a second run at fewer slices");
  solve
      ->add_option("--coarse-slices", args.coarse_slices,
                   "Slices of that second run (default half the scene's)")
      ->check(CLI::Range(1, 1000000))
      ->needs("--estimate-slicing");
  std::string rules;
  for (const std::string& name : update_rule_names()) rules += (rules.empty() ? "" : " | ") + name;
  solve->add_option("--rule", args.rule, "Force update rule: " + rules)
      ->check(CLI::IsMember(update_rule_names()));
  solve->add_option("--c", args.c, "Step c of P' = P + c*d in N/mm (rule seed)")
      ->check(CLI::PositiveNumber);
  solve->add_option("--vtk", args.vtk, "ParaView file (.vtp) of fibres and contact forces");
  solve->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  solve->add_flag("--help-scene", args.help_scene, "Print every scene field with its default");
  return solve;
}

}  // namespace fibrecheck
