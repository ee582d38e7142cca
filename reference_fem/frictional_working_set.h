#pragma once

#include <Eigen/Core>

#include "contact_compliance.h"
#include "frictional_contact.h"
#include "tresca_fixed_point.h"

namespace fibrecheck {

/// Coulomb's law at every candidate (tresca_fixed_point.h) with W formed only on a working set of
/// contacts. On a tow most candidates never push, and the whole frictional W, (1 + tangents)²
/// entries for every pair of contacts on a fibre, is several times the memory of the influence
/// matrices it comes from; W_SS of the contacts that push is a few per cent of it.
///
/// The working set starts as the contacts whose reaction `r` is not zero on entry (the frictionless
/// answer's pushing set, or the last frictional answer's), and the fixed point runs on the problem
/// restricted to it. After every inner problem, every candidate outside the set that its answer
/// leaves overlapping (w = q − W·r above `options.threshold` in its normal row) joins, and the
/// inner problem is solved again with it. The candidates outside the set carry no force and do not
/// overlap, so Coulomb's law holds at them too: the answer is the whole problem's. The fixed point
/// settles to the same slip as on the whole problem (1e-9 of the largest slip of the whole).
///
/// `compliance` is W, its rows the components of the reaction as `problem.offset` numbers them;
/// `problem.W` is not read. Every process must make the same calls (W may be shared out).
TrescaSolve tresca_on_working_set(const ContactCompliance& compliance,
                                  const FrictionalProblem& problem, const TrescaOptions& options,
                                  Eigen::VectorXd& r);

}  // namespace fibrecheck
