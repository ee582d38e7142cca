#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace fibrecheck {

/// The frictionless contact problem of one candidate list as the quadratic programme it is:
/// minimise ½·Pᵀ·W·P − d₀ᵀ·P over P ≥ 0, whose gradient W·P − d₀ is minus the overlaps d of
/// §4.3.2 (d = d₀ − W·P with the normals of the undeformed fibres). Its optimality conditions are
/// the contact conditions: d ≤ 0, P ≥ 0, P·d = 0.
struct ContactQuadraticProgramme {
  /// y = W·x.
  std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)> compliance;
  /// z ≈ W_FF⁻¹·r on the free contacts F (`free[k]`), zero elsewhere.
  std::function<void(const Eigen::VectorXd& r, const std::vector<unsigned char>& free,
                     Eigen::VectorXd& z)>
      preconditioner;
  double largest_eigenvalue = 0.0;  ///< of W, for the projected steps
};

struct ProjectedCgOutcome {
  long compliance_products = 0;  ///< applications of W: the cost, comparable to iterations
  double residual = 0.0;         ///< of the last iterate, by the recurrence (mm)
  bool finite = true;
};

/// The residual the solver's criteria watch (§4.3.6), from the gradient g = −d: the largest
/// overlap (d > 0 anywhere) or gap where a force pushes (d < 0 with P > 0), mm.
double contact_residual(const Eigen::VectorXd& P, const Eigen::VectorXd& g);

/// Dostál's MPRGP (modified proportioning with reduced gradient projections, preconditioned in
/// face): conjugate gradients on the contacts that push, with the preconditioner restricted to
/// them; a step that would open a contact is cut at the bound and followed by a projected gradient
/// step of 1/λmax (expansion); when the contacts held at zero force would gain more than the free
/// ones (the proportioning test), a line search along their part of the gradient adds them.
/// Each step lowers the energy, so the method cannot cycle; it converges for any positive
/// definite W, in a number of steps that follows the preconditioned condition number.
///
/// `P` (forces, N, ≥ 0) and `g` = W·P − d₀ (mm) are the start and are updated in place. Stops when
/// `contact_residual` < `tolerance` by the recurrence, after `max_products` applications of W, or
/// on a non-finite value.
ProjectedCgOutcome solve_by_projected_cg(const ContactQuadraticProgramme& problem,
                                         Eigen::VectorXd& P, Eigen::VectorXd& g, double tolerance,
                                         long max_products);

}  // namespace fibrecheck
