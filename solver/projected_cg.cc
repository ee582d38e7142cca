#include "projected_cg.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecheck {

namespace {

using Eigen::Index;
using Eigen::VectorXd;

// Sums in fixed blocks, added in order: the same result with any number of threads, so that the
// iteration takes the same path on one core as on two.
constexpr Index kBlock = 8192;

Index block_count(Index n) {
  return (n + kBlock - 1) / kBlock;
}

double dot(const VectorXd& a, const VectorXd& b) {
  const Index n = a.size();
  const Index blocks = block_count(n);
  std::vector<double> part(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (Index i = 0; i < blocks; ++i) {
    const Index start = i * kBlock, size = std::min(n, start + kBlock) - start;
    part[i] = a.segment(start, size).dot(b.segment(start, size));
  }
  double sum = 0.0;
  for (double x : part) sum += x;
  return sum;
}

/// One pass over the contacts: which push (the free set F), the free gradient φ (g on F), the
/// chopped gradient β (min(g, 0) off F), ‖β‖², φ̃ᵀφ with the reduced free gradient
/// φ̃ = min(P/ᾱ, φ), and the contact residual.
struct Classification {
  double beta_squared = 0.0;
  double reduced_free = 0.0;
  double residual = 0.0;
};

Classification classify(const VectorXd& P, const VectorXd& g, double step,
                        std::vector<unsigned char>& free, VectorXd& phi, VectorXd& beta) {
  const Index n = P.size();
  const Index blocks = block_count(n);
  std::vector<Classification> part(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (Index b = 0; b < blocks; ++b) {
    Classification c;
    for (Index i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      const bool pushes = P[i] > 0.0;
      free[i] = pushes;
      phi[i] = pushes ? g[i] : 0.0;
      beta[i] = pushes ? 0.0 : std::min(g[i], 0.0);
      c.beta_squared += beta[i] * beta[i];
      c.reduced_free += std::min(P[i] / step, phi[i]) * phi[i];
      const double r = pushes ? std::fabs(g[i]) : -g[i];
      // Written so that a NaN is never below the tolerance.
      c.residual = !(r <= c.residual) ? r : c.residual;
    }
    part[b] = c;
  }
  Classification total;
  for (const Classification& c : part) {
    total.beta_squared += c.beta_squared;
    total.reduced_free += c.reduced_free;
    total.residual = !(c.residual <= total.residual) ? c.residual : total.residual;
  }
  return total;
}

}  // namespace

double contact_residual(const VectorXd& P, const VectorXd& g) {
  double residual = 0.0;
  for (Index i = 0; i < P.size(); ++i)
    residual = std::max(residual, P[i] > 0.0 ? std::fabs(g[i]) : -g[i]);
  return residual;
}

namespace {

/// The state of one solve: forces P and gradient g = W·P − d₀ (updated in place), the workspace,
/// and Nesterov's momentum of the projected steps (from y, its gradient g_y).
class ProjectedCg {
 public:
  ProjectedCg(const ContactQuadraticProgramme& problem, VectorXd& P, VectorXd& g, double tolerance,
              long max_products)
      : problem_(problem), P_(P), g_(g), tolerance_(tolerance), max_products_(max_products) {}

  ProjectedCgOutcome run();

 private:
  static constexpr double kGamma = 1.0;  ///< proportioning: β may be as large as the free gradient
  static constexpr int kSettled = 10;    ///< projected steps without a change of the free set

  double energy(const VectorXd& force, const VectorXd& gradient) const {
    return 0.5 * (dot(force, gradient) - dot(force, d0_));
  }
  void restart_momentum() {
    y_ = P_;
    g_y_ = g_;
    momentum_ = 1.0;
  }
  void conjugate_gradients_in_face();
  void projected_step();

  const ContactQuadraticProgramme& problem_;
  VectorXd& P_;
  VectorXd& g_;
  double tolerance_;
  long max_products_;
  double step_ = 0.0;
  double f_ = 0.0;  ///< the energy ½PᵀWP − d₀ᵀP
  ProjectedCgOutcome out_;
  std::vector<unsigned char> free_;
  VectorXd phi_, beta_, z_, p_, Ap_, d0_, y_, g_y_, next_, g_next_;
  double momentum_ = 1.0;
  int settled_ = 0, since_face_ = 0;
};

// Projected steps with Nesterov's momentum, restarted whenever the energy rises; after kSettled of
// them with the same free set (and while the proportioning test allows), conjugate gradients on it.
ProjectedCgOutcome ProjectedCg::run() {
  const Index n = P_.size();
  if (n == 0) return out_;
  step_ = problem_.largest_eigenvalue > 0.0 ? 1.0 / problem_.largest_eigenvalue : 0.0;
  free_.resize(static_cast<std::size_t>(n));
  for (VectorXd* v : {&phi_, &beta_, &z_, &p_, &Ap_, &d0_, &y_, &g_y_, &next_, &g_next_})
    v->resize(n);
  problem_.compliance(P_, d0_);
  ++out_.compliance_products;
  d0_ -= g_;
  f_ = energy(P_, g_);
  y_ = P_;
  g_y_ = g_;
  while (true) {
    const Classification c = classify(P_, g_, step_, free_, phi_, beta_);
    out_.residual = c.residual;
    if (!std::isfinite(c.residual) || !std::isfinite(f_)) {
      out_.finite = false;
      break;
    }
    if (c.residual < tolerance_ || out_.compliance_products >= max_products_) break;
    if ((settled_ >= kSettled || since_face_ >= kSettled * 5) &&
        !(c.beta_squared > kGamma * kGamma * c.reduced_free)) {
      conjugate_gradients_in_face();
      restart_momentum();
      continue;
    }
    projected_step();
  }
  return out_;
}

// Conjugate gradients in the face of the pushing contacts, preconditioned there, until a force
// would fall below zero (the step is cut there, the contact leaves the face and the directions
// start again on the smaller face) or the overlapping contacts held at zero outweigh the free
// gradient (Dostál's proportioning test).
void ProjectedCg::conjugate_gradients_in_face() {
  const Index n = P_.size();
  settled_ = 0;
  since_face_ = 0;
  double pAp = 0.0;
  bool first = true;
  while (out_.compliance_products < max_products_) {
    problem_.preconditioner(phi_, free_, z_);
    if (first) {
      p_ = z_;
    } else {
      const double gamma = dot(z_, Ap_) / pAp;  // conjugate to the last direction
      p_ = z_ - gamma * p_;
      for (Index i = 0; i < n; ++i)
        if (!free_[i]) p_[i] = 0.0;
    }
    first = false;
    problem_.compliance(p_, Ap_);
    ++out_.compliance_products;
    pAp = dot(p_, Ap_);
    const double gp = dot(g_, p_);
    if (!std::isfinite(pAp) || !std::isfinite(gp) || !(pAp > 0.0)) break;
    double feasible = std::numeric_limits<double>::infinity();
    Index blocking = -1;
    for (Index i = 0; i < n; ++i)
      if (free_[i] && p_[i] > 0.0 && P_[i] < feasible * p_[i])
        feasible = P_[i] / p_[i], blocking = i;
    const double alpha = gp / pAp;
    const bool blocked = alpha > feasible;
    const double taken = blocked ? feasible : alpha;
    P_ -= taken * p_;
    g_ -= taken * Ap_;
    P_ = P_.cwiseMax(0.0);
    if (blocked) P_[blocking] = 0.0;
    f_ = energy(P_, g_);
    first = blocked;
    const Classification inner = classify(P_, g_, step_, free_, phi_, beta_);
    out_.residual = inner.residual;
    if (!(inner.residual >= tolerance_)) break;
    if (inner.beta_squared > kGamma * kGamma * inner.reduced_free) break;
  }
}

// A projected step of 1/λmax from y, then the momentum for the next one.
void ProjectedCg::projected_step() {
  const Index n = P_.size();
  next_ = (y_ - step_ * g_y_).cwiseMax(0.0);
  int changes = 0;
  for (Index i = 0; i < n; ++i) changes += (next_[i] > 0.0) != (P_[i] > 0.0);
  problem_.compliance(next_, g_next_);
  ++out_.compliance_products;
  g_next_ -= d0_;
  const double f_next = energy(next_, g_next_);
  settled_ = changes == 0 ? settled_ + 1 : 0;
  ++since_face_;
  const double following = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum_ * momentum_));
  const double beta_k = f_next > f_ ? 0.0 : (momentum_ - 1.0) / following;
  momentum_ = f_next > f_ ? 1.0 : following;
  y_ = next_ + beta_k * (next_ - P_);
  g_y_ = g_next_ + beta_k * (g_next_ - g_);
  P_.swap(next_);
  g_.swap(g_next_);
  f_ = f_next;
}

}  // namespace

ProjectedCgOutcome solve_by_projected_cg(const ContactQuadraticProgramme& problem, VectorXd& P,
                                         VectorXd& g, double tolerance, long max_products) {
  return ProjectedCg(problem, P, g, tolerance, max_products).run();
}

}  // namespace fibrecheck
