#include "subset_solve.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace fibrecheck {

bool solve_on_subset(const Eigen::SparseMatrix<double>& W, const std::vector<Eigen::Index>& index,
                     const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const Eigen::Index m = static_cast<Eigen::Index>(index.size());
  x.resize(m);
  if (m == 0) return true;
  std::vector<Eigen::Index> position(static_cast<std::size_t>(W.rows()), -1);
  for (Eigen::Index k = 0; k < m; ++k) position[static_cast<std::size_t>(index[k])] = k;
  std::vector<Eigen::Triplet<double>> entries;
  double largest_diagonal = 0.0;
  for (Eigen::Index c = 0; c < m; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(W, index[c]); it; ++it) {
      const Eigen::Index row = position[static_cast<std::size_t>(it.row())];
      if (row < 0) continue;
      entries.emplace_back(row, c, it.value());
      if (row == c) largest_diagonal = std::max(largest_diagonal, std::fabs(it.value()));
    }
  Eigen::SparseMatrix<double> Wss(m, m);
  Wss.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Wss);
  if (ldlt.info() == Eigen::Success) {
    x = ldlt.solve(b);
    const Eigen::VectorXd& D = ldlt.vectorD();
    if (ldlt.info() == Eigen::Success && x.allFinite() &&
        D.minCoeff() > 1e-14 * D.cwiseAbs().maxCoeff())
      return true;
  }
  Eigen::SparseMatrix<double> identity(m, m);
  identity.setIdentity();
  const Eigen::SparseMatrix<double> regularised_matrix =
      Wss + (1e-10 * largest_diagonal) * identity;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> regularised(regularised_matrix);
  if (regularised.info() != Eigen::Success) return false;
  x = regularised.solve(b);
  return regularised.info() == Eigen::Success && x.allFinite();
}

}  // namespace fibrecheck
