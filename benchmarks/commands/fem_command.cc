#include "fem_command.h"

#include <algorithm>
#include <iostream>

#include "atomic_file.h"
#include "contact_problem.h"
#include "exit_codes.h"
#include "input_error.h"
#include "mpi_session.h"
#include "reference_solver.h"
#include "result.h"
#include "scene.h"
#include "vtk_writer.h"

namespace fibrecheck {

namespace {

bool ends_with(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

/// The reference's options from the command line, checked against the scene.
ReferenceOptions reference_options(const FemArguments& args, const Scene& scene) {
  ReferenceOptions options;
  const bool continuous = args.line_contact == "continuous";
  options.line_contact = continuous ? LineContact::continuous : LineContact::slices;
  if (args.refine == "auto" && !continuous)
    throw InputError("command line", "--refine",
                     "auto refines the continuous line contact: use it with "
                     "--line-contact continuous");
  const bool fixed = !args.refine.empty() && args.refine != "auto";
  options.refine_until_converged = args.refine == "auto" || (args.refine.empty() && continuous);
  options.refine = fixed ? std::stoi(args.refine) : 0;
  if (options.refine < 0 && (!continuous || options.refine < coarsest_refinement(scene)))
    throw InputError("command line", "--refine",
                     continuous ? "the coarsest continuous line contact for " +
                                      std::to_string(scene.contact.slices) + " slices is K = " +
                                      std::to_string(coarsest_refinement(scene)) +
                                      " (n/2^-K cells, whole and at least 4)"
                                : "a negative refinement coarsens the continuous line contact "
                                  "only: use it with --line-contact continuous");
  // Contacts are told apart by their quadrature point's index, which has 20 bits.
  if (continuous && fixed && (2LL * scene.contact.slices << options.refine) >= (1LL << 20))
    throw InputError("command line", "--refine",
                     "continuous line contact at 2 × contact.slices × 2^K points: that must "
                     "stay below 2^20");
  options.max_refine = std::max(options.refine, finest_refinement(scene));
  options.beam_solver = args.beam_solver == "cg_amg" ? BeamSolver::cg_amg : BeamSolver::direct;
  options.contact_assembly = args.contact_assembly == "saddle_point"
                                 ? ContactAssembly::saddle_point
                                 : ContactAssembly::compliance_matrix;
  options.degree = args.degree;
  if (ends_with(args.vtk, ".vtu")) options.vtu = args.vtk;
  options.print_timing = !args.quiet;
  return options;
}

}  // namespace

int run_fem(const FemArguments& args) {
  Scene scene = read_scene(args.scene);
  if (args.slices > 0) scene.contact.slices = args.slices;
  validate_scene(scene);
  ReferenceOptions options = reference_options(args, scene);
  // Output folders exist before the run, so that it cannot fail at the end for want of one.
  for (const std::string& path : {args.out, args.vtk, args.contact_problem})
    if (!path.empty()) create_parent_folder(path);

  const MpiSession mpi;
  // Every process computes the same result; the first one speaks and writes.
  const bool first = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (!args.quiet && first)
    options.progress = [](const std::string& line) { std::cerr << "  " << line << "\n"; };
  // The final step's problem, for solvers outside fibrecheck.
  ContactProblem problem;
  if (!args.contact_problem.empty())
    options.contact_problem = [&](const ContactProblem& p) { problem = p; };
  Result result;
  try {
    result = solve_reference(scene, options);
  } catch (const std::exception& e) {
    // The other processes may wait for this one in a collective call: stop them all. A single
    // process hands the error on like every command.
    if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1) throw;
    std::cerr << "fibrecheck fem: error: " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, kExitFailure);
  }
  const int code = result.status == Status::converged ? kExitConverged : kExitUnsolved;
  if (!first) return code;
  if (!args.quiet) {
    std::cout << "scene " << scene.name << ": finite-element reference, " << scene.fibres.size()
              << " fibres\n  " << brief_report(result) << "\n";
    for (const std::string& w : result.warnings) std::cout << "  warning: " << w << "\n";
  }
  if (!args.out.empty()) write_result(args.out, result);
  if (!args.vtk.empty() && options.vtu.empty()) write_vtk(args.vtk, scene, result);
  if (!args.contact_problem.empty()) {
    problem.step = std::max<int>(1, static_cast<int>(result.steps.size()));
    write_contact_problem(args.contact_problem, problem);
  }
  return code;
}

CLI::App* add_fem_command(CLI::App& app, FemArguments& args) {
  CLI::App* fem =
      app.add_subcommand("fem", "Solve a scene with the implicit finite-element reference");
  fem->add_option("scene", args.scene, "Scene file (JSON)")->required();
  fem->add_option("--out", args.out, "Result file (JSON)");
  fem->add_option("--slices", args.slices, "Cross-sections n (overrides contact.slices)")
      ->check(CLI::Range(1, 1000000));
  fem->add_option("--line-contact", args.line_contact,
                  "Line contacts at the n slices (as the iterative solver) or continuous (Gauss "
                  "points of n*2^K cells)")
      ->check(CLI::IsMember({"slices", "continuous"}));
  fem->add_option("--beam-solver", args.beam_solver,
                  "Beams' linear solver: direct (MUMPS, the default) or cg_amg (CG with hypre "
                  "BoomerAMG on the system's two Laplace halves)")
      ->check(CLI::IsMember({"direct", "cg_amg"}));
  fem->add_option("--contact-assembly", args.contact_assembly,
                  "The contact problem as the compliance matrix (the default: dense per fibre, "
                  "held whole by every process) or as saddle points of the beams and the "
                  "contacts (memory linear, shared over the processes; frictionless)")
      ->check(CLI::IsMember({"compliance_matrix", "saddle_point"}));
  fem->add_option("--degree", args.degree,
                  "Degree of the beam elements: 2 (the default: exact at the nodes) or 1 (linear, "
                  "to study the elements themselves)")
      ->check(CLI::Range(1, 2));
  fem->add_option(
         "--refine", args.refine,
         "Refinements K (0-12): elements (and continuous-mode cells) 2^K times smaller; down "
         "to -2 in continuous mode (n/4 cells); auto (the default in continuous mode): "
         "refine from the coarsest until the line force settles")
      ->check([](const std::string& value) -> std::string {
        if (value == "auto") return "";
        try {
          std::size_t used = 0;
          const int k = std::stoi(value, &used);
          if (used == value.size() && k >= -2 && k <= 12) return "";
        } catch (const std::exception&) {
        }
        return "--refine: expected a whole number from -2 to 12, or auto";
      });
  fem->add_option("--vtk", args.vtk,
                  "ParaView file: .vtu = the finite-element beams (w, M, displacement), .vtp = "
                  "fibres and contact forces")
      ->check([](const std::string& path) -> std::string {
        return ends_with(path, ".vtu") || ends_with(path, ".vtp")
                   ? ""
                   : "--vtk: the file must end in .vtu or .vtp";
      });
  fem->add_option("--export-contact-problem", args.contact_problem,
                  "The final step's contact problem (compliance W with its tangential blocks, "
                  "free overlaps and slips q, mu) and the reference's answer, as JSON for "
                  "solvers outside fibrecheck (fibrecheck-siconos reads it)");
  fem->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  return fem;
}

}  // namespace fibrecheck
