// The reference shared out over several MPI processes gives the answer of one process: run by
// ctest under `mpiexec -np 2`, and after the program's own run on three processes.
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "blas_threads.h"
#include "reference_solver.h"
#include "shared_compliance.h"

namespace fibrecheck {
namespace {

std::vector<double> forces_and_displacements(const Result& r) {
  std::vector<double> values;
  for (const ContactResult& c : r.contacts)
    for (const ContactPoint& p : c.points)
      values.insert(values.end(), p.force.data(), p.force.data() + 3);
  for (const FibreResult& f : r.fibres)
    for (const Eigen::Vector3d& u : f.displacement)
      values.insert(values.end(), u.data(), u.data() + 3);
  return values;
}

TEST(ReferenceMpi, TwoProcessesGiveTheAnswerOfOne) {
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) != 2)
    GTEST_SKIP() << "run this test with mpiexec -np 2";
  const Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/small_tow_19.json");
  ReferenceOptions alone;
  alone.communicator = MPI_COMM_SELF;
  const Result one = solve_reference(scene, alone);
  const Result two = solve_reference(scene);  // MPI_COMM_WORLD: the fibres shared out
  ASSERT_EQ(one.status, Status::converged) << one.message;
  ASSERT_EQ(two.status, Status::converged) << two.message;
  EXPECT_EQ(one.finite_elements->unknowns, two.finite_elements->unknowns);
  ASSERT_EQ(one.contacts.size(), two.contacts.size());
  const std::vector<double> x = forces_and_displacements(one), y = forces_and_displacements(two);
  ASSERT_EQ(x.size(), y.size());
  // Forces (~1e-4 N) and displacements (~1e-3 mm) to round-off of the two factorisations.
  double force_scale = 0.0;
  for (const ContactResult& c : one.contacts)
    for (const ContactPoint& p : c.points) force_scale = std::max(force_scale, p.force.norm());
  const std::size_t forces = 3 * [&] {
    std::size_t n = 0;
    for (const ContactResult& c : one.contacts) n += c.points.size();
    return n;
  }();
  double largest_u = 0.0;
  for (std::size_t i = forces; i < x.size(); ++i) largest_u = std::max(largest_u, std::fabs(x[i]));
  for (std::size_t i = 0; i < x.size(); ++i)
    EXPECT_NEAR(x[i], y[i], 1e-9 * (i < forces ? force_scale : largest_u)) << i;
  // And both processes hold the same result.
  std::vector<double> first = y;
  MPI_Bcast(first.data(), static_cast<int>(first.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_EQ(first[i], y[i]) << i;
  EXPECT_NE(std::find(two.stages.begin(), two.stages.end(), "mpi_2_processes"), two.stages.end());
}

// W shared out over two processes, each holding part of every shared entry (as two fibres give
// parts of one contact's W_jk), acts as the whole W on one: products to the round-off of one sum,
// solves on a set to that of a factorisation of a well-conditioned matrix, the same bits on both
// processes.
TEST(ReferenceMpi, SharedComplianceActsAsTheWholeOnOne) {
  const int rank = static_cast<int>(dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD));
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) != 2)
    GTEST_SKIP() << "run this test with mpiexec -np 2";
  // W = I + A·Aᵀ, A banded: sparse, symmetric, positive definite, condition about 10.
  constexpr int n = 40;
  Eigen::SparseMatrix<double> A(n, n);
  std::vector<Eigen::Triplet<double>> a;
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - 2); j <= std::min(n - 1, i + 2); ++j)
      a.emplace_back(i, j, 0.3 + 0.1 * ((3 * i + 7 * j) % 5));
  A.setFromTriplets(a.begin(), a.end());
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  const Eigen::SparseMatrix<double> W = identity + Eigen::SparseMatrix<double>(A * A.transpose());
  // Process r's part: a quarter (r = 0) or three quarters (r = 1) of each entry.
  const Eigen::SparseMatrix<double> part = (rank == 0 ? 0.25 : 0.75) * W;
  const AssembledCompliance whole(W);
  const SharedCompliance shared(part, MPI_COMM_WORLD);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < n; k += 3) x[k] = 1.0 + 0.01 * k;
  const Eigen::VectorXd Wx = whole.times(x), Sx = shared.times(x);
  EXPECT_LE((Wx - Sx).cwiseAbs().maxCoeff(), 1e-15 * Wx.cwiseAbs().maxCoeff() * n);
  const Eigen::VectorXd d = shared.diagonal();
  for (int k = 0; k < n; ++k) EXPECT_NEAR(d[k], W.coeff(k, k), 1e-15 * W.coeff(k, k));
  const std::vector<Eigen::Index> set = {1, 2, 3, 7, 8, 20, 21, 22, 39};
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(set.size()), 1, 2);
  Eigen::VectorXd from_whole, from_shared;
  ASSERT_TRUE(whole.solve_on_subset(set, b, from_whole));
  ASSERT_TRUE(shared.solve_on_subset(set, b, from_shared));
  EXPECT_LE((from_whole - from_shared).cwiseAbs().maxCoeff(),
            1e-13 * from_whole.cwiseAbs().maxCoeff());
  Eigen::VectorXd first = from_shared;
  MPI_Bcast(first.data(), static_cast<int>(first.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (Eigen::Index i = 0; i < first.size(); ++i) EXPECT_EQ(first[i], from_shared[i]) << i;
}

// The contact problem held as saddle points over two processes (each holds one fibre's unknowns,
// and the line contact's rows couple them) gives the answer of the compliance matrix on one: the
// deflections to 1e-9, the slices' forces to 1e-5 of the largest. A line contact's compliance is
// a smooth kernel that determines its slices' forces less well than its deflections: the
// compliance matrix itself gives slice forces 1.5e-6 of the largest apart on one process and two
// (parallel_fibres, December 2026), and the saddle points on two 1.2e-6 from it on one.
TEST(ReferenceMpi, SaddlePointsOverTwoProcessesGiveTheAnswerOfOne) {
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) != 2)
    GTEST_SKIP() << "run this test with mpiexec -np 2";
  const Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/parallel_fibres.json");
  ReferenceOptions alone;
  alone.communicator = MPI_COMM_SELF;
  ReferenceOptions shared;
  shared.contact_assembly = ContactAssembly::saddle_point;
  const Result one = solve_reference(scene, alone);
  const Result two = solve_reference(scene, shared);
  ASSERT_EQ(one.status, Status::converged) << one.message;
  ASSERT_EQ(two.status, Status::converged) << two.message;
  EXPECT_NE(two.message.find("held as saddle points"), std::string::npos) << two.message;
  const std::vector<double> x = forces_and_displacements(one), y = forces_and_displacements(two);
  ASSERT_EQ(x.size(), y.size());
  std::size_t forces = 0;
  double force_scale = 0.0, largest_u = 0.0;
  for (const ContactResult& c : one.contacts)
    for (const ContactPoint& p : c.points) force_scale = std::max(force_scale, p.force.norm());
  for (const ContactResult& c : one.contacts) forces += 3 * c.points.size();
  for (std::size_t i = forces; i < x.size(); ++i) largest_u = std::max(largest_u, std::fabs(x[i]));
  for (std::size_t i = 0; i < x.size(); ++i)
    EXPECT_NEAR(x[i], y[i], i < forces ? 1e-5 * force_scale : 1e-9 * largest_u) << i;
  std::vector<double> first = y;
  MPI_Bcast(first.data(), static_cast<int>(first.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_EQ(first[i], y[i]) << i;
}

// Two processes on one machine share its cores with OpenBLAS: each may start at most its share of
// threads (OpenBLAS alone would start one per core in each).
TEST(ReferenceMpi, ProcessesShareTheCoresWithOpenBlas) {
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) != 2)
    GTEST_SKIP() << "run this test with mpiexec -np 2";
  if (blas_threads() < 0) GTEST_SKIP() << "the BLAS is not OpenBLAS";
  const Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/two_fibres_crossing.json");
  ASSERT_EQ(solve_reference(scene).status, Status::converged);
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  EXPECT_LE(blas_threads(), std::max(1, cores / 2));
}

