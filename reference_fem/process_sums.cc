#include "process_sums.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cstddef>

namespace fibrecheck {

void sum_over_processes(std::vector<double>& values, MPI_Comm comm) {
  if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1) return;
  constexpr std::size_t piece = std::size_t(1) << 28;
  for (std::size_t start = 0; start < values.size(); start += piece)
    MPI_Allreduce(MPI_IN_PLACE, values.data() + start,
                  static_cast<int>(std::min(piece, values.size() - start)), MPI_DOUBLE, MPI_SUM,
                  comm);
}

bool all_over_processes(bool holds, MPI_Comm comm) {
  int all = holds ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, comm);
  return all != 0;
}

}  // namespace fibrecheck
