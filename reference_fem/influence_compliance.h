#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "contact_compliance.h"

namespace fibrecheck {

/// W applied through the fibres' influence matrices, never formed (its rows a contact each, or with
/// friction one per component of a contact's reaction). W_jk = Σ_f G_f(s_j, s_k) φ_j·φ_k
/// over the fibres f both contacts act on, with G_f fibre f's influence matrix in its contact
/// stations and φ the part across the fibre of the force a unit reaction puts on it there. W would
/// hold (contacts on a fibre)² entries per fibre, G_f only (stations on it)²: on a compacted tow
/// several contacts share each slice's station, and W took several times the memory of the
/// influence matrices it is made of.
///
/// The fibres are shared out over the processes, each holding the influence matrices of its own.
/// A product W·x is, fibre by fibre, the displacement the contacts' forces give at its stations,
/// summed over the processes; a solve on a set gathers the set's entries from every process (the
/// pushing contacts, a few per cent of the candidates on a tow) and solves them as the assembled W
/// does (subset_solve.h), on every process alike. Every process must make the same calls with the
/// same arguments; the answers are the same bits on every process.
class InfluenceCompliance : public ContactCompliance {
 public:
  /// One side of a row of W on a fibre (a contact's, or with friction one component of its
  /// reaction): its station there and φ.
  struct Side {
    Eigen::Index row;
    int station;
    Eigen::Vector3d direction;
  };
  /// A fibre this process holds: its influence matrix (`stations` × `stations`, symmetric, stored
  /// densely from `G`, which must outlive this object) and the sides of its contacts.
  struct Fibre {
    const double* G;
    int stations;
    std::vector<Side> sides;
  };

  InfluenceCompliance(std::vector<Fibre> fibres, Eigen::Index rows, MPI_Comm communicator);
  Eigen::VectorXd times(const Eigen::VectorXd& x) const override;
  bool solve_on_subset(const std::vector<Eigen::Index>& index, const Eigen::VectorXd& b,
                       Eigen::VectorXd& x) const override;
  Eigen::SparseMatrix<double> on_subset(const std::vector<Eigen::Index>& index) const override;
  /// W_kk of every row.
  Eigen::VectorXd diagonal() const;

 private:
  /// A side held here: its fibre (in fibres_) and its place in that fibre's sides.
  struct Held {
    int fibre, side;
  };
  std::vector<Fibre> fibres_;
  Eigen::Index rows_;
  MPI_Comm comm_;
  /// The sides of row k held here: held_[first_[k]] to held_[first_[k + 1]].
  std::vector<std::size_t> first_;
  std::vector<Held> held_;
};

}  // namespace fibrecheck
