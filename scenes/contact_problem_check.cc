#include "contact_problem_check.h"

#include <algorithm>
#include <cmath>

namespace fibrecheck {

namespace {

/// Whether contact j's friction can do anything: some tangent it can slip along.
bool friction_matters(const ContactProblem& p, std::size_t j) {
  const Eigen::Index o = p.offset[j];
  const double normal = p.W.coeff(o, o);
  for (Eigen::Index i = o + 1; i < p.offset[j + 1]; ++i)
    if (p.W.coeff(i, i) > 1e-12 * normal) return true;
  return false;
}

}  // namespace

ProblemResidual problem_residual(const ContactProblem& p, const Eigen::VectorXd& r) {
  ProblemResidual residual;
  if (!r.allFinite()) return {INFINITY, INFINITY, INFINITY};  // a non-finite answer solves nothing
  const Eigen::VectorXd w = p.q - p.W * r;
  for (std::size_t j = 0; j < p.contacts.size(); ++j) {
    const Eigen::Index o = p.offset[j];
    const Eigen::Index t = p.offset[j + 1] - o - 1;
    if (p.contacts[j].excluded) {
      residual.excluded_N =
          std::max(residual.excluded_N, r.segment(o, t + 1).cwiseAbs().maxCoeff());
      continue;
    }
    const double W_nn = p.W.coeff(o, o);
    if (!(W_nn > 0.0)) continue;
    const double rho = 1.0 / W_nn;
    // Normal: P = max(0, P + ρ·w_n), the overlap left w_n ≤ 0 with P·w_n = 0.
    const double P = std::max(0.0, r[o] + rho * w[o]);
    residual.overlap_mm = std::max(residual.overlap_mm, std::fabs(r[o] - P) / rho);
    if (t == 0) continue;
    // Tangential: F = proj_{|F| ≤ μP}(F + ρ_t·w_t), ρ_t from the largest tangential compliance.
    double W_tt = 0.0;
    for (Eigen::Index i = o + 1; i <= o + t; ++i) W_tt = std::max(W_tt, p.W.coeff(i, i));
    if (!(W_tt > 1e-12 * W_nn)) continue;  // nothing slips: any friction in the disk will do
    const double rho_t = 1.0 / W_tt;
    Eigen::VectorXd trial = r.segment(o + 1, t) + rho_t * w.segment(o + 1, t);
    const double radius = p.mu * std::max(r[o], 0.0);
    if (trial.norm() > radius) trial *= radius / trial.norm();
    residual.slip_mm = std::max(residual.slip_mm, (r.segment(o + 1, t) - trial).norm() / rho_t);
  }
  return residual;
}

double residual_scale(const ContactProblem& p) {
  const double largest = p.q.size() > 0 ? p.q.cwiseAbs().maxCoeff() : 0.0;
  return largest > 0.0 ? largest : 1.0;
}

bool solves(const ContactProblem& p, const ProblemResidual& residual, double relative_tolerance) {
  const double bound = relative_tolerance * residual_scale(p);
  return residual.overlap_mm <= bound && residual.slip_mm <= bound && residual.excluded_N == 0.0;
}

double ProblemAgreement::relative() const {
  const double forces = normal_scale_N > 0.0 ? std::max(normal_N, friction_N) / normal_scale_N
                                             : std::max(normal_N, friction_N);
  const double gaps = w_scale_mm > 0.0 ? w_mm / w_scale_mm : w_mm;
  return std::max(forces, gaps);
}

ProblemAgreement compare_answers(const ContactProblem& p, const Eigen::VectorXd& a,
                                 const Eigen::VectorXd& b) {
  ProblemAgreement agreement;
  const Eigen::VectorXd wa = p.q - p.W * a, wb = p.q - p.W * b;
  for (std::size_t j = 0; j < p.contacts.size(); ++j) {
    if (p.contacts[j].excluded) continue;
    ++agreement.contacts;
    const Eigen::Index o = p.offset[j];
    const Eigen::Index t = p.offset[j + 1] - o - 1;
    agreement.normal_N = std::max(agreement.normal_N, std::fabs(a[o] - b[o]));
    agreement.normal_scale_N =
        std::max({agreement.normal_scale_N, std::fabs(a[o]), std::fabs(b[o])});
    agreement.w_mm = std::max(agreement.w_mm,
                              (wa.segment(o, t + 1) - wb.segment(o, t + 1)).cwiseAbs().maxCoeff());
    agreement.w_scale_mm =
        std::max(agreement.w_scale_mm, p.q.segment(o, t + 1).cwiseAbs().maxCoeff());
    if (t == 0) continue;
    if (friction_matters(p, j)) {
      ++agreement.frictions_compared;
      agreement.friction_N =
          std::max(agreement.friction_N, (a.segment(o + 1, t) - b.segment(o + 1, t)).norm());
    } else {
      ++agreement.frictions_not_unique;
    }
  }
  return agreement;
}

}  // namespace fibrecheck
