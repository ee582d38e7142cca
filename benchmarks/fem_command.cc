#include "fem_command.h"

#include <iostream>

#include "atomic_file.h"
#include "exit_codes.h"
#include "input_error.h"
#include "iterative_solver.h"
#include "mpi_session.h"
#include "reference_solver.h"
#include "result.h"
#include "scene.h"
#include "vtk_writer.h"

namespace fibrecheck {

void add_fem_command(CLI::App& app, int& exit_code) {
  struct Arguments {
    std::string scene, out, vtk, line_contact = "slices", beam_solver = "direct", refine;
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
  fem->add_option("--line-contact", args->line_contact,
                  "Line contacts at the n slices (as the iterative solver) or continuous (Gauss "
                  "points of n*2^K cells)")
      ->check(CLI::IsMember({"slices", "continuous"}));
  fem->add_option("--beam-solver", args->beam_solver,
                  "Beams' linear solver: direct (MUMPS, the default) or cg_amg (CG with hypre "
                  "BoomerAMG on the system's two Laplace halves)")
      ->check(CLI::IsMember({"direct", "cg_amg"}));
  fem->add_option("--refine", args->refine,
                  "Refinements K (0-12): elements (and continuous-mode cells) 2^K times smaller; "
                  "auto (the default in continuous mode): refine until the line force settles")
      ->check([](const std::string& value) -> std::string {
        if (value == "auto") return "";
        try {
          std::size_t used = 0;
          const int k = std::stoi(value, &used);
          if (used == value.size() && k >= 0 && k <= 12) return "";
        } catch (const std::exception&) {
        }
        return "--refine: expected a whole number from 0 to 12, or auto";
      });
  fem->add_option("--vtk", args->vtk,
                  "ParaView file: .vtu = the finite-element beams (w, M, displacement), .vtp = "
                  "fibres and contact forces")
      ->check([](const std::string& path) -> std::string {
        const auto dot = path.rfind('.');
        const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
        return ext == ".vtu" || ext == ".vtp" ? "" : "--vtk: the file must end in .vtu or .vtp";
      });
  fem->add_flag("--quiet,-q", args->quiet, "Print nothing but errors");
  fem->callback([args, &exit_code] {
    Scene scene;
    try {
      scene = read_scene(args->scene);
      if (args->slices > 0) scene.contact.slices = args->slices;
      validate_scene(scene);
      const bool continuous = args->line_contact == "continuous";
      if (args->refine == "auto" && !continuous)
        throw InputError("--refine", "",
                         "auto refines the continuous line contact: use it with "
                         "--line-contact continuous");
      // Contacts are told apart by their station number, which has 20 bits.
      const bool fixed = !args->refine.empty() && args->refine != "auto";
      if (continuous && fixed &&
          (2LL * scene.contact.slices << std::stoi(args->refine)) >= (1LL << 20))
        throw InputError("--refine", "",
                         "continuous line contact at 2 × contact.slices × 2^K stations: that must "
                         "stay below 2^20");
      // Output folders exist before the run, so that it cannot fail at the end for want of one.
      for (const std::string& path : {args->out, args->vtk})
        if (!path.empty()) create_parent_folder(path);
    } catch (const InputError& e) {
      std::cerr << "fibrecheck fem: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
      return;
    }
    const MpiSession mpi;
    // Every process computes the same result; the first one speaks and writes.
    const bool first = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    const bool vtu = args->vtk.size() > 4 && args->vtk.substr(args->vtk.size() - 4) == ".vtu";
    ReferenceOptions options;
    options.line_contact =
        args->line_contact == "continuous" ? LineContact::continuous : LineContact::slices;
    const bool continuous = options.line_contact == LineContact::continuous;
    options.refine_until_converged = args->refine == "auto" || (args->refine.empty() && continuous);
    options.refine = args->refine.empty() || args->refine == "auto" ? 0 : std::stoi(args->refine);
    while (options.max_refine > 0 &&
           (2LL * scene.contact.slices << options.max_refine) >= (1LL << 20))
      --options.max_refine;
    options.beam_solver = args->beam_solver == "cg_amg" ? BeamSolver::cg_amg : BeamSolver::direct;
    if (vtu) options.vtu = args->vtk;
    options.print_timing = !args->quiet;
    if (!args->quiet && first)
      options.progress = [](const std::string& line) { std::cerr << "  " << line << "\n"; };
    Result result;
    try {
      result = solve_reference(scene, options);
    } catch (const std::exception& e) {
      std::cerr << "fibrecheck fem: error: " << e.what() << "\n";
      // The other processes may wait for this one in a collective call: stop them all.
      if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        MPI_Abort(MPI_COMM_WORLD, kExitFailure);
      exit_code = kExitFailure;
      return;
    }
    exit_code = result.status == "converged" ? kExitConverged : kExitUnsolved;
    if (!first) return;
    if (!args->quiet) {
      std::cout << "scene " << scene.name << ": finite-element reference, " << scene.fibres.size()
                << " fibres\n  " << brief_report(result) << "\n";
      for (const std::string& w : result.warnings) std::cout << "  warning: " << w << "\n";
    }
    try {
      if (!args->out.empty()) write_result(args->out, result);
      if (!args->vtk.empty() && !vtu) write_vtk(args->vtk, scene, result);
    } catch (const std::exception& e) {
      std::cerr << "fibrecheck fem: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
      return;
    }
  });
}

}  // namespace fibrecheck
