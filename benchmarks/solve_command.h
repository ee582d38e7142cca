#pragma once

#include <CLI/CLI.hpp>

namespace fibrecheck {

/// `fibrecheck solve SCENE... [--out RESULT | --out-dir DIR] [--slices N] [--rule R] [--c X]
/// [--vtk FILE.vtp] [--quiet] [--help-scene]`: runs the iterative solver.
void add_solve_command(CLI::App& app, int& exit_code);

}  // namespace fibrecheck
