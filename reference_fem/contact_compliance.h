#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace fibrecheck {

/// The compliance W of the contact problem (mm/N: the overlap each unit force removes, DESIGN §3)
/// as the active-set method uses it — products W·x and solves on subsets of the contacts — so that
/// W can be held as a matrix or only applied, through the finite elements, without ever being
/// formed (saddle_point_compliance.h).
class ContactCompliance {
 public:
  virtual ~ContactCompliance() = default;
  /// W·x; x is mostly zero (the contacts that do not push).
  virtual Eigen::VectorXd times(const Eigen::VectorXd& x) const = 0;
  /// Solves W_SS·x = b for the rows and columns `index`, as solve_on_subset (subset_solve.h) does:
  /// regularised by 1e-10 of W_SS's largest diagonal entry when W_SS is singular; false when even
  /// that fails or the answer is not finite.
  virtual bool solve_on_subset(const std::vector<Eigen::Index>& index, const Eigen::VectorXd& b,
                               Eigen::VectorXd& x) const = 0;
  /// W_SS for the rows and columns `index`, in their order.
  virtual Eigen::SparseMatrix<double> on_subset(const std::vector<Eigen::Index>& index) const = 0;
};

/// W held as a sparse matrix, assembled from the fibres' influence matrices.
class AssembledCompliance : public ContactCompliance {
 public:
  explicit AssembledCompliance(const Eigen::SparseMatrix<double>& W) : W_(W) {}
  Eigen::VectorXd times(const Eigen::VectorXd& x) const override;
  bool solve_on_subset(const std::vector<Eigen::Index>& index, const Eigen::VectorXd& b,
                       Eigen::VectorXd& x) const override;
  Eigen::SparseMatrix<double> on_subset(const std::vector<Eigen::Index>& index) const override;

 private:
  const Eigen::SparseMatrix<double>& W_;
};

}  // namespace fibrecheck
