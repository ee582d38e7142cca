#pragma once

#include <mpi.h>

namespace fibrecheck {

/// How many processes of `communicator` share this process's machine (MPI's shared-memory split),
/// which share its cores and its memory.
int processes_on_this_machine(MPI_Comm communicator);

}  // namespace fibrecheck
