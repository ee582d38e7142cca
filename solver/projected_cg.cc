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

ProjectedCgOutcome solve_by_projected_cg(const ContactQuadraticProgramme& problem, VectorXd& P,
                                         VectorXd& g, double tolerance, long max_products) {
  ProjectedCgOutcome out;
  const Index n = P.size();
  if (n == 0) return out;
  const double step = problem.largest_eigenvalue > 0.0 ? 1.0 / problem.largest_eigenvalue : 0.0;
  constexpr double kGamma = 1.0;  // proportioning: β may be as large as the free gradient
  constexpr int kSettled = 10;    // projected steps without a change of the free set
  std::vector<unsigned char> free(static_cast<std::size_t>(n));
  VectorXd phi(n), beta(n), z(n), p(n), Ap(n), d0(n), y(n), g_y(n), next(n), g_next(n);
  problem.compliance(P, d0);
  ++out.compliance_products;
  d0 -= g;
  auto energy = [&](const VectorXd& force, const VectorXd& gradient) {
    return 0.5 * (dot(force, gradient) - dot(force, d0));
  };
  double f = energy(P, g);
  // Projected steps with Nesterov's momentum from y (its gradient g_y), restarted whenever the
  // energy rises; after kSettled of them with the same free set, conjugate gradients on it.
  y = P;
  g_y = g;
  double momentum = 1.0;
  int settled = 0, since_face = 0;
  auto restart_momentum = [&]() {
    y = P;
    g_y = g;
    momentum = 1.0;
  };
  while (true) {
    const Classification c = classify(P, g, step, free, phi, beta);
    out.residual = c.residual;
    if (!std::isfinite(c.residual) || !std::isfinite(f)) {
      out.finite = false;
      break;
    }
    if (c.residual < tolerance || out.compliance_products >= max_products) break;

    if ((settled >= kSettled || since_face >= kSettled * 5) &&
        !(c.beta_squared > kGamma * kGamma * c.reduced_free)) {
      // Conjugate gradients in the face of the pushing contacts, preconditioned there, until a
      // force would fall below zero (the step is cut there) or the overlapping contacts held at
      // zero outweigh the free gradient (Dostál's proportioning test).
      settled = 0;
      since_face = 0;
      double pAp = 0.0;
      bool first = true;
      while (out.compliance_products < max_products) {
        problem.preconditioner(phi, free, z);
        if (first) {
          p = z;
        } else {
          const double gamma = dot(z, Ap) / pAp;  // conjugate to the last direction
          p = z - gamma * p;
          for (Index i = 0; i < n; ++i)
            if (!free[i]) p[i] = 0.0;
        }
        first = false;
        problem.compliance(p, Ap);
        ++out.compliance_products;
        pAp = dot(p, Ap);
        const double gp = dot(g, p);
        if (!std::isfinite(pAp) || !std::isfinite(gp) || !(pAp > 0.0)) break;
        double feasible = std::numeric_limits<double>::infinity();
        Index blocking = -1;
        for (Index i = 0; i < n; ++i)
          if (free[i] && p[i] > 0.0 && P[i] < feasible * p[i]) feasible = P[i] / p[i], blocking = i;
        const double alpha = gp / pAp;
        const bool blocked = alpha > feasible;
        const double taken = blocked ? feasible : alpha;
        P -= taken * p;
        g -= taken * Ap;
        P = P.cwiseMax(0.0);
        if (blocked) {
          P[blocking] = 0.0;
        }
        f = energy(P, g);
        // Cut at a bound: the contact leaves the face and the conjugate directions start again
        // on the smaller face.
        first = blocked;
        const Classification inner = classify(P, g, step, free, phi, beta);
        out.residual = inner.residual;
        if (!(inner.residual >= tolerance)) break;
        if (inner.beta_squared > kGamma * kGamma * inner.reduced_free) break;
      }
      restart_momentum();
      continue;
    }

    // A projected step from y.
    next = (y - step * g_y).cwiseMax(0.0);
    int changes = 0;
    for (Index i = 0; i < n; ++i) changes += (next[i] > 0.0) != (P[i] > 0.0);
    problem.compliance(next, g_next);
    ++out.compliance_products;
    g_next -= d0;
    const double f_next = energy(next, g_next);
    settled = changes == 0 ? settled + 1 : 0;
    ++since_face;
    const double following = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum * momentum));
    const double beta_k = f_next > f ? 0.0 : (momentum - 1.0) / following;
    momentum = f_next > f ? 1.0 : following;
    y = next + beta_k * (next - P);
    g_y = g_next + beta_k * (g_next - g);
    P.swap(next);
    g.swap(g_next);
    f = f_next;
  }
  return out;
}

}  // namespace fibrecheck
