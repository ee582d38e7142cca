#include <mpi.h>

#include <algorithm>
#include <thread>

#include "blas_threads.h"
#include "machine_processes.h"
#include "reference_solver.h"

namespace fibrecheck {

// Declared in reference_solver.h: Debian's OpenBLAS starts a thread per core in every process, so
// p processes on one machine would run p threads per core inside MUMPS and PETSc. The processes
// that share a machine (MPI's shared-memory split) divide its cores among them; a BLAS already
// using fewer threads, or one process alone, is left as it is.
void share_cores_with_blas(MPI_Comm communicator) {
  const int here = processes_on_this_machine(communicator);
  if (here <= 1) return;
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int share = std::max(1, cores / here);
  if (blas_threads() > share) set_blas_threads(share);
}

}  // namespace fibrecheck
