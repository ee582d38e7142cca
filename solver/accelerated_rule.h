#pragma once

#include "force_update.h"

namespace fibrecheck {

/// Rule `accelerated`: the projected step of rule auto (c = 1/λmax(W)) followed by Nesterov's
/// momentum, P ← max(0, P' + β·(P' − P_{k−1})) (and the friction forces alike, onto their disks),
/// restarted when the step has pointed uphill, −(d, s)·(P' − P_k) > 0, on `kRestartStreak`
/// updates in a row. Single uphill steps come and go as force-free contacts turn and open, so a
/// restart on each would throw momentum away too often.
class AcceleratedRule : public ForceUpdate {
 public:
  double step(double lambda_max) const override;
  bool allows_working_set() const override { return true; }
  long update(IterationState& state, const UpdateContext& context) override;
  void restart(IterationState& state) override;

 private:
  static constexpr int kRestartStreak = 20;
  double momentum_t_ = 1.0;
  int uphill_streak_ = 0;
  Eigen::VectorXd next_;
  std::vector<Eigen::Vector3d> next_friction_;
};

}  // namespace fibrecheck
