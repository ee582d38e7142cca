#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contact_compliance.h"

namespace fibrecheck {

/// W shared out over the processes by fibres. W_jk = Σ_f over the fibres both contacts act on, so
/// W = Σ_p W_p with W_p the part of process p's own fibres: each process holds its W_p and the
/// influence matrices of its own fibres only, and its memory falls with the processes. A product
/// sums W_p·x over the processes; a solve on a set gathers the set's entries of every W_p (the
/// pushing contacts, a few per cent of the candidates on a tow) and solves it as the assembled W
/// does (subset_solve.h), on every process alike. On one process W_p is W and the answers are
/// those of AssembledCompliance to the last bit.
///
/// Every process must make the same calls with the same arguments; the answers are the same bits
/// on every process.
class SharedCompliance : public ContactCompliance {
 public:
  SharedCompliance(const Eigen::SparseMatrix<double>& part, MPI_Comm communicator)
      : part_(part), comm_(communicator) {}
  Eigen::VectorXd times(const Eigen::VectorXd& x) const override;
  bool solve_on_subset(const std::vector<Eigen::Index>& index, const Eigen::VectorXd& b,
                       Eigen::VectorXd& x) const override;
  /// W_kk of every contact.
  Eigen::VectorXd diagonal() const;

 private:
  const Eigen::SparseMatrix<double>& part_;
  MPI_Comm comm_;
};

}  // namespace fibrecheck
