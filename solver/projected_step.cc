#include "projected_step.h"

#include <algorithm>

#include "friction.h"
#include "parallel_work.h"

namespace fibrecheck {

double projected_step(const IterationState& state, const UpdateContext& context, bool weighted,
                      bool restart_test, Eigen::VectorXd& next,
                      std::vector<Eigen::Vector3d>& next_friction) {
  const Eigen::Index n = static_cast<Eigen::Index>(state.contacts.size());
  const Contact* const contact = state.contacts.data();
  const bool coulomb = context.coulomb;
  next.resize(n);
  if (coulomb) next_friction.resize(n);
  Eigen::Vector3d* const friction = next_friction.data();
  const double* const bound = state.bound.data();
  constexpr Eigen::Index kBlock = 8192;
  const Eigen::Index blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> uphill_part(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (Eigen::Index b = 0; b < blocks; ++b) {
    double part = 0.0;
    for (Eigen::Index k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
      const Contact& c = contact[k];
      const double step = weighted ? context.step * c.weight : context.step;
      next[k] = std::max(0.0, c.force + step * c.overlap);
      if (restart_test) part += -c.overlap * (next[k] - state.iterate[k]);
      if (!coulomb) continue;
      friction[k] = onto_coulomb_disk(c.friction + step * c.slip, bound[k]);
      if (restart_test) part += -c.slip.dot(friction[k] - state.friction_iterate[k]);
    }
    uphill_part[b] = part;
  }
  double uphill = 0.0;
  for (double part : uphill_part) uphill += part;
  return uphill;
}

void apply_forces(IterationState& state, const UpdateContext& context, const Eigen::VectorXd& next,
                  const std::vector<Eigen::Vector3d>& next_friction) {
  const Eigen::Index n = static_cast<Eigen::Index>(state.contacts.size());
  Contact* const contact = state.contacts.data();
  const bool coulomb = context.coulomb;
  const bool seed_friction = context.seed_friction;
  const double mu = context.mu;
  const ContactGeometry& geometry = *context.geometry;
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (Eigen::Index k = 0; k < n; ++k) {
    Contact& c = contact[k];
    if (coulomb) c.friction = next_friction[k];
    if (seed_friction)
      c.friction = coulomb_capped_friction(state.force_on_a[k],
                                           geometry.deformed_normal(c, state.u_a[k], state.u_b[k]),
                                           next[k], mu);
    c.force = next[k];
    state.force_on_a[k] = c.force_on_a();
  }
  state.forces_gathered = true;
}

}  // namespace fibrecheck
