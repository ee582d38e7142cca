#include "projected_rule.h"

#include "projected_step.h"

namespace fibrecheck {

double ProjectedRule::step(double lambda_max) const {
  if (c_) return *c_;
  return lambda_max > 0.0 ? 1.0 / lambda_max : 0.0;
}

long ProjectedRule::update(IterationState& state, const UpdateContext& context) {
  projected_step(state, context, weighted(), false, next_, next_friction_);
  apply_forces(state, context, next_, next_friction_);
  return 1;
}

}  // namespace fibrecheck
