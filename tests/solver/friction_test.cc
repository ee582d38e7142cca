// Friction of §4.3.4: keep the previous resultant (Eqs. 4.29–4.30), capped by Coulomb (4.31–4.33).
#include "friction.h"

#include <gtest/gtest.h>

namespace fibrecheck {
namespace {

TEST(Friction, KeepsTheTangentialPartOfThePreviousResultantBelowTheCap) {
  // The normal turned from z towards y; the old resultant was purely along z.
  const Eigen::Vector3d previous(0, 0, 1e-4);
  const Eigen::Vector3d normal = Eigen::Vector3d(0, 0.1, 1).normalized();
  const Eigen::Vector3d f = coulomb_capped_friction(previous, normal, 1e-4, 0.5);
  EXPECT_NEAR(f.dot(normal), 0.0, 1e-18);
  // Below the cap the new normal part plus friction reproduce the old resultant exactly.
  EXPECT_NEAR((previous.dot(normal) * normal + f - previous).norm(), 0.0, 1e-18);
}

TEST(Friction, CapsAtMuTimesTheNormalForce) {
  const Eigen::Vector3d previous(0, 1e-4, 1e-4);
  const Eigen::Vector3d normal(0, 0, 1);
  for (double mu : {0.0, 0.1, 0.3}) {
    const Eigen::Vector3d f = coulomb_capped_friction(previous, normal, 2e-4, mu);
    EXPECT_NEAR(f.norm(), std::min(1e-4, mu * 2e-4), 1e-20) << "mu = " << mu;
    if (mu > 0) {
      EXPECT_NEAR(f.normalized().dot(Eigen::Vector3d::UnitY()), 1.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace fibrecheck
