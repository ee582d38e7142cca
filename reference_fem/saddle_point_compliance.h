#pragma once

#include <mpi.h>
#include <petscksp.h>
#include <petscmat.h>

#include <Eigen/Core>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "beam_model.h"
#include "contact_compliance.h"
#include "fibre.h"

namespace fibrecheck {

/// One side of a contact: the fibre, the fraction of its length where the contact acts (a mesh
/// node), and the force a unit reaction puts on the fibre there (−n on A, +n on B or a fibre
/// against a wall).
struct ContactSideForce {
  int fibre;
  double s;
  Eigen::Vector3d direction;
};

/// The compliance W of the contact problem never formed: W = −B·S⁻¹·Bᵀ, with S the finite-element
/// beams' mixed system and B the contacts' rows (row k reads the overlap that contact k's forces
/// remove from the deflections at its sides; Bᵀ puts a unit reaction on them as nodal forces). So
///  - W·x is one finite-element solve under the forces x (each process its own fibres, the
///    contacts' overlaps summed over the processes), and
///  - W_SS·x = b is the saddle-point system [S Bᵀ_S; B_S 0]·[y; x] = [0; b] of the beams and the
///    set's constraint rows, solved by MUMPS over all the processes at once.
/// Memory grows with the unknowns of the finite elements and the contacts, not with the square of
/// the contacts on a fibre, and each process holds its own fibres' part: this is how the
/// reference holds tows whose influence matrices would not fit. Its answers are those of the
/// assembled W to round-off.
///
/// Every process must make the same calls with the same arguments (the active-set method runs on
/// every process alike); the answers are the same bits on every process.
class SaddlePointCompliance : public ContactCompliance {
 public:
  /// `model`: this process's beams (null when it has no fibre); `owner[f]` the process that meshes
  /// fibre f; `sides[k]` the sides of contact k, on any process's fibres.
  SaddlePointCompliance(MPI_Comm communicator, BeamModel* model, const std::vector<Fibre>& fibres,
                        std::vector<int> owner, std::vector<std::vector<ContactSideForce>> sides);
  ~SaddlePointCompliance() override;
  SaddlePointCompliance(const SaddlePointCompliance&) = delete;
  SaddlePointCompliance& operator=(const SaddlePointCompliance&) = delete;

  Eigen::VectorXd times(const Eigen::VectorXd& x) const override;
  bool solve_on_subset(const std::vector<Eigen::Index>& index, const Eigen::VectorXd& b,
                       Eigen::VectorXd& x) const override;
  /// A product W·e_k, a finite-element solve, per column: for sets of a few hundred.
  Eigen::SparseMatrix<double> on_subset(const std::vector<Eigen::Index>& index) const override;

  /// Per contact: every side of it lies where a support pins the fibre, so no force moves it.
  std::vector<char> immovable() const;

  /// Hears a line every 5 s while sets are solved (each a factorisation of the whole system).
  void report_to(std::function<void(const std::string&)> progress) {
    progress_ = std::move(progress);
  }

 private:
  /// The saddle-point matrix with a row and a column for every contact, made once: the pattern
  /// stays, so MUMPS analyses it once and each set only refactorises.
  void make_system();
  /// The set's values: its contacts' rows and columns, the others' rows the identity.
  void set_values(const std::vector<Eigen::Index>& index, double regularisation) const;
  /// False when MUMPS finds a null pivot in the unregularised system.
  bool factorise(const std::vector<Eigen::Index>& index, double regularisation) const;
  /// False when the solve fails, its backward error is too large or its answer not finite.
  bool solve_factorised(const std::vector<Eigen::Index>& index, const Eigen::VectorXd& b,
                        Eigen::VectorXd& x) const;
  /// W_kk of the contacts `index`, by rounds of unit reactions that share no fibre.
  Eigen::VectorXd self_compliances(const std::vector<Eigen::Index>& index) const;

  MPI_Comm comm_;
  int rank_ = 0, processes_ = 1;
  BeamModel* model_;
  const std::vector<Fibre>& fibres_;
  std::vector<int> owner_;
  std::vector<std::vector<ContactSideForce>> sides_;
  /// Each contact's constraint row (global), and its coefficients on this process's unknowns.
  struct Coefficient {
    Eigen::Index contact;
    PetscInt column;
    double value;
  };
  std::vector<PetscInt> constraint_row_;
  std::vector<Coefficient> coefficients_;
  Mat A_ = nullptr;
  Vec rhs_ = nullptr, solution_ = nullptr;
  KSP ksp_ = nullptr;
  std::function<void(const std::string&)> progress_;
  mutable long factorisations_ = 0;
  mutable std::chrono::steady_clock::time_point last_report_ = std::chrono::steady_clock::now();
};

}  // namespace fibrecheck
