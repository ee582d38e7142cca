#include "normal_mixing.h"

#include <Eigen/QR>

namespace fibrecheck {

void NormalMixing::restart() {
  last_f_.resize(0);
  last_g_.resize(0);
  dF_.clear();
  dG_.clear();
}

Eigen::VectorXd NormalMixing::mix(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  const Eigen::VectorXd f = g - x;
  if (last_f_.size() == f.size()) {
    dF_.push_back(f - last_f_);
    dG_.push_back(g - last_g_);
    if (static_cast<int>(dF_.size()) > depth_) dF_.pop_front(), dG_.pop_front();
  } else {
    dF_.clear();
    dG_.clear();
  }
  last_f_ = f;
  last_g_ = g;
  if (dF_.empty()) return g;
  const Eigen::Index m = static_cast<Eigen::Index>(dF_.size());
  Eigen::MatrixXd DF(f.size(), m), DG(f.size(), m);
  for (Eigen::Index j = 0; j < m; ++j) DF.col(j) = dF_[j], DG.col(j) = dG_[j];
  const Eigen::VectorXd gamma = DF.colPivHouseholderQr().solve(f);
  Eigen::VectorXd next = g - DG * gamma;
  for (Eigen::Index k = 0; k + 2 < next.size(); k += 3) {
    const double size = next.segment<3>(k).norm();
    next.segment<3>(k) =
        size > 0.0 ? Eigen::Vector3d(next.segment<3>(k) / size) : Eigen::Vector3d(g.segment<3>(k));
  }
  return next;
}

}  // namespace fibrecheck
