#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contact_compliance.h"

namespace fibrecheck {

struct ActiveSetSolve {
  bool solved = false;    ///< no contact left outside the set that overlaps
  bool singular = false;  ///< a single contact added made the set's system singular
  int passes = 0;
};

/// The frictionless contact problem P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 (DESIGN §3) is the quadratic
/// programme min ½PᵀWP − Pᵀd0 over P ≥ 0, solved exactly by an active-set method in the manner of
/// Lawson–Hanson's non-negative least squares: add the contacts that overlap most (by more than
/// `tolerance`, mm) to the set of pushing contacts, solve W_SS·P_S = d0_S, step back to
/// feasibility when a force would turn negative (dropping the contact that blocks), and repeat. A
/// pass that adds one contact lowers the objective strictly, so no set comes back and the method
/// ends in a finite number of passes (the plain primal–dual active set cycles on a dense W).
///  - Passes add blocks of the most overlapping contacts, at most max(8, |set|): a big block of
///    contacts that mostly will not push costs one solve per contact dropped again. When a block
///    gains nothing or makes the set singular (two walls in one plane), the next pass adds one.
///  - A single contact that gains nothing (round-off decides it) is set aside until P changes.
///  - Contacts marked in `excluded` (nothing can move them) are never added.
/// `pushing` holds a first guess of the set (the last outer iteration's) on entry and the final
/// set on return; `P` (N) the answer. bounded_active_set, which would take P ≥ 0 as the box
/// [0, ∞), solves friction's Tresca problems; the two stay apart because each one's order of
/// passes, block additions and set-aside rule fix the answers it gives: here every frictionless
/// answer to the last bit, there the friction answers, which need not be unique.
ActiveSetSolve nonnegative_active_set(const ContactCompliance& W, const Eigen::VectorXd& d0,
                                      double tolerance, const std::vector<char>& excluded,
                                      int max_passes, Eigen::VectorXd& P,
                                      std::vector<char>& pushing);
/// The same with W assembled.
ActiveSetSolve nonnegative_active_set(const Eigen::SparseMatrix<double>& W,
                                      const Eigen::VectorXd& d0, double tolerance,
                                      const std::vector<char>& excluded, int max_passes,
                                      Eigen::VectorXd& P, std::vector<char>& pushing);

}  // namespace fibrecheck
