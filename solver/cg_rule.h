#pragma once

#include "fibre_stiffness.h"
#include "force_update.h"
#include "superposition.h"

namespace fibrecheck {

/// Rule `cg` (frictionless only): each candidate list's quadratic programme min ½PᵀWP − d₀ᵀP over
/// P ≥ 0 solved at once by projected conjugate gradients (projected_cg.h), preconditioned by the
/// fibres' exact beam stiffness at the loaded stations (fibre_stiffness.h); the loop then measures
/// the overlaps afresh through the superposition. An update costs as many iterations as it
/// applied W.
class CgRule : public ForceUpdate {
 public:
  CgRule(const Superposition& superposition, const std::vector<Fibre>& fibres,
         const IterationState& state)
      : superposition_(superposition), stiffness_(fibres), state_(state) {}

  double step(double lambda_max) const override;
  bool solves_each_list() const override { return true; }
  void attach(const std::vector<Contact>& contacts) override { stiffness_.attach(contacts); }
  long update(IterationState& state, const UpdateContext& context) override;

 private:
  const Superposition& superposition_;
  FibreStiffness stiffness_;
  const IterationState& state_;  ///< whose contacts W is applied on
  Eigen::VectorXd P_, g_;
};

}  // namespace fibrecheck
