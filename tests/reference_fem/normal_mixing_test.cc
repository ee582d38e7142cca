// The mixing of the deformed contact's normals on a map whose fixed point is known.
#include "normal_mixing.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace fibrecheck {
namespace {

/// Each normal made a unit vector again.
Eigen::VectorXd unit_normals(Eigen::VectorXd x) {
  for (Eigen::Index k = 0; k < x.size(); k += 3) x.segment<3>(k).normalize();
  return x;
}

/// A map of stacked unit normals with the fixed point `fixed` that contracts slowly along one
/// subspace (by `slow`) and fast along the rest (by 0.3), as the geometric update of fibres that
/// roll on each other does: g(x) = the normals of fixed + M·(x − fixed).
struct RollingMap {
  Eigen::VectorXd fixed;
  Eigen::MatrixXd M;
  Eigen::VectorXd operator()(const Eigen::VectorXd& x) const {
    return unit_normals(fixed + M * (x - fixed));
  }
};

RollingMap rolling_map(int contacts, double slow, std::mt19937& random) {
  std::normal_distribution<double> gauss;
  const int n = 3 * contacts;
  Eigen::VectorXd fixed(n);
  for (int i = 0; i < n; ++i) fixed[i] = gauss(random);
  const Eigen::VectorXd normals = unit_normals(fixed);
  // The slow turns lie in each contact's tangent plane, as a rolling fibre's do.
  Eigen::MatrixXd B(n, 2);
  for (int i = 0; i < n; ++i) B(i, 0) = gauss(random), B(i, 1) = gauss(random);
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k < n; k += 3)
      B.col(j).segment<3>(k) -=
          normals.segment<3>(k).dot(B.col(j).segment<3>(k)) * normals.segment<3>(k);
  const Eigen::MatrixXd Q = B.householderQr().householderQ() * Eigen::MatrixXd::Identity(n, 2);
  const Eigen::MatrixXd projection = Q * Q.transpose();
  return {normals, slow * projection + 0.3 * (Eigen::MatrixXd::Identity(n, n) - projection)};
}

/// Updates until no normal turns by more than `turn`, mixing or not; the count, or -1 after `cap`.
int updates_to(const RollingMap& map, Eigen::VectorXd x, double turn, bool mixing, int cap,
               Eigen::VectorXd* end = nullptr) {
  NormalMixing mix(4);
  for (int update = 1; update <= cap; ++update) {
    const Eigen::VectorXd g = map(x);
    if ((g - x).lpNorm<Eigen::Infinity>() <= turn) {
      if (end) *end = g;
      return update;
    }
    x = mixing ? mix.mix(x, g) : g;
  }
  return -1;
}

// The plain update shrinks the slow turn by 0.95 an update: from a few hundredths of a radian to
// 1e-10 it takes about 300 updates (303 here; mixing takes 9). Mixing sees the two rates and
// removes the slow one as a Krylov method would: the normalisation leaves it nonlinear, but near
// the fixed point only by the square of the turn.
TEST(NormalMixing, TurnsSlowlyContractingNormalsToTheirFixedPointInFewUpdates) {
  std::mt19937 random(5);
  const RollingMap map = rolling_map(50, 0.95, random);
  std::normal_distribution<double> gauss;
  Eigen::VectorXd start = map.fixed;
  for (Eigen::Index i = 0; i < start.size(); ++i) start[i] += 0.03 * gauss(random);
  start = unit_normals(start);
  const int plain = updates_to(map, start, 1e-10, false, 2000);
  Eigen::VectorXd end;
  const int mixed = updates_to(map, start, 1e-10, true, 2000, &end);
  EXPECT_GT(plain, 200);
  ASSERT_GT(mixed, 0);
  EXPECT_LT(mixed, 25);
  EXPECT_LT((end - map.fixed).lpNorm<Eigen::Infinity>(), 1e-9);
  for (Eigen::Index k = 0; k < end.size(); k += 3)
    EXPECT_NEAR(end.segment<3>(k).norm(), 1.0, 1e-14);
}

// Restarted, the mixing remembers nothing: its next answer is the followed normals themselves.
TEST(NormalMixing, RestartedGivesTheFollowedNormals) {
  std::mt19937 random(6);
  const RollingMap map = rolling_map(4, 0.9, random);
  NormalMixing mix(4);
  Eigen::VectorXd x = unit_normals(map.fixed + 0.1 * Eigen::VectorXd::Ones(map.fixed.size()));
  for (int update = 0; update < 3; ++update) x = mix.mix(x, map(x));
  const Eigen::VectorXd g = map(x);
  EXPECT_NE(mix.mix(x, g), g);
  mix.restart();
  EXPECT_EQ(mix.mix(x, g), g);
}

}  // namespace
}  // namespace fibrecheck
