#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// `fibrecheck solve SCENE... [--out RESULT | --out-dir DIR] [--slices N] [--rule R] [--c X]
/// [--estimate-slicing [--coarse-slices M]] [--vtk FILE.vtp] [--quiet] [--help-scene]`: the
/// iterative solver on each scene.
struct SolveArguments {
  std::vector<std::string> scenes;
  std::string out, out_dir, vtk, rule;
  int slices = 0;
  bool estimate_slicing = false;
  int coarse_slices = 0;  ///< 0: half the scene's slices
  double c = 0.0;
  bool quiet = false;
  bool help_scene = false;
};

/// Registers the sub-command and its options, which fill `args`.
CLI::App* add_solve_command(CLI::App& app, SolveArguments& args);

/// Runs it: 0 when every scene converged, 3 when one did not (its result is written with its
/// status). Bad input throws InputError before anything is written.
int run_solve(const SolveArguments& args);

}  // namespace fibrecheck
