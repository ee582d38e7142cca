#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace fibrecheck {

/// The equations W_FF·x_F = b_F of an active set's free variables F, solved again and again as F
/// changes a few variables at a time. The factor kept is the LDLᵀ of W with every variable outside
/// F an identity row and column, so a variable joining F is a row added to the factor and one
/// leaving it a row deleted (CHOLMOD's rank-2 modifications, about the cost of a solve), where a
/// sparse LDLᵀ of W_FF from scratch costs an ordering and a factorisation each time. A fresh
/// factor is ordered on its own pattern; where F has changed by many variables since, it is made
/// again. An answer judged is judged by its own residual in W_FF, which must be at round-off
/// (modifications accumulate error: the factor is then made afresh). As in
/// solve_on_subset, a W_FF with a pivot below 1e-14 of the largest (contacts that constrain the
/// same motion twice) is solved regularised, W_FF + εI with ε 1e-10 of W's largest diagonal entry,
/// by a second factor kept the same way.
class FreeSetFactor {
 public:
  explicit FreeSetFactor(const Eigen::SparseMatrix<double>& W);
  ~FreeSetFactor();
  FreeSetFactor(const FreeSetFactor&) = delete;
  FreeSetFactor& operator=(const FreeSetFactor&) = delete;

  /// x with x_F solving W_FF·x_F = b_F (or its regularised equations) and zero outside F
  /// (`free[i]` non-zero for i in F). False when even a fresh factor leaves a residual above
  /// round-off: the caller then solves them another way. Not `judged`, the answer is the factor's
  /// as it stands, only checked to be finite: for solves whose answers only steer, the last of
  /// which the caller judges by `answers`.
  bool solve(const std::vector<char>& free, const Eigen::VectorXd& b, Eigen::VectorXd& x,
             bool judged = true);
  /// The last answer's residual (x for F and b, by the factor that gave it) is at round-off.
  bool answers(const std::vector<char>& free, const Eigen::VectorXd& b,
               const Eigen::VectorXd& x) const;

  /// The smallest pivot of the last answer's factor over its largest, on F: about the reciprocal
  /// of W_FF's condition number.
  double pivot_ratio() const;
  const Eigen::SparseMatrix<double>& matrix() const { return W_; }
  int factorisations() const { return factorisations_; }
  int modifications() const { return modifications_; }

 private:
  class Factor;
  bool solve_with(Factor& factor, const std::vector<char>& free, const Eigen::VectorXd& b,
                  Eigen::VectorXd& x, bool judged);
  double residual_ratio(const std::vector<char>& free, const Eigen::VectorXd& b,
                        const Eigen::VectorXd& x, double shift) const;

  const Eigen::SparseMatrix<double>& W_;
  double epsilon_ = 0.0;
  double last_shift_ = 0.0;  ///< of the factor that gave the last answer
  std::unique_ptr<Factor> exact_, regularised_;
  int factorisations_ = 0;
  int modifications_ = 0;
};

}  // namespace fibrecheck
