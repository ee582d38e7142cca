#include "compliance_operator.h"

#include <cmath>

#include "beam.h"

namespace fibrecheck {

void ComplianceOperator::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const std::size_t n = contacts_.size();
  const int m = components();
  std::vector<Eigen::Vector3d> force_on_a(n), u_a, u_b;
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const double scale = weighted_ ? std::sqrt(c.weight) : 1.0;
    const double P = scale * x[m * k];
    force_on_a[k] = (c.kind == ContactKind::wall ? P : -P) * c.normal;
    if (m == 3 && c.tangents >= 1) force_on_a[k] += scale * x[m * k + 1] * c.tangent;
    if (m == 3 && c.tangents == 2) force_on_a[k] += scale * x[m * k + 2] * c.second_tangent();
  }
  superposition_.contact_displacements(contacts_, force_on_a, false, u_a, u_b);
  y.setZero(static_cast<Eigen::Index>(m * n));
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts_[k];
    const double scale = weighted_ ? std::sqrt(c.weight) : 1.0;
    const Eigen::Vector3d relative = c.relative(u_a[k], u_b[k]);
    // The overlap P removes: n·(u_B − u_A), or n·u_A for a fibre pushed off a wall.
    y[m * k] = scale * c.normal.dot(c.kind == ContactKind::wall ? u_a[k] : relative);
    // A tangential force on A removes slip: its part of W is −t·(u_B − u_A).
    if (m == 3 && c.tangents >= 1) y[m * k + 1] = -scale * c.tangent.dot(relative);
    if (m == 3 && c.tangents == 2) y[m * k + 2] = -scale * c.second_tangent().dot(relative);
  }
}

double ComplianceOperator::largest_eigenvalue(int max_iterations, double tolerance) const {
  const Eigen::Index n = static_cast<Eigen::Index>(components() * contacts_.size());
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
