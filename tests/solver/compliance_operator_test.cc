// The contact compliance operator W applied matrix-free: it must be the symmetric positive
// semi-definite Delassus matrix whose diagonal is each contact's own compliance, and the power
// iteration must find its largest eigenvalue.
#include "compliance_operator.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "contact_detection.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

// Three fibres along y pressed onto one along x at different places, plus a parallel pair and a
// wall: point, line and wall contacts all coupled through shared fibres.
Scene coupled_scene() {
  using testing::fibre;
  Scene s;
  s.fibres.push_back(fibre("X", {0, 0, 0}, {1, 0, 0}));
  s.fibres.push_back(fibre("Y1", {0.2, -0.5, 0.019}, {0.2, 0.5, 0.019}));
  s.fibres.push_back(fibre("Y2", {0.55, -0.5, 0.0195}, {0.55, 0.5, 0.0195}));
  s.fibres.push_back(fibre("Y3", {0.8, -0.4, 0.0199}, {0.8, 0.6, 0.0199}, 0.01, 200000));
  s.fibres.push_back(fibre("P", {0, 0.0199, 0}, {1, 0.0199, 0}));
  WallSpec wall;
  wall.id = "floor";
  wall.point = {0, 0, -0.0099};
  wall.normal = {0, 0, 1};
  s.walls.push_back(wall);
  s.contact.slices = 10;
  return s;
}

TEST(ComplianceOperator, IsSymmetricWithSelfCompliancesOnItsDiagonal) {
  const Scene scene = coupled_scene();
  std::vector<Fibre> fibres;
  for (const FibreSpec& f : scene.fibres) fibres.push_back(make_fibre(f, scene.contact.axis, 10.0));
  Superposition superposition(fibres, scene);
  ContactDetector detector(fibres, scene, 0.0025);
  std::vector<std::vector<Eigen::Vector3d>> grid(
      fibres.size(), std::vector<Eigen::Vector3d>(detector.grid().size(), Eigen::Vector3d::Zero()));
  const std::vector<Contact> contacts = detector.detect(grid);
  int kinds[3] = {0, 0, 0};
  for (const Contact& c : contacts) ++kinds[static_cast<int>(c.kind)];
  ASSERT_EQ(kinds[0], 6);  // X and P each cross Y1, Y2, Y3
  ASSERT_GE(kinds[1], 5);  // X–P slices
  ASSERT_GE(kinds[2], 5);  // X, P on the floor
  superposition.attach(contacts);
  const ComplianceOperator op(superposition, contacts);
  const Eigen::Index n = static_cast<Eigen::Index>(contacts.size());
  Eigen::MatrixXd W(n, n);
  Eigen::VectorXd e, column;
  for (Eigen::Index j = 0; j < n; ++j) {
    e = Eigen::VectorXd::Unit(n, j);
    op.apply(e, column);
    W.col(j) = column;
  }
  EXPECT_LE((W - W.transpose()).norm(), 1e-10 * W.norm());
  for (Eigen::Index k = 0; k < n; ++k)
    EXPECT_NEAR(W(k, k), self_compliance(contacts[k], fibres), 1e-9 * W(k, k));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (W + W.transpose()));
  EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-9 * eigen.eigenvalues().maxCoeff());
  const double lambda = op.largest_eigenvalue(200, 1e-10);
  EXPECT_NEAR(lambda, eigen.eigenvalues().maxCoeff(), 1e-6 * lambda);
}

}  // namespace
}  // namespace fibrecheck
