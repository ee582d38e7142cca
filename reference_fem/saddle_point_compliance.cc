#include "saddle_point_compliance.h"

#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "petsc_check.h"
#include "process_sums.h"

namespace fibrecheck {

namespace {

/// The backward error a solve of the saddle-point system may leave: a backward-stable direct solve
/// leaves a few times machine epsilon.
constexpr double kBackwardError = 1e-12;
/// Steps of refinement on the set's own equations after each solve.
constexpr int kRefinements = 1;

}  // namespace

SaddlePointCompliance::SaddlePointCompliance(MPI_Comm communicator, BeamModel* model,
                                             const std::vector<Fibre>& fibres,
                                             std::vector<int> owner,
                                             std::vector<std::vector<ContactSideForce>> sides)
    : comm_(communicator),
      model_(model),
      fibres_(fibres),
      owner_(std::move(owner)),
      sides_(std::move(sides)) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &processes_);
  make_system();
}

SaddlePointCompliance::~SaddlePointCompliance() {
  if (ksp_) KSPDestroy(&ksp_);
  if (rhs_) VecDestroy(&rhs_);
  if (solution_) VecDestroy(&solution_);
  if (A_) MatDestroy(&A_);
}

// Process r holds the rows of its own fibres' unknowns and then the constraint rows of the
// contacts whose first side is on one of its fibres. A side's coefficients are its direction
// across the fibre (its parts along e1 and e2) at the deflection unknowns of its node; a pinned
// node carries none. Every coefficient is in the pattern from the start, zero until its contact
// is in a set.
void SaddlePointCompliance::make_system() {
  const Eigen::Index n = static_cast<Eigen::Index>(sides_.size());
  const long unknowns = model_ ? static_cast<long>(model_->unknowns()) : 0;
  std::vector<long> beams_of(static_cast<std::size_t>(processes_), 0),
      constraints_of(static_cast<std::size_t>(processes_), 0);
  MPI_Allgather(&unknowns, 1, MPI_LONG, beams_of.data(), 1, MPI_LONG, comm_);
  constraint_row_.resize(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k)
    constraint_row_[k] = static_cast<PetscInt>(constraints_of[owner_[sides_[k].front().fibre]]++);
  std::vector<long> first_row(static_cast<std::size_t>(processes_) + 1, 0);
  for (int r = 0; r < processes_; ++r) {
    first_row[r + 1] = first_row[r] + beams_of[r] + constraints_of[r];
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    const int r = owner_[sides_[k].front().fibre];
    constraint_row_[k] += static_cast<PetscInt>(first_row[r] + beams_of[r]);
  }
  const long mine = first_row[rank_];
  std::vector<PetscInt> on_unknown(static_cast<std::size_t>(unknowns), 0);
  for (Eigen::Index k = 0; k < n; ++k)
    for (const ContactSideForce& side : sides_[k]) {
      if (owner_[side.fibre] != rank_) continue;
      const Fibre& f = fibres_[side.fibre];
      for (int plane = 0; plane < 2; ++plane) {
        const long unknown = model_->deflection_unknown(side.fibre, side.s, plane);
        const double value = side.direction.dot(plane == 0 ? f.e1 : f.e2);
        if (unknown < 0) continue;
        coefficients_.push_back({k, static_cast<PetscInt>(mine + unknown), value});
        ++on_unknown[unknown];
      }
    }

  const PetscInt local = static_cast<PetscInt>(beams_of[rank_] + constraints_of[rank_]);
  std::vector<long> beam_row_start(static_cast<std::size_t>(unknowns) + 1, 0);
  std::vector<PetscInt> beam_columns;
  std::vector<double> beam_values;
  if (model_)
    model_->for_each_matrix_entry([&](long row, long column, double value) {
      ++beam_row_start[row + 1];
      beam_columns.push_back(static_cast<PetscInt>(mine + column));
      beam_values.push_back(value);
    });
  std::partial_sum(beam_row_start.begin(), beam_row_start.end(), beam_row_start.begin());
  // A constraint row has at most two sides of two coefficients each, and its diagonal.
  std::vector<PetscInt> diagonal_count(static_cast<std::size_t>(local), 5),
      off_count(static_cast<std::size_t>(local), 4);
  for (long row = 0; row < unknowns; ++row) {
    diagonal_count[row] =
        static_cast<PetscInt>(beam_row_start[row + 1] - beam_row_start[row]) + on_unknown[row];
    off_count[row] = on_unknown[row];
  }
  check(MatCreate(comm_, &A_), "MatCreate");
  check(MatSetSizes(A_, local, local, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(A_, MATAIJ), "MatSetType");
  check(MatSeqAIJSetPreallocation(A_, 0, diagonal_count.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(A_, 0, diagonal_count.data(), 0, off_count.data()),
        "MatMPIAIJSetPreallocation");
  check(MatSetOption(A_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  for (long row = 0; row < unknowns; ++row) {
    const PetscInt global = static_cast<PetscInt>(mine + row);
    const long first = beam_row_start[row];
    check(MatSetValues(A_, 1, &global, static_cast<PetscInt>(beam_row_start[row + 1] - first),
                       beam_columns.data() + first, beam_values.data() + first, INSERT_VALUES),
          "MatSetValues");
  }
  set_values({}, 0.0);
  check(MatCreateVecs(A_, &solution_, &rhs_), "MatCreateVecs");

  PC pc;
  Mat factor;
  check(KSPCreate(comm_, &ksp_), "KSPCreate");
  check(KSPSetOperators(ksp_, A_, A_), "KSPSetOperators");
  check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  check(PCSetType(pc, PCLU), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
  check(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
  // No iterative refinement of the whole system (solve_on_subset refines on the set's own
  // equations, which is what the answers need); null pivots detected (ICNTL(24)) at 1e-13 of the
  // matrix's norm, where a set that constrains one motion twice leaves round-off.
  check(MatMumpsSetIcntl(factor, 10, 0), "MatMumpsSetIcntl");
  check(MatMumpsSetIcntl(factor, 24, 1), "MatMumpsSetIcntl");
  check(MatMumpsSetCntl(factor, 3, 1e-13), "MatMumpsSetCntl");
}

void SaddlePointCompliance::set_values(const std::vector<Eigen::Index>& index,
                                       double regularisation) const {
  std::vector<char> in_set(sides_.size(), 0);
  for (const Eigen::Index k : index) in_set[k] = 1;
  for (const Coefficient& c : coefficients_) {
    const double value = in_set[c.contact] ? c.value : 0.0;
    const PetscInt row = constraint_row_[c.contact];
    check(MatSetValue(A_, row, c.column, value, INSERT_VALUES), "MatSetValue");
    check(MatSetValue(A_, c.column, row, value, INSERT_VALUES), "MatSetValue");
  }
  for (std::size_t k = 0; k < sides_.size(); ++k)
    if (owner_[sides_[k].front().fibre] == rank_)
      check(MatSetValue(A_, constraint_row_[k], constraint_row_[k],
                        in_set[k] ? regularisation : 1.0, INSERT_VALUES),
            "MatSetValue");
  check(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

// W·x: the fibres under the nodal forces of the reactions x (each process its own), then each
// contact's overlap removed, n·(u_B − u_A) as the sides' directions read it, summed over the
// processes.
Eigen::SparseMatrix<double> SaddlePointCompliance::on_subset(
    const std::vector<Eigen::Index>& index) const {
  const Eigen::Index m = static_cast<Eigen::Index>(index.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sides_.size()));
  for (Eigen::Index j = 0; j < m; ++j) {
    unit[index[j]] = 1.0;
    const Eigen::VectorXd column = times(unit);
    unit[index[j]] = 0.0;
    for (Eigen::Index i = 0; i < m; ++i)
      if (column[index[i]] != 0.0) entries.emplace_back(i, j, column[index[i]]);
  }
  Eigen::SparseMatrix<double> Wss(m, m);
  Wss.setFromTriplets(entries.begin(), entries.end());
  return Wss;
}

Eigen::VectorXd SaddlePointCompliance::times(const Eigen::VectorXd& x) const {
  const Eigen::Index n = x.size();
  std::vector<double> y(static_cast<std::size_t>(n), 0.0);
  if (model_) {
    std::vector<NodalForce> forces;
    for (Eigen::Index k = 0; k < n; ++k)
      if (x[k] != 0.0)
        for (const ContactSideForce& side : sides_[k])
          if (owner_[side.fibre] == rank_)
            forces.push_back({side.fibre, side.s, x[k] * side.direction});
    model_->run(forces, false);
    for (Eigen::Index k = 0; k < n; ++k)
      for (const ContactSideForce& side : sides_[k])
        if (owner_[side.fibre] == rank_)
          y[k] += side.direction.dot(model_->displacement(side.fibre, side.s));
  }
  sum_over_processes(y, comm_);
  return Eigen::Map<Eigen::VectorXd>(y.data(), n);
}

// As the assembled W's solve_on_subset: the set's system as it is, and where that is singular
// (MUMPS finds a null pivot: contacts that constrain the same motion twice) or its solve fails,
// regularised by 1e-10 of its largest self-compliance. The answer is then refined on the set's own
// equations, with the residual b − (W_SS + εI)·x from the beams' factorisation: the saddle point's
// residual is small in the beams' unknowns, but a line contact's compliance is a smooth kernel, and
// MUMPS over several processes leaves the slices' forces 1e-6 apart without it.
bool SaddlePointCompliance::solve_on_subset(const std::vector<Eigen::Index>& index,
                                            const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const Eigen::Index m = static_cast<Eigen::Index>(index.size());
  x.resize(m);
  if (m == 0) return true;
  double epsilon = 0.0;
  if (!factorise(index, epsilon) || !solve_factorised(index, b, x)) {
    epsilon = 1e-10 * self_compliances(index).cwiseAbs().maxCoeff();
    if (!factorise(index, epsilon) || !solve_factorised(index, b, x)) return false;
  }
  Eigen::VectorXd full = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sides_.size())), delta;
  for (int step = 0; step < kRefinements; ++step) {
    for (Eigen::Index i = 0; i < m; ++i) full[index[i]] = x[i];
    const Eigen::VectorXd Wx = times(full);
    Eigen::VectorXd residual(m);
    for (Eigen::Index i = 0; i < m; ++i) residual[i] = b[i] - Wx[index[i]] - epsilon * x[i];
    if (!solve_factorised(index, residual, delta)) return false;
    x += delta;
  }
  return x.allFinite();
}

// [S Bᵀ_S; B_S εI] for the set, the other contacts' rows x_k = 0, factorised by MUMPS over all
// the processes.
bool SaddlePointCompliance::factorise(const std::vector<Eigen::Index>& index,
                                      double regularisation) const {
  set_values(index, regularisation);
  ++factorisations_;
  if (progress_ && std::chrono::steady_clock::now() - last_report_ > std::chrono::seconds(5)) {
    last_report_ = std::chrono::steady_clock::now();
    progress_("  saddle points: " + std::to_string(factorisations_) + " factorisations, a set of " +
              std::to_string(index.size()) + " contacts");
  }
  // The preconditioner sees the new values and factorises again (analysed once: the pattern
  // stays). A failed factorisation is not an error to PETSc: the solve's reason says so.
  PC pc;
  Mat factor;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  check(PCSetUp(pc), "PCSetUp (MUMPS factorisation)");
  check(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
  PetscInt null_pivots = 0;
  check(MatMumpsGetInfog(factor, 28, &null_pivots), "MatMumpsGetInfog");
  return null_pivots == 0 || regularisation > 0.0;
}

// [S Bᵀ_S; B_S εI]·[y; x] = [0; b] by the factorisation just made, judged by its own residual
// (the normwise backward error of the whole system); x gathered on every process.
bool SaddlePointCompliance::solve_factorised(const std::vector<Eigen::Index>& index,
                                             const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const PetscInt m = static_cast<PetscInt>(index.size());
  x.resize(m);
  check(VecSet(rhs_, 0.0), "VecSet");
  for (PetscInt i = 0; i < m; ++i)
    if (owner_[sides_[index[i]].front().fibre] == rank_)
      check(VecSetValue(rhs_, constraint_row_[index[i]], b[i], INSERT_VALUES), "VecSetValue");
  check(VecAssemblyBegin(rhs_), "VecAssemblyBegin");
  check(VecAssemblyEnd(rhs_), "VecAssemblyEnd");
  check(KSPSolve(ksp_, rhs_, solution_), "KSPSolve (MUMPS)");
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
  if (reason < 0) return false;

  Vec residual;
  check(VecDuplicate(rhs_, &residual), "VecDuplicate");
  check(MatMult(A_, solution_, residual), "MatMult");
  check(VecAYPX(residual, -1.0, rhs_), "VecAYPX");
  PetscReal r = 0, a = 0, s = 0, f = 0;
  check(VecNorm(residual, NORM_INFINITY, &r), "VecNorm");
  check(MatNorm(A_, NORM_INFINITY, &a), "MatNorm");
  check(VecNorm(solution_, NORM_INFINITY, &s), "VecNorm");
  check(VecNorm(rhs_, NORM_INFINITY, &f), "VecNorm");
  VecDestroy(&residual);
  if (!std::isfinite(s) || !(r <= kBackwardError * (a * s + f))) return false;

  std::vector<PetscInt> rows(static_cast<std::size_t>(m));
  for (PetscInt i = 0; i < m; ++i) rows[i] = constraint_row_[index[i]];
  IS wanted;
  Vec gathered;
  VecScatter scatter;
  check(ISCreateGeneral(PETSC_COMM_SELF, m, rows.data(), PETSC_COPY_VALUES, &wanted),
        "ISCreateGeneral");
  check(VecCreateSeq(PETSC_COMM_SELF, m, &gathered), "VecCreateSeq");
  check(VecScatterCreate(solution_, wanted, gathered, nullptr, &scatter), "VecScatterCreate");
  check(VecScatterBegin(scatter, solution_, gathered, INSERT_VALUES, SCATTER_FORWARD),
        "VecScatterBegin");
  check(VecScatterEnd(scatter, solution_, gathered, INSERT_VALUES, SCATTER_FORWARD),
        "VecScatterEnd");
  const PetscScalar* values = nullptr;
  check(VecGetArrayRead(gathered, &values), "VecGetArrayRead");
  for (PetscInt i = 0; i < m; ++i) x[i] = values[i];
  check(VecRestoreArrayRead(gathered, &values), "VecRestoreArrayRead");
  VecScatterDestroy(&scatter);
  VecDestroy(&gathered);
  ISDestroy(&wanted);
  return x.allFinite();
}

// Rounds of unit reactions on contacts that share no fibre: in a round, contact k's overlap
// comes from its own reaction alone, W_kk.
Eigen::VectorXd SaddlePointCompliance::self_compliances(
    const std::vector<Eigen::Index>& index) const {
  Eigen::VectorXd w(static_cast<Eigen::Index>(index.size()));
  std::vector<char> done(index.size(), 0);
  const Eigen::Index n = static_cast<Eigen::Index>(sides_.size());
  for (std::size_t left = index.size(); left > 0;) {
    std::vector<char> loaded(fibres_.size(), 0);
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(n);
    std::vector<std::size_t> round;
    for (std::size_t i = 0; i < index.size(); ++i) {
      if (done[i]) continue;
      const auto& sides = sides_[index[i]];
      if (std::any_of(sides.begin(), sides.end(),
                      [&](const ContactSideForce& s) { return loaded[s.fibre] != 0; }))
        continue;
      for (const ContactSideForce& s : sides) loaded[s.fibre] = 1;
      unit[index[i]] = 1.0;
      round.push_back(i);
    }
    const Eigen::VectorXd response = times(unit);
    for (std::size_t i : round) {
      w[static_cast<Eigen::Index>(i)] = response[index[i]];
      done[i] = 1;
      --left;
    }
  }
  return w;
}

std::vector<char> SaddlePointCompliance::immovable() const {
  std::vector<double> movable(sides_.size(), 0.0);
  for (std::size_t k = 0; k < sides_.size(); ++k)
    for (const ContactSideForce& side : sides_[k])
      if (owner_[side.fibre] == rank_)
        for (int plane = 0; plane < 2; ++plane)
          if (model_->deflection_unknown(side.fibre, side.s, plane) >= 0) movable[k] = 1.0;
  sum_over_processes(movable, comm_);
  std::vector<char> result(sides_.size());
  for (std::size_t k = 0; k < sides_.size(); ++k) result[k] = movable[k] == 0.0 ? 1 : 0;
  return result;
}

}  // namespace fibrecheck
