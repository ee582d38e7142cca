#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace fibrecheck {

/// The frictional contact problem of one load step (DESIGN §2–3), in the reaction r of every
/// contact: its normal force P and its friction force along its tangents (one for slices and
/// walls, two for crossings), `offset[j]` the index of contact j's P and offset[j + 1] − 1 of its
/// last tangent. W is the frictional Delassus operator from the finite elements: (W·r) is the
/// overlap and the slip the reaction removes; q the overlap and slip with no contact force. A
/// solution satisfies Coulomb's law at every contact with w = q − W·r = (d, s):
///   P ≥ 0, d ≤ 0, P·d = 0;  |F| ≤ μP;  |F| < μP ⇒ s = 0;  |F| = μP ⇒ s = λF, λ ≥ 0.
struct FrictionalProblem {
  Eigen::SparseMatrix<double> W;
  Eigen::VectorXd q;
  std::vector<Eigen::Index> offset;
  double mu = 0.0;
  /// Contacts nothing can move (both sides pinned): no reaction.
  std::vector<char> excluded;
  /// Tresca's law instead of Coulomb's where given: contact j's disk radius is bounds[j] (N),
  /// whatever its normal force (the inner problem of a Tresca fixed point, a convex QP).
  Eigen::VectorXd bounds;
};

struct FrictionalSolve {
  bool settled = false;  ///< the residual reached the tolerance
  int newton_steps = 0;
  double residual = 0.0;  ///< mm, the largest violation of Coulomb's law left (as ‖Φ_j‖/ρ_j)
  bool singular = false;  ///< a Newton system could not be solved even regularised
  int stalled_steps = 0;  ///< steps where no fraction of the Newton step lowered ‖Φ‖
};

/// Solves the problem exactly by a semismooth Newton method on the natural map of Coulomb's law
/// (the Alart–Curnier form): Φ_j(r) = r_j − proj_j(r_j + ρ_j w_j), proj_j taking the normal part
/// to max(0, ·) and the tangential part onto the disk of radius μ times it, ρ_j = 1/W_jj. Its
/// zeros are the solutions; on a fixed set of open, sticking and slipping contacts Φ is linear for
/// one tangent (slices, walls), so the method ends with the exact answer once the set is right;
/// for two tangents (crossings) it converges quadratically. Each step solves the system of
/// the closed contacts by a sparse LU (it is as sparse as W); a backtracking search on ‖Φ‖
/// globalises it. `r` holds the start (for example the frictionless answer) on entry and the answer
/// on return; `tolerance` is in mm.
FrictionalSolve solve_frictional(const FrictionalProblem& problem, double tolerance, int max_steps,
                                 Eigen::VectorXd& r);

}  // namespace fibrecheck
