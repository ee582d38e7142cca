#include "convergence.h"

#include <algorithm>
#include <cmath>

#include "parallel_work.h"

namespace fibrecheck {

Residuals measure_residuals(const std::vector<Contact>& contacts) {
  Residuals r;
  double max_overlap = contacts.empty() ? 0.0 : -INFINITY, gap_force = 0.0;
  int non_finite = 0;
  const int n = static_cast<int>(contacts.size());
#pragma omp parallel for schedule(static) reduction(max : max_overlap, gap_force) \
    reduction(+ : non_finite) if (n > kParallelContacts)
  for (int k = 0; k < n; ++k) {
    const Contact& c = contacts[k];
    if (!std::isfinite(c.overlap)) ++non_finite;
    max_overlap = std::max(max_overlap, c.overlap);
    if (c.force > 0.0) gap_force = std::max(gap_force, -c.overlap);
  }
  // max() passes a NaN over: a non-finite overlap makes the residuals non-finite instead, so the
  // solver reports it rather than reading it as converged.
  if (non_finite > 0) max_overlap = NAN;
  r.max_overlap = max_overlap;
  r.gap_force = non_finite > 0 ? NAN : gap_force;
  r.overlap = non_finite > 0 ? NAN : std::max(0.0, r.max_overlap);
  return r;
}

bool EnergyWindow::push(double energy) {
  energies_.push_back(energy);
  if (static_cast<int>(energies_.size()) > window_ + 1) energies_.pop_front();
  if (tolerance_ <= 0.0 || static_cast<int>(energies_.size()) < window_ + 1) return false;
  // Written so that a NaN or infinite energy is never "within t_U".
  for (double e : energies_)
    if (!(std::fabs(e - energy) <= tolerance_)) return false;
  return true;
}

DivergenceMonitor::Verdict DivergenceMonitor::observe(long iteration, double residual) {
  if (first_ < 0.0) first_ = std::max(residual, tolerance_);
  if (residual > std::max(extent_, 1e2 * first_)) return Verdict::growth;
  if (reference_ < 0.0) {
    const double scene = std::isfinite(extent_) ? kReferenceOfExtent * extent_ : 0.0;
    reference_ = std::max({residual, tolerance_, scene});
    best_ = residual;
    best_iteration_ = iteration;
    return Verdict::fine;
  }
  if (residual > 1e4 * reference_) return Verdict::growth;
  if (residual < best_) {
    best_ = residual;
    best_iteration_ = iteration;
  }
  const long patience = unstable_step_ ? 200L : std::max(5000L, iteration / 5);
  if (iteration - best_iteration_ > patience) return Verdict::stalled;
  return Verdict::fine;
}

}  // namespace fibrecheck
