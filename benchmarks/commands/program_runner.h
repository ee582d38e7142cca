#pragma once

#include <string>

#include "scale_study.h"

namespace fibrecheck {

/// Runs a program as a child process and waits for it: its exit code, wall time, peak resident
/// memory (wait4's ru_maxrss: the largest of the child and the processes it waited for, so under
/// mpiexec the largest rank), the largest peak proportional set size of the child and the
/// processes descended from it (sampled every tenth of a second) and the last lines of its
/// standard error. Its standard output is
/// discarded. Open MPI's permission to run as root is passed on when this process is root.
ProgramRun run_program(const std::vector<std::string>& arguments);

/// This program's own path (for studies that run it again), and the path of a program beside it.
std::string this_program();
std::string program_beside_this(const std::string& name);

/// The full path of `name` found on PATH, or empty.
std::string find_on_path(const std::string& name);

}  // namespace fibrecheck
