#include "slicing_estimate.h"

#include <cmath>

#include "metrics.h"

namespace fibrecheck {

SlicingEstimate estimate_slicing_error(const Result& fine, const Result& coarse, int fine_slices,
                                       int coarse_slices, const SlicingOrders& orders) {
  const Errors difference = measure_errors(coarse, fine, "slicing estimate").errors;
  const double ratio = static_cast<double>(fine_slices) / coarse_slices;
  auto extrapolate = [ratio](double d, double p) { return d / (std::pow(ratio, p) - 1.0); };
  SlicingEstimate e;
  e.deflection = extrapolate(difference.deflection, orders.deflection);
  e.force = extrapolate(difference.force, orders.force);
  e.energy = extrapolate(difference.energy, orders.energy);
  e.slices = fine_slices;
  e.coarse_slices = coarse_slices;
  e.deflection_order = orders.deflection;
  e.force_order = orders.force;
  e.energy_order = orders.energy;
  e.time_s = coarse.wall_time_s;
  return e;
}

void observe_slicing_orders(SlicingEstimate& e, const Result& fine, const Result& coarse,
                            const Result& coarser, int coarser_slices) {
  const Errors near = measure_errors(coarse, fine, "slicing estimate").errors;
  const Errors far = measure_errors(coarser, coarse, "slicing estimate").errors;
  const double ratio = static_cast<double>(e.slices) / e.coarse_slices;
  auto order = [ratio](double d_near, double d_far) {
    return d_near > 0.0 && d_far > 0.0 ? std::log(d_far / d_near) / std::log(ratio) : NAN;
  };
  e.coarser_slices = coarser_slices;
  e.observed_deflection_order = order(near.deflection, far.deflection);
  e.observed_force_order = order(near.force, far.force);
  e.observed_energy_order = order(near.energy, far.energy);
  e.time_s += coarser.wall_time_s;
}

bool slicing_orders_hold(const SlicingEstimate& e) {
  auto holds = [](double observed, double assumed, double estimate) {
    return !std::isfinite(observed) || estimate < 1e-12 ||
           (observed > 0.5 * assumed && observed < 2.0 * assumed);
  };
  return holds(e.observed_force_order, e.force_order, e.force) &&
         holds(e.observed_deflection_order, e.deflection_order, e.deflection);
}

}  // namespace fibrecheck
