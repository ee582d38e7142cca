#pragma once

#include "comparison.h"

namespace fibrecheck {

/// The solvers the harness commands hand to the harness: the iterative solver as the scene says,
/// and, in a build with the finite-element stack, the reference on one process (in a build
/// without it, asking for the reference is bad input with a message saying what is missing).
/// Unless `quiet`, the reference prints its refinements; with `progress_every_s` above zero the
/// iterative solver prints a line that often from inside a run (its load path's step, iteration
/// and residuals), so that a study's hour-long run says where it stands.
Solvers make_solvers(bool quiet, double progress_every_s = 0.0);

/// True in a build with the finite-element stack.
bool have_reference();

}  // namespace fibrecheck
