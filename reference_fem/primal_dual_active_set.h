#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact_compliance.h"
#include "nonnegative_active_set.h"

namespace fibrecheck {

/// The frictionless contact problem P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 by the primal–dual active set
/// (a semismooth Newton method on min(P, −d) = 0): solve W_SS·P_S = d0_S on the guessed set S,
/// then take as the next set the contacts of S whose force is positive and those outside it that
/// overlap by more than `tolerance` (mm), until the set stays. Each pass changes any number of
/// contacts, so where it converges it takes a handful of passes where nonnegative_active_set takes
/// one per block it adds and per contact it drops — what matters when each solve is a
/// factorisation of the whole finite-element system (saddle_point_compliance.h). It need not
/// converge when W is not an M-matrix (it can cycle between sets): it stops on the first set that
/// comes back or after `max_passes`, with `solved` false and the last set in `pushing`, for
/// nonnegative_active_set to finish from. Contacts marked in `excluded` are never in a set.
ActiveSetSolve primal_dual_active_set(const ContactCompliance& W, const Eigen::VectorXd& d0,
                                      double tolerance, const std::vector<char>& excluded,
                                      int max_passes, Eigen::VectorXd& P,
                                      std::vector<char>& pushing);

}  // namespace fibrecheck
