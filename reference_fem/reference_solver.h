#pragma once

#include <mpi.h>

#include <functional>
#include <string>

#include "beam_model.h"
#include "contact_problem.h"
#include "fibre_mesh.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// How line contacts (slices between nearly parallel fibres, fibre–wall stations) are enforced.
enum class LineContact {
  slices,     ///< at the same n slice midpoints as the iterative solver
  continuous  ///< at the two Gauss points of n·2^K cells: the line contact itself as K grows
};

/// How the reference holds its contact problem.
enum class ContactAssembly {
  /// The compliance matrix W, assembled from each fibre's dense influence matrix in its contact
  /// stations, held whole by every process: memory grows with the square of the contacts on a
  /// fibre. Friction, the contact problem handed to outside solvers and the beam solver cg_amg
  /// take this one.
  compliance_matrix,
  /// W never formed: products by finite-element solves and the active set's systems as saddle
  /// points of the beams and the contacts' constraint rows, solved by MUMPS over the processes
  /// (saddle_point_compliance.h): memory linear in the unknowns and shared out. Frictionless.
  saddle_point
};

struct ReferenceOptions {
  LineContact line_contact = LineContact::slices;
  /// Refinements: elements (and in continuous mode the Gauss cells) are 2^refine times smaller.
  /// In continuous mode it may be negative, down to coarsest_refinement(scene): n/2^-K cells.
  int refine = 0;
  /// Continuous mode: refine once more (from the coarsest refinement, or `refine` if lower) until
  /// the summed line and wall contact force, extrapolated (Richardson, with the order observed on
  /// the last three refinements), is known to `refinement_tolerance` (relative; two successive
  /// extrapolations agree), at most up to `max_refine`. Line and wall pairs then carry their
  /// extrapolated force, and the result its order and error estimate.
  bool refine_until_converged = false;
  double refinement_tolerance = 1e-4;
  int max_refine = 8;
  /// MUMPS (exact to round-off) or CG with BoomerAMG (relative residual 1e-14), for large tows.
  BeamSolver beam_solver = BeamSolver::direct;
  /// Degree of the beam elements: 2 (exact at the nodes and for the moments of uniform loads) or
  /// 1 (linear, for studies of the finite element itself).
  unsigned int degree = 2;
  ContactAssembly contact_assembly = ContactAssembly::compliance_matrix;
  int max_outer_iterations = 30;
  int max_active_set_iterations = 100000;
  /// The beams' solution as a ParaView .vtu file (with several processes, one .vtu per process
  /// and a .pvtu that collects them); empty: none.
  std::string vtu;
  /// Receives a line after every outer iteration (progress); may be empty.
  std::function<void(const std::string&)> progress;
  /// The processes that share the fibres (every one ends with the same result).
  MPI_Comm communicator = MPI_COMM_WORLD;
  /// Prints the wall time of each phase at the end (deal.II's TimerOutput), on the first process.
  bool print_timing = false;
  /// Receives each load step's contact problem as last solved, with the answer and the step's
  /// status, on every process (for solvers outside fibrecheck; may be empty).
  std::function<void(const ContactProblem&)> contact_problem;
};

/// The implicit reference (DESIGN §3): the fibres as finite-element beams (BeamModel) and every
/// contact solved at once, exactly, as the complementarity problem P ≥ 0, d = d0 − W·P ≤ 0,
/// P·d = 0 — d0 and W from finite-element solutions, the problem solved by an active-set method
/// (no penalty parameter in the answer). An outer loop re-detects the contact candidates on the
/// deformed finite-element fibres (with the contact model shared with the iterative solver),
/// re-meshes, and stops when the candidates and the active set no longer change. Every number it
/// reports — displacements, energies, the dropped axial load — comes from its own finite elements.
/// With friction (μ > 0) the same problem is solved with Coulomb's law, exactly, per load step
/// (frictional_contact.h).
///
/// Runs on every process of `options.communicator` (MPI must be initialised): the fibres are
/// shared out among the processes, each meshes and solves its own, and every process ends with the
/// same result.
Result solve_reference(const Scene& scene, const ReferenceOptions& options = {});

/// The Gauss cells of the continuous line contact at refinement K: n·2^K for the scene's n slices.
int continuous_cells(const Scene& scene, int K);

/// Debian's OpenBLAS (which MUMPS and PETSc call) starts a thread per core in every process; with
/// several processes on one machine that oversubscribes its cores. This gives each process of
/// `communicator` its share of the cores on its machine (at least one thread) when OpenBLAS is the
/// BLAS and would use more; solve_reference calls it.
void share_cores_with_blas(MPI_Comm communicator);

/// The coarsest refinement K ≤ 0 of the continuous line contact: n/2^-K cells, whole, at least 4
/// and at most 4 times fewer than the scene's slices. The line force converges at first order, so
/// its extrapolation needs four refinements; starting them below n keeps the finest one small
/// enough that its compliance matrix (condition growing with the fourth power of the points: a
/// smooth beam kernel) can still be solved to the round-off of the finite elements.
int coarsest_refinement(const Scene& scene);

/// The finest refinement K whose continuous line contact, 2·n·2^K Gauss points along a line for the
/// scene's n slices, stays within `points` (the influence matrices are dense per fibre: memory and
/// time grow with its square).
int finest_refinement(const Scene& scene, long points = 2048);

/// The mesh options of the reference's first outer iteration (what `fibrecheck mesh` writes): nodes
/// at the contact candidates of the fibres under the scene's loads, refined there, and at the
/// result's sample positions.
MeshOptions reference_mesh_options(const Scene& scene, const ReferenceOptions& options = {});

}  // namespace fibrecheck
