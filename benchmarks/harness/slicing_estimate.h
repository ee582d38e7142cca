#pragma once

#include "result.h"

namespace fibrecheck {

/// The orders at which the slice study sees a line contact's errors fall with the number of
/// slices n (error ∝ n^−p) on fibres that touch along their whole length: first in the line
/// force, fourth in deflection and strain energy.
struct SlicingOrders {
  double deflection = 4.0;
  double force = 1.0;
  double energy = 4.0;
};

/// The slicing error of `fine` (a result at `fine_slices` slices) estimated from `coarse`, the
/// same scene at `coarse_slices` < `fine_slices`: if each error falls as n^−p, the difference of
/// the two runs is the fine run's error times (n_fine/n_coarse)^p − 1 (Richardson). The
/// difference is measured as the comparison measures errors (DESIGN §6), with the fine run as the
/// truth. It assumes the orders hold from `coarse_slices` on, and that the two runs' own iteration
/// errors are small beside the difference.
SlicingEstimate estimate_slicing_error(const Result& fine, const Result& coarse, int fine_slices,
                                       int coarse_slices, const SlicingOrders& orders = {});

/// Checks the assumed orders with a third run, `coarser` at `coarser_slices` ≈ coarse²/fine: where
/// the errors fall as n^−p the differences of successive runs shrink by (n_fine/n_coarse)^p, and
/// that ratio gives the observed order of each metric (NaN where a difference is zero).
void observe_slicing_orders(SlicingEstimate& estimate, const Result& fine, const Result& coarse,
                            const Result& coarser, int coarser_slices);

/// Whether the observed orders of deflection and force lie within a factor of two of the
/// assumed ones (true where nothing was observed, or the differences are at round-off).
bool slicing_orders_hold(const SlicingEstimate& estimate);

}  // namespace fibrecheck
