#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace fibrecheck {

/// `fibrecheck fem SCENE [--out RESULT] [--slices N] [--line-contact slices|continuous]
/// [--refine K|auto] [--beam-solver direct|cg_amg] [--contact-assembly
/// compliance_matrix|saddle_point]
/// [--degree 1|2] [--vtk FILE]
/// [--export-contact-problem FILE] [--quiet]`: the implicit finite-element reference on one scene,
/// on every MPI process it is started with.
struct FemArguments {
  std::string scene, out, vtk, contact_problem, line_contact = "slices", beam_solver = "direct",
                                                refine, contact_assembly = "compliance_matrix";
  int slices = 0;
  unsigned int degree = 2;
  bool quiet = false;
};

/// Registers the sub-command and its options, which fill `args`.
CLI::App* add_fem_command(CLI::App& app, FemArguments& args);

/// Runs it: 0 when the reference converged, 3 otherwise (its result is written with its status).
/// Bad input throws InputError before anything is written.
int run_fem(const FemArguments& args);

}  // namespace fibrecheck