// `mpiexec -np 3 fibrecheck fem` on the two crossing fibres (run by ctest before this test, which
// runs alone): the process that owns no fibre takes part in every sum, and the program writes
// the answer of one process — the same force, energy and displacements.
TEST(ReferenceMpi, ProgramOnMoreProcessesThanFibresGivesTheAnswerOfOne) {
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) != 1)
    GTEST_SKIP() << "run this test on one process, after the three-process run";
  const Result three = read_result(FIBRECHECK_THREE_PROCESS_RESULT);
  const Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/two_fibres_crossing.json");
  const Result one = solve_reference(scene);
  ASSERT_EQ(one.status, Status::converged) << one.message;
  EXPECT_EQ(three.status, Status::converged) << three.message;
  EXPECT_NE(std::find(three.stages.begin(), three.stages.end(), "mpi_3_processes"),
            three.stages.end());
  ASSERT_EQ(three.contacts.size(), 1u);
  ASSERT_EQ(one.contacts.size(), 1u);
  // Results are written with 17 significant digits; the factorisations differ only in round-off.
  EXPECT_NEAR(three.contacts[0].total_force, one.contacts[0].total_force,
              1e-9 * one.contacts[0].total_force);
  EXPECT_NEAR(three.strain_energy_exact, one.strain_energy_exact, 1e-9 * one.strain_energy_exact);
  const std::vector<double> x = forces_and_displacements(one), y = forces_and_displacements(three);
  ASSERT_EQ(x.size(), y.size());
  double largest = 0.0;
  for (double v : x) largest = std::max(largest, std::fabs(v));
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], y[i], 1e-9 * largest) << i;
}

}  // namespace
}  // namespace fibrecheck

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  // Only the first process reports, so ctest's log is read once.
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
        ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  return RUN_ALL_TESTS();
}
