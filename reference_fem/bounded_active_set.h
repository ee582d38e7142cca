#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "free_set_factor.h"

namespace fibrecheck {

struct BoundedSolve {
  bool solved = false;    ///< no bound left that the objective wants to leave
  bool singular = false;  ///< a free set whose system could not be solved even regularised
  int passes = 0;
  int free_solves = 0;  ///< systems of the free variables solved
};

/// The box-constrained QP min ½rᵀWr − qᵀr, lo ≤ r ≤ hi (W symmetric positive semi-definite), solved
/// exactly by a bounded-variable active-set method in the manner of Lawson–Hanson (Stark–Parker's
/// BVLS): variables are free or held at a bound; the free ones solve their equations W_FF·r_F =
/// q_F − W_FB·r_B; when one would leave its box the step stops at the first bound hit and the
/// variables that reach their bounds there are held; then the variables whose bound the objective
/// wants to leave (w = q − W·r beyond `tolerance` pointing inside) are freed, the most violating
/// first, and the passes repeat. Each pass lowers the objective, so no set returns and the method
/// ends. `lo[i] = hi[i]` fixes a variable. `r` holds a start on entry (clamped into the box; the
/// variables strictly inside it start free) and the answer on return. This is the Tresca problem of
/// friction with one tangent per contact: P ≥ 0 and |F| ≤ g, a box. nonnegative_active_set solves
/// the frictionless problem, this one's box [0, ∞); the two stay apart because each one's order of
/// passes, block additions and set-aside rule fix the answers it gives: there every frictionless
/// answer to the last bit, here the friction answers, which need not be unique.
BoundedSolve bounded_active_set(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                double tolerance, int max_passes, Eigen::VectorXd& r);

/// The same with the free set's factor kept from an earlier solve with the same W (the inner
/// problems of a Tresca fixed point differ only in their bounds): a warm start then modifies the
/// factor by the variables whose state changed instead of factorising afresh.
BoundedSolve bounded_active_set(FreeSetFactor& factor, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                double tolerance, int max_passes, Eigen::VectorXd& r);

}  // namespace fibrecheck
