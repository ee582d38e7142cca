#include "force_update.h"

#include "accelerated_rule.h"
#include "cg_rule.h"
#include "projected_rule.h"

namespace fibrecheck {

std::unique_ptr<ForceUpdate> make_force_update(UpdateRule rule, std::optional<double> c,
                                               const Superposition& superposition,
                                               const std::vector<Fibre>& fibres,
                                               const IterationState& state) {
  switch (rule) {
    case UpdateRule::seed:
      return std::make_unique<ProjectedRule>(c);
    case UpdateRule::automatic:
      return std::make_unique<ProjectedRule>(std::nullopt);
    case UpdateRule::accelerated:
      return std::make_unique<AcceleratedRule>();
    case UpdateRule::conjugate_gradient:
      return std::make_unique<CgRule>(superposition, fibres, state);
  }
  return nullptr;
}

}  // namespace fibrecheck
