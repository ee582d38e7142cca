#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace fibrecheck {

/// How far restarted GMRES goes: a restart every `restart` products, at most `max_products` in
/// all, stopping at a residual of `reduction` times the right-hand side's.
struct GmresLimits {
  int restart;
  int max_products;
  double reduction;
};

/// x with A·x = b by restarted GMRES, right-preconditioned by `precondition` (Saad, Iterative
/// Methods for Sparse Linear Systems, §9.3.2), to a residual of `limits.reduction`·‖b‖.
template <class Apply, class Precondition>
Eigen::VectorXd gmres(const Apply& apply, const Precondition& precondition,
                      const Eigen::VectorXd& b, const GmresLimits& limits) {
  const int restart = limits.restart;
  const int max_products = limits.max_products;
  const Eigen::Index n = b.size();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), r = b, z(n), w(n);
  const double stop = limits.reduction * b.norm();
  int products = 0;
  while (products < max_products && r.norm() > stop) {
    const double beta = r.norm();
    std::vector<Eigen::VectorXd> V{r / beta};
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(restart + 1, restart);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(restart + 1), cs(restart), sn(restart);
    g[0] = beta;
    int j = 0;
    for (; j < restart && products < max_products; ++j) {
      precondition(V[j], z);
      apply(z, w);
      ++products;
      for (int i = 0; i <= j; ++i) {
        H(i, j) = w.dot(V[i]);
        w -= H(i, j) * V[i];
      }
      H(j + 1, j) = w.norm();
      for (int i = 0; i < j; ++i) {
        const double h = cs[i] * H(i, j) + sn[i] * H(i + 1, j);
        H(i + 1, j) = -sn[i] * H(i, j) + cs[i] * H(i + 1, j);
        H(i, j) = h;
      }
      const double rho = std::hypot(H(j, j), H(j + 1, j));
      if (!(rho > 0.0)) break;
      cs[j] = H(j, j) / rho;
      sn[j] = H(j + 1, j) / rho;
      H(j, j) = rho;
      H(j + 1, j) = 0.0;
      g[j + 1] = -sn[j] * g[j];
      g[j] *= cs[j];
      const bool done = std::fabs(g[j + 1]) <= stop || !(w.norm() > 0.0);
      if (!done) V.push_back(w / w.norm());
      if (done) {
        ++j;
        break;
      }
    }
    const Eigen::VectorXd y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    w.setZero();
    for (int i = 0; i < j; ++i) w += y[i] * V[static_cast<std::size_t>(i)];
    precondition(w, z);
    x += z;
    apply(x, w);
    ++products;
    r = b - w;
  }
  return x;
}

}  // namespace fibrecheck
