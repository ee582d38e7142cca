#pragma once

#include <mpi.h>

#include <vector>

namespace fibrecheck {

/// The reference shares its fibres out among the processes (fibre f on process f mod p), and each
/// process fills in the numbers of its own fibres only, leaving zeros elsewhere: a sum over the
/// processes then gives every process every fibre's numbers, the same bits on each (DESIGN §3: the
/// same answer on any number of processes). Sums `values` element by element over `comm`, in
/// place; nothing to do on one process. MPI counts are ints, so long vectors go in pieces.
void sum_over_processes(std::vector<double>& values, MPI_Comm comm);

/// Whether `holds` holds on every process of `comm`.
bool all_over_processes(bool holds, MPI_Comm comm);

}  // namespace fibrecheck
