#pragma once

#include <functional>
#include <string>

#include "iterative_solver.h"

namespace fibrecheck {

/// One line saying where a long iterative run stands: the step of its load path, the iteration,
/// the residuals against t_d, the updates of the normals and of the Tresca radii, and the time.
std::string progress_line(const IterationProgress& p);

/// Prints `progress_line` to the error stream after `indent`: in place on a terminal (each line
/// overwriting the last), else one line each time.
std::function<void(const IterationProgress&)> progress_printer(bool in_place,
                                                               const std::string& indent);

}  // namespace fibrecheck
