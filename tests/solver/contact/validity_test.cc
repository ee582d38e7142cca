// Validity of small-deflection theory, read off a result's samples.

#include "validity.h"

#include <gtest/gtest.h>

#include "fibre.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

// A fibre of length 1 along x, radius 0.01, its samples on the parabola w = 4·w0·s(1 − s): the
// largest deflection w0 at mid-span, the largest slope 4·w0 at the supports (less half a sample
// step by differences: 4·w0·(1 − Δs)).
Result parabola(double w0, int samples = 101) {
  Result r;
  FibreResult f;
  f.id = "A";
  for (int j = 0; j < samples; ++j) {
    const double s = static_cast<double>(j) / (samples - 1);
    f.displacement.emplace_back(0.3 * w0, 0.0, -4.0 * w0 * s * (1.0 - s));  // axial part ignored
  }
  r.fibres.push_back(f);
  return r;
}

std::vector<Fibre> one_fibre(double length = 1.0, double radius = 0.01) {
  Scene s;
  s.fibres.push_back(testing::fibre("A", {0, 0, 0}, {length, 0, 0}, radius));
  return make_fibres(s);
}

TEST(Validity, DeflectionAndSlopeComeFromTheSamples) {
  Result r = parabola(0.02);
  assess_validity(r, one_fibre());
  EXPECT_NEAR(r.max_deflection_over_radius, 2.0, 1e-12);
  EXPECT_NEAR(r.max_slope, 4 * 0.02 * (1 - 0.01), 1e-12);
  EXPECT_TRUE(r.warnings.empty());  // 0.079 rad: within small-deflection theory
}

TEST(Validity, SteepFibresAreFlaggedWithTheStatusLeftAlone) {
  Result r = parabola(0.19);  // the slope of coincident fibres pushed 19 radii apart
  r.status = Status::converged;
  assess_validity(r, one_fibre());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("outside small-deflection theory"), std::string::npos);
  EXPECT_NE(r.warnings[0].find("fibre A"), std::string::npos);
  EXPECT_EQ(r.status, Status::converged);
}

TEST(Validity, StubbyFibresAreFlaggedForShear) {
  Result r = parabola(1e-6);
  assess_validity(r, one_fibre(1.0, 0.1));  // L/r = 10: 8.8 % from shear
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("shear deformation"), std::string::npos);
  Result slender = parabola(1e-6);
  assess_validity(slender, one_fibre(1.0, 0.03));  // L/r = 33: 0.8 %
  EXPECT_TRUE(slender.warnings.empty());
}

}  // namespace
}  // namespace fibrecheck
