#include "contact_compliance.h"

#include <vector>

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

Eigen::SparseMatrix<double> AssembledCompliance::on_subset(
    const std::vector<Eigen::Index>& index) const {
  std::vector<Eigen::Index> position(static_cast<std::size_t>(W_.rows()), -1);
  for (std::size_t i = 0; i < index.size(); ++i)
    position[static_cast<std::size_t>(index[i])] = static_cast<Eigen::Index>(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t j = 0; j < index.size(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(W_, index[j]); it; ++it)
      if (position[static_cast<std::size_t>(it.row())] >= 0)
        entries.emplace_back(position[static_cast<std::size_t>(it.row())],
                             static_cast<Eigen::Index>(j), it.value());
  const Eigen::Index m = static_cast<Eigen::Index>(index.size());
  Eigen::SparseMatrix<double> Wss(m, m);
  Wss.setFromTriplets(entries.begin(), entries.end());
  return Wss;
}

}  // namespace fibrecheck
