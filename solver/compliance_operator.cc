#include "compliance_operator.h"

#include <cmath>

#include "beam.h"

namespace fibrecheck {

void ComplianceOperator::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const std::size_t n = contacts_.size();
  std::vector<Eigen::Vector3d> force_on_a(n), u_a, u_b;
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const double xk = weighted_ ? std::sqrt(c.weight) * x[k] : x[k];
    force_on_a[k] = (c.kind == ContactKind::wall ? xk : -xk) * c.normal;
  }
  superposition_.contact_displacements(contacts_, force_on_a, false, u_a, u_b);
  y.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    y[k] = c.kind == ContactKind::wall ? c.normal.dot(u_a[k]) : c.normal.dot(u_b[k] - u_a[k]);
    if (weighted_) y[k] *= std::sqrt(c.weight);
  }
}

double ComplianceOperator::largest_eigenvalue(int max_iterations, double tolerance) const {
  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  if (n == 0) return 0.0;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n) / std::sqrt(static_cast<double>(n)), y;
  double lambda = 0.0;
  for (int it = 0; it < max_iterations; ++it) {
    apply(x, y);
    const double next = x.dot(y);  // Rayleigh quotient, ‖x‖ = 1
    const double norm = y.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return std::max(lambda, next);
    x = y / norm;
    if (it > 2 && std::fabs(next - lambda) <= tolerance * std::fabs(next)) return next;
    lambda = next;
  }
  return lambda;
}

double self_compliance(const Contact& c, const std::vector<Fibre>& fibres) {
  auto along = [&](int f, double s) {
    const Fibre& fibre = fibres[f];
    const double axial = c.normal.dot(fibre.t);
    return point_compliance(s * fibre.length, fibre.length, fibre.EI) * (1.0 - axial * axial);
  };
  double w = along(c.a, c.s_a);
  if (c.kind != ContactKind::wall) w += along(c.b, c.s_b);
  return w;
}

}  // namespace fibrecheck
