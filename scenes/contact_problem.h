#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace fibrecheck {

/// One contact of an exported contact problem: what it joins and how many tangents it has.
struct ProblemContact {
  std::string kind;                 ///< "point", "line" or "wall", as in the result files
  std::vector<std::string> fibres;  ///< one name for a wall contact, two otherwise
  int tangents = 0;                 ///< 0 frictionless, 1 slices and walls, 2 crossings
  bool excluded = false;            ///< both sides pinned: nothing can move, no reaction
};

/// The contact problem of one load step, as the reference solved it, for solvers outside
/// fibrecheck (file format "fibrecheck-contact-problem", DESIGN §3). The unknowns are the
/// reactions r, per contact its normal force P (N) then its friction force along each of its
/// tangents (N); `offset[j]` is contact j's first unknown. With w = q − W·r — per contact the
/// overlap left (mm) then the slip left along each tangent (mm) — a solution satisfies at every
/// contact that is not excluded
///   P ≥ 0, w_n ≤ 0, P·w_n = 0;  |F| ≤ μP;  |F| < μP ⇒ w_t = 0;  |F| = μP ⇒ w_t = λF, λ ≥ 0,
/// and an excluded contact has r = 0. W is the frictional compliance (Delassus) matrix of the
/// finite elements, symmetric positive semi-definite, q the overlaps and slips with no contact
/// force. μ = 0 gives every contact 0 tangents: the linear complementarity problem of DESIGN §3.
struct ContactProblem {
  std::string scene;
  int step = 1;  ///< the load step (1 without a load path)
  double mu = 0.0;
  std::vector<ProblemContact> contacts;
  std::vector<Eigen::Index> offset;  ///< contacts.size() + 1 entries
  Eigen::SparseMatrix<double> W;
  Eigen::VectorXd q;
  /// The reference's answer and its status ("converged", ...), empty when not solved.
  Eigen::VectorXd reaction;
  std::string status;
};

/// Sets `offset` from the contacts' tangents.
void set_offsets(ContactProblem& problem);

/// Writes the problem as JSON (W as its non-zero triplets), atomically.
void write_contact_problem(const std::string& path, const ContactProblem& problem);

/// Reads a problem written by write_contact_problem; throws InputError naming the file and field
/// when it is not one (sizes that disagree, a non-symmetric W, values that are not finite).
ContactProblem read_contact_problem(const std::string& path);

}  // namespace fibrecheck
