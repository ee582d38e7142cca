#include "accelerated_rule.h"

#include <algorithm>
#include <cmath>

#include "parallel_work.h"
#include "projected_step.h"

namespace fibrecheck {

double AcceleratedRule::step(double lambda_max) const {
  return lambda_max > 0.0 ? 1.0 / lambda_max : 0.0;
}

long AcceleratedRule::update(IterationState& state, const UpdateContext& context) {
  const Eigen::Index n = static_cast<Eigen::Index>(state.contacts.size());
  const double uphill = projected_step(state, context, false, true, next_, next_friction_);
  uphill_streak_ = uphill > 0.0 ? uphill_streak_ + 1 : 0;
  const bool restart = uphill_streak_ >= kRestartStreak;
  if (restart) uphill_streak_ = 0, momentum_t_ = 1.0;
  const double t_next = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum_t_ * momentum_t_));
  const double beta = (momentum_t_ - 1.0) / t_next;
  momentum_t_ = restart ? 1.0 : t_next;
  state.previous.swap(state.iterate);  // P_{k−1} ← P_k, without copying
  state.iterate.swap(next_);           // P_k ← P'
  next_.resize(n);
  const Eigen::VectorXd& iterate = state.iterate;
  const Eigen::VectorXd& previous = state.previous;
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (Eigen::Index k = 0; k < n; ++k)
    next_[k] = std::max(0.0, iterate[k] + beta * (iterate[k] - previous[k]));
  if (context.coulomb) {
    state.previous_friction.swap(state.friction_iterate);
    state.friction_iterate.swap(next_friction_);
    next_friction_.resize(n);
    for (Eigen::Index k = 0; k < n; ++k)
      next_friction_[k] =
          onto_coulomb_disk(state.contacts[static_cast<std::size_t>(k)].tangential(
                                state.friction_iterate[k] +
                                beta * (state.friction_iterate[k] - state.previous_friction[k])),
                            state.bound[k]);
  }
  apply_forces(state, context, next_, next_friction_);
  return 1;
}

void AcceleratedRule::restart(IterationState& state) {
  momentum_t_ = 1.0;
  state.previous = state.iterate;
  state.previous_friction = state.friction_iterate;
}

}  // namespace fibrecheck
