#pragma once

#include <mpi.h>

#include <cstddef>
#include <string>
#include <vector>

namespace fibrecheck {

/// What the reference holds on a process (bytes): the dense influence matrix of each fibre in its
/// contact stations, and the compliance matrix W assembled from them, whose entries couple every
/// two contacts on a fibre (with friction, every two of their reaction components) — both grow
/// with the square of the contacts per fibre — and the finite elements of its fibres, which grow
/// with their unknowns.
struct MemoryNeed {
  double influence = 0.0;
  double compliance = 0.0;
  double finite_elements = 0.0;
  double total() const { return influence + compliance + finite_elements; }
};

/// What the finite elements of `unknowns` unknowns take at their peak (bytes): Gmsh's model while
/// it meshes them, the beams' matrices and MUMPS's factor of the Laplace matrix, and the blocks of
/// right-hand sides the influence matrices are solved in.
double finite_element_memory(double unknowns);

/// The need of `stations` contact stations and `sides` contacts acting on each fibre, and with
/// friction (`frictional` not empty) their reaction components there (1 + tangents each): G in
/// doubles twice (as the finite elements give it and packed for the sums over the processes), and
/// for W and its frictional form the triplets of their assembly and the matrices.
MemoryNeed contact_problem_memory(const std::vector<std::size_t>& stations,
                                  const std::vector<std::size_t>& sides,
                                  const std::vector<std::size_t>& frictional);

/// The memory (bytes) each process of `communicator` may take: what its machine has available
/// (Linux's MemAvailable, else the physical memory), shared among the processes on that machine,
/// less a tenth kept for everything else; the smallest over the processes, so that every process
/// decides alike.
double memory_within_reach(MPI_Comm communicator);

/// A progress line: what the contact problem will take against what there is.
std::string memory_line(const MemoryNeed& need, double within_reach);

/// The message of a scene beyond reach: what it would need against what there is.
/// `saddle_points`: the problem could be held as saddle points instead, whose memory grows with
/// the unknowns (ContactAssembly::saddle_point), and the message says how.
std::string beyond_reach_message(const MemoryNeed& need, double within_reach,
                                 const std::string& widest_fibre, std::size_t widest_stations,
                                 bool saddle_points = false);

}  // namespace fibrecheck
