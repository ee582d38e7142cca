#include "fem_command.h"

#include <deal.II/base/mpi.h>

#include <iostream>

#include "exit_codes.h"
#include "input_error.h"
#include "iterative_solver.h"
#include "reference_solver.h"
#include "result.h"
#include "scene.h"
#include "vtk_writer.h"

namespace fibrecheck {

void add_fem_command(CLI::App& app, int& exit_code) {
  struct Arguments {
    std::string scene, out, vtk;
    int slices = 0;
    bool quiet = false;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* fem =
      app.add_subcommand("fem", "Solve a scene with the implicit finite-element reference");
  fem->add_option("scene", args->scene, "Scene file (JSON)")->required();
  fem->add_option("--out", args->out, "Result file (JSON)");
  fem->add_option("--slices", args->slices, "Cross-sections n (overrides contact.slices)")
      ->check(CLI::Range(1, 1000000));
  fem->add_option("--vtk", args->vtk, "ParaView file (.vtp) of fibres and contact forces");
  fem->add_flag("--quiet,-q", args->quiet, "Print nothing but errors");
  fem->callback([args, &exit_code] {
    Scene scene;
    try {
      scene = read_scene(args->scene);
      if (args->slices > 0) scene.contact.slices = args->slices;
      validate_scene(scene);
    } catch (const InputError& e) {
      std::cerr << "fibrecheck fem: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
      return;
    }
    int argc = 1;
    char name[] = "fibrecheck";
    char* argv_storage[] = {name, nullptr};
    char** argv = argv_storage;
    dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    const Result result = solve_reference(scene);
    if (!args->quiet) {
      std::cout << "scene " << scene.name << ": finite-element reference, " << scene.fibres.size()
                << " fibres\n  " << brief_report(result) << "\n";
      for (const std::string& w : result.warnings) std::cout << "  warning: " << w << "\n";
    }
    try {
      if (!args->out.empty()) write_result(args->out, result);
      if (!args->vtk.empty()) write_vtk(args->vtk, scene, result);
    } catch (const std::exception& e) {
      std::cerr << "fibrecheck fem: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
      return;
    }
    exit_code = result.status == "converged" ? kExitConverged : kExitUnsolved;
  });
}

}  // namespace fibrecheck
