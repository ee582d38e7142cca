#pragma once

#include "comparison.h"

namespace fibrecheck {

/// The solvers the harness commands hand to the harness: the iterative solver as the scene says,
/// and, in a build with the finite-element stack, the reference on one process (in a build
/// without it, asking for the reference is bad input with a message saying what is missing).
/// `progress`, when not quiet, prints the reference's refinements.
Solvers make_solvers(bool quiet);

/// True in a build with the finite-element stack.
bool have_reference();

}  // namespace fibrecheck
