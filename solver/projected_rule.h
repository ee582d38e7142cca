#pragma once

#include <optional>

#include "force_update.h"

namespace fibrecheck {

/// The seed's rule as written (§4.3.2): P' = max(0, P + c·d) on every contact from the same state,
/// with the scene's c, taken as c/n per slice (Eq. 4.28) — rule `seed`; or with c = 1/λmax(W),
/// stable by construction — rule `auto`.
class ProjectedRule : public ForceUpdate {
 public:
  /// With `c` the seed's rule on that step (N/mm); without, rule auto.
  explicit ProjectedRule(std::optional<double> c) : c_(c) {}

  double step(double lambda_max) const override;
  bool weighted() const override { return c_.has_value(); }
  bool allows_working_set() const override { return !c_.has_value(); }
  long update(IterationState& state, const UpdateContext& context) override;

 private:
  std::optional<double> c_;
  Eigen::VectorXd next_;
  std::vector<Eigen::Vector3d> next_friction_;
};

}  // namespace fibrecheck
