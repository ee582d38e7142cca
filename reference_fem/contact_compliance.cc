#include "contact_compliance.h"

#include "subset_solve.h"

namespace fibrecheck {

Eigen::VectorXd AssembledCompliance::times(const Eigen::VectorXd& x) const {
  const Eigen::Index n = x.size();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k)
    if (x[k] != 0.0)
      for (Eigen::SparseMatrix<double>::InnerIterator it(W_, k); it; ++it)
        y[it.row()] += x[k] * it.value();
  return y;
}

bool AssembledCompliance::solve_on_subset(const std::vector<Eigen::Index>& index,
                                          const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  return fibrecheck::solve_on_subset(W_, index, b, x);
}

}  // namespace fibrecheck
