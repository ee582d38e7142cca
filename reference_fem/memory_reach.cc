#include "memory_reach.h"

#include <unistd.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "machine_processes.h"

namespace fibrecheck {

MemoryNeed contact_problem_memory(const std::vector<std::size_t>& stations,
                                  const std::vector<std::size_t>& sides,
                                  const std::vector<std::size_t>& frictional) {
  constexpr double kTriplet = sizeof(Eigen::Triplet<double>);
  constexpr double kEntry = sizeof(double) + sizeof(int);  // a compressed sparse entry
  MemoryNeed need;
  for (std::size_t f = 0; f < stations.size(); ++f) {
    const double m = static_cast<double>(stations[f]);
    const double c = static_cast<double>(sides[f]);
    const double r = frictional.empty() ? 0.0 : static_cast<double>(frictional[f]);
    need.influence += 2 * sizeof(double) * m * m;
    need.compliance += (kTriplet + kEntry) * (c * c + r * r);
  }
  return need;
}

// Measured on generated tows of 1 000 to 12 000 fibres (docs/reference.md, "Memory per process"):
// the peak resident memory of a process, less the libraries' pages and its influence matrices,
// came to 0.40–0.45 kB per unknown of its fibres.
double finite_element_memory(double unknowns) {
  constexpr double kBytesPerUnknown = 450.0;
  return kBytesPerUnknown * unknowns;
}

namespace {

/// MemAvailable of /proc/meminfo (bytes), or 0 where there is none.
double available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return 1024.0 * kib;
  return 0.0;
}

}  // namespace

double memory_within_reach(MPI_Comm communicator) {
  double machine = available_memory();
  if (machine <= 0.0)
    machine =
        static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  const int here = std::max(processes_on_this_machine(communicator), 1);
  double mine = 0.9 * machine / here, smallest = mine;
  MPI_Allreduce(&mine, &smallest, 1, MPI_DOUBLE, MPI_MIN, communicator);
  return smallest;
}

std::string memory_line(const MemoryNeed& need, double within_reach) {
  constexpr double kGiB = 1 << 30;
  std::ostringstream out;
  out.precision(3);
  out << "finite elements and contact problem: " << need.total() / kGiB
      << " GiB on the process that needs most (finite elements " << need.finite_elements / kGiB
      << ", influence matrices " << need.influence / kGiB << ", compliance matrix "
      << need.compliance / kGiB << "), " << within_reach / kGiB << " GiB within reach";
  return out.str();
}

std::string beyond_reach_message(const MemoryNeed& need, double within_reach,
                                 const std::string& widest_fibre, std::size_t widest_stations,
                                 bool saddle_points) {
  constexpr double kGiB = 1 << 30;
  std::ostringstream out;
  out.precision(3);
  out << "the reference would need " << need.total() / kGiB
      << " GiB on the process that needs most (finite elements " << need.finite_elements / kGiB
      << " GiB, dense influence matrices " << need.influence / kGiB << " GiB, compliance matrix "
      << need.compliance / kGiB << " GiB; fibre " << widest_fibre << " alone has "
      << widest_stations << " contact stations), more than the " << within_reach / kGiB
      << " GiB each process has on this machine: give the reference fewer slices "
         "(fibrecheck fem --slices) or a coarser continuous line contact, or more processes "
         "on more machines (mpiexec -np), each holding its own fibres";
  if (saddle_points && need.finite_elements < within_reach)
    out << ", or hold the contact problem as saddle points, in memory linear in the unknowns "
           "(fibrecheck fem --contact-assembly saddle_point)";
  return out.str();
}

}  // namespace fibrecheck
