// fibrecheck: cross-checks the iterative fibre-contact method for tow compaction.
//
// Sample runs (one per sub-command):
//   fibrecheck solve scenes/two_fibres_crossing.json --out crossing.result.json --vtk crossing.vtp
//   fibrecheck solve scenes/small_tow_19.json --rule accelerated --out tow.result.json
//   fibrecheck solve --help-scene
//   fibrecheck fem scenes/parallel_fibres.json --line-contact continuous --out parallel.fem.json
//   mpirun -np 2 fibrecheck fem scenes/small_tow_19.json --out tow.fem.json --vtk tow.vtu
//   fibrecheck mesh scenes/small_tow_19.json --out small_tow_19.msh --geo small_tow_19.geo
//   fibrecheck generate tow --fibres 1000 --slices 100 --seed 7 --out tow1000.json
//   fibrecheck compare scenes/*.json --out build/compare
//   fibrecheck compare --run my.result.json --truth reference.result.json
//   fibrecheck study slices scenes/parallel_fibres.json --slices 2,4,8,16,32 --out
//   build/study/slices fibrecheck study tolerance scenes/small_tow_19.json --out
//   build/study/tolerance fibrecheck study stability scenes/two_fibres_crossing.json --out
//   build/study/stability fibrecheck report build/compare build/study --out build/report
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>

#include "compare_command.h"
#include "exit_codes.h"
#include "generate_command.h"
#include "input_error.h"
#include "report_command.h"
#include "solve_command.h"
#include "study_command.h"
#ifdef FIBRECHECK_WITH_FEM
#include "fem_command.h"
#include "mesh_command.h"
#endif

namespace fibrecheck {
namespace {

/// Runs one sub-command and maps what it throws to the program's exit codes, in this one place:
/// bad input (scene, option, path) is 2 with one line naming the file, the field and the reason;
/// anything else is an internal error, 1.
int run_command(const std::string& name, const std::function<int()>& run) {
  try {
    return run();
  } catch (const InputError& e) {
    std::cerr << "fibrecheck " << name << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "fibrecheck " << name << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "fibrecheck " << name << ": error: " << e.what() << "\n";
    return kExitFailure;
  }
}

/// Threads waiting for work sleep rather than spin, unless OMP_WAIT_POLICY says otherwise. A
/// spinning thread holds a core another program needs, and each parallel region then waits for a
/// thread the system has put aside: a 1 000-fibre tow took 2.4 times as long with one of two cores
/// busy, 1.4 times with sleeping threads (and 1.2 times as long on an idle machine). The OpenMP
/// runtime reads the policy once, at start-up, so the program sets it and starts itself again.
void let_waiting_threads_sleep(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  setenv("OMP_WAIT_POLICY", "passive", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: then carry on as started
}

}  // namespace
}  // namespace fibrecheck

int main(int argc, char** argv) {
  using namespace fibrecheck;
  let_waiting_threads_sleep(argv);
  CLI::App app{"fibrecheck: the iterative fibre-contact method of tow compaction, checked"};
  app.require_subcommand(1);
  SolveArguments solve;
  GenerateArguments generate;
  CLI::App* solve_app = add_solve_command(app, solve);
  CLI::App* tow_app = add_generate_command(app, generate);
  CompareArguments compare;
  StudyArguments study;
  ReportArguments report;
  CLI::App* compare_app = add_compare_command(app, compare);
  CLI::App* study_app = add_study_command(app, study);
  CLI::App* report_app = add_report_command(app, report);
#ifdef FIBRECHECK_WITH_FEM
  FemArguments fem;
  MeshArguments mesh;
  CLI::App* fem_app = add_fem_command(app, fem);
  CLI::App* mesh_app = add_mesh_command(app, mesh);
#else
  for (const char* name : {"mesh", "fem"})
    app.add_subcommand(name, "(needs the build with -DFIBRECHECK_WITH_FEM=ON)")->allow_extras();
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  if (solve_app->parsed()) return run_command("solve", [&] { return run_solve(solve); });
  if (tow_app->parsed()) return run_command("generate tow", [&] { return run_generate(generate); });
  if (compare_app->parsed()) return run_command("compare", [&] { return run_compare(compare); });
  if (study_app->parsed())
    return run_command("study " + study.study, [&] { return run_study(study); });
  if (report_app->parsed()) return run_command("report", [&] { return run_report(report); });
#ifdef FIBRECHECK_WITH_FEM
  if (fem_app->parsed()) return run_command("fem", [&] { return run_fem(fem); });
  if (mesh_app->parsed()) return run_command("mesh", [&] { return run_mesh(mesh); });
#else
  const std::string name = app.get_subcommands().front()->get_name();
  std::cerr << "fibrecheck " << name
            << ": error: this build has no finite-element stack; configure with "
               "-DFIBRECHECK_WITH_FEM=ON\n";
  return kExitBadInput;
#endif
  return kExitFailure;
}
