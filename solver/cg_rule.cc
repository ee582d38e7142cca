#include "cg_rule.h"

#include <algorithm>

#include "compliance_operator.h"
#include "projected_cg.h"

namespace fibrecheck {

double CgRule::step(double lambda_max) const {
  return lambda_max > 0.0 ? 1.0 / lambda_max : 0.0;
}

long CgRule::update(IterationState& state, const UpdateContext& context) {
  ContactQuadraticProgramme problem;
  problem.compliance = [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    ComplianceOperator(superposition_, state_.contacts).apply(x, y);
  };
  problem.preconditioner = [this](const Eigen::VectorXd& r, const std::vector<unsigned char>& free,
                                  Eigen::VectorXd& z) { stiffness_.apply(r, free, z); };
  problem.largest_eigenvalue = context.lambda_max;
  const Eigen::Index n = static_cast<Eigen::Index>(state.contacts.size());
  P_.resize(n);
  g_.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    P_[k] = state.contacts[k].force;
    g_[k] = -state.contacts[k].overlap;
  }
  // Half the tolerance by the recurrence, so that the overlaps measured afresh meet it.
  const ProjectedCgOutcome outcome =
      solve_by_projected_cg(problem, P_, g_, 0.5 * context.tolerance, context.max_products);
  for (Eigen::Index k = 0; k < n; ++k) state.contacts[k].force = P_[k];
  state.forces_gathered = false;
  return std::max(1L, outcome.compliance_products);
}

}  // namespace fibrecheck
