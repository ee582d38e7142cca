// fibrecheck: cross-checks the iterative fibre-contact method for tow compaction.
//
// Sample runs:
//   fibrecheck solve scenes/two_fibres_crossing.json --out crossing.result.json --vtk crossing.vtp
//   fibrecheck solve scenes/small_tow_19.json --rule accelerated --out tow.result.json
//   fibrecheck solve --help-scene
//   fibrecheck generate tow --fibres 1000 --slices 100 --seed 7 --out tow1000.json
//   fibrecheck mesh scenes/small_tow_19.json --out small_tow_19.msh --geo small_tow_19.geo
#include <CLI/CLI.hpp>
#include <iostream>

#include "exit_codes.h"
#include "generate_command.h"
#include "solve_command.h"
#ifdef FIBRECHECK_WITH_FEM
#include "fem_command.h"
#include "mesh_command.h"
#endif

int main(int argc, char** argv) {
  CLI::App app{"fibrecheck: the iterative fibre-contact method of tow compaction, checked"};
  app.require_subcommand(1);
  int exit_code = fibrecheck::kExitConverged;
  fibrecheck::add_solve_command(app, exit_code);
  fibrecheck::add_generate_command(app, exit_code);
#ifdef FIBRECHECK_WITH_FEM
  fibrecheck::add_mesh_command(app, exit_code);
  fibrecheck::add_fem_command(app, exit_code);
#else
  for (const char* name : {"mesh", "fem"})
    app.add_subcommand(name, "(needs the build with -DFIBRECHECK_WITH_FEM=ON)")
        ->allow_extras()
        ->callback([&exit_code, name] {
          std::cerr << "fibrecheck " << name
                    << ": error: this build has no finite-element stack; "
                       "configure with -DFIBRECHECK_WITH_FEM=ON\n";
          exit_code = fibrecheck::kExitBadInput;
        });
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return fibrecheck::kExitBadInput;
  }
  return exit_code;
}
