// The fibre stiffness at loaded stations (the mixed w–M form) and the preconditioner built on it:
// K must be the exact inverse of the simply supported beam's Green's function, and the
// preconditioner the exact inverse of W on a line contact between two parallel fibres.
#include "fibre_stiffness.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "compliance_operator.h"
#include "contact_detection.h"
#include "superposition.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

TEST(FibreStiffness, OneStationAtMidSpanIs48EIOverLCubed) {
  const double L = 2.0, EI = 3.5;
  std::vector<Eigen::Array2d> v = {Eigen::Array2d(1.0, -2.0)};
  FibreStiffness::beam_stiffness(L, EI, {1.0}, v);
  EXPECT_NEAR(v[0][0], 48 * EI / (L * L * L), 1e-12);
  EXPECT_NEAR(v[0][1], -2 * 48 * EI / (L * L * L), 1e-12);
}

// K·G = I for uneven stations, two of them a thousandth of the length apart, in both planes at
// once.
TEST(FibreStiffness, IsTheInverseOfTheGreensFunction) {
  const double L = 1.0, EI = testing::bending_stiffness(0.01, 80000);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> position(0.0, L);
  std::vector<double> x(40);
  for (double& s : x) s = position(random);
  x.push_back(x[3] + 1e-3);
  std::sort(x.begin(), x.end());
  const std::size_t m = x.size();
  for (std::size_t j = 0; j < m; ++j) {
    // Column j of G: deflections under a unit load at x_j (plane 1) and 2 units (plane 2).
    std::vector<Eigen::Array2d> v(m);
    for (std::size_t i = 0; i < m; ++i)
      v[i] = Eigen::Array2d(1.0, 2.0) * testing::unit_load_deflection(x[j], x[i], EI);
    FibreStiffness::beam_stiffness(L, EI, x, v);
    for (std::size_t i = 0; i < m; ++i) {
      EXPECT_NEAR(v[i][0], i == j ? 1.0 : 0.0, 1e-8) << i << ", " << j;
      EXPECT_NEAR(v[i][1], i == j ? 2.0 : 0.0, 2e-8) << i << ", " << j;
    }
  }
}

Eigen::MatrixXd columns(const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& op,
                        Eigen::Index n) {
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd column;
  for (Eigen::Index j = 0; j < n; ++j) {
    op(Eigen::VectorXd::Unit(n, j), column);
    M.col(j) = column;
  }
  return M;
}

// Two parallel fibres of different radius and modulus on common supports: the preconditioner
// inverts the line's W exactly, whatever the slice count, also on a subset of free slices.
TEST(FibreStiffness, InvertsTheComplianceOfALineContact) {
  for (int slices : {10, 100}) {
    const Scene scene = testing::parallel(1e-4, slices);
    const std::vector<Fibre> fibres = make_fibres(scene);
    Superposition superposition(fibres, scene);
    ContactDetector detector(fibres, scene, 0.001);
    std::vector<std::vector<Eigen::Vector3d>> grid(
        fibres.size(),
        std::vector<Eigen::Vector3d>(detector.grid().size(), Eigen::Vector3d::Zero()));
    const std::vector<Contact> contacts = detector.detect(grid);
    const Eigen::Index n = static_cast<Eigen::Index>(contacts.size());
    ASSERT_GE(n, slices - 2);
    superposition.attach(contacts);
    FibreStiffness stiffness(fibres);
    stiffness.attach(contacts);
    const ComplianceOperator op(superposition, contacts);
    const Eigen::MatrixXd W = columns([&](const auto& x, auto& y) { op.apply(x, y); }, n);
    std::vector<unsigned char> free(static_cast<std::size_t>(n), 1);
    const Eigen::MatrixXd Q =
        columns([&](const auto& r, auto& z) { stiffness.apply(r, free, z); }, n);
    EXPECT_LE((Q * W - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-8)
        << slices << " slices";
    // Every third slice free: Q on them inverts W's principal block on them.
    std::vector<Eigen::Index> chosen;
    for (Eigen::Index k = 0; k < n; ++k) {
      free[k] = k % 3 == 0;
      if (free[k]) chosen.push_back(k);
    }
    const Eigen::MatrixXd Qs =
        columns([&](const auto& r, auto& z) { stiffness.apply(r, free, z); }, n);
    const Eigen::Index m = static_cast<Eigen::Index>(chosen.size());
    Eigen::MatrixXd product(m, m);
    for (Eigen::Index i = 0; i < m; ++i)
      for (Eigen::Index j = 0; j < m; ++j) {
        double sum = 0.0;
        for (Eigen::Index k = 0; k < m; ++k)
          sum += Qs(chosen[i], chosen[k]) * W(chosen[k], chosen[j]);
        product(i, j) = sum;
      }
    EXPECT_LE((product - Eigen::MatrixXd::Identity(m, m)).cwiseAbs().maxCoeff(), 1e-8);
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!free[k]) {
        EXPECT_EQ(Qs.row(k).cwiseAbs().maxCoeff(), 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace fibrecheck
