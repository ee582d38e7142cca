// The line quadratures of a line contact (seed §4.3.3, Eq. 4.28). Test problem: rules on [0, 1].
// Known answers, written out here:
//  - slices(n): the midpoints (i + 1/2)/n, i = 0…n−1, each of weight 1/n (Eq. 4.28);
//  - gauss(cells): in cell i the two points (i + 1/2 ∓ 1/(2√3))/cells, each of weight 1/(2·cells);
//  - the weights of either rule sum to 1;
//  - the midpoint rule integrates linears exactly, but x² only to 1/3 − 1/(12n²);
//  - the two-point Gauss rule integrates cubics exactly, but x⁴ on one cell only to
//    1/5 − 1/180 (its error f⁗·h⁵/4320 with f⁗ = 24, h = 1), on c cells to 1/5 − 1/(180c⁴).
#include "line_quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace fibrecheck {
namespace {

// Positions and weights are one or two roundings of numbers ≤ 1 (a few ulp, ~1e-16); integrals of
// polynomials of degree ≤ 4 with coefficients ≤ 1 over ≤ 200 points add at most ~200 ulp.
constexpr double kPosition = 1e-15;
constexpr double kIntegral = 1e-13;

double integrate(const LineQuadrature& q, const std::function<double(double)>& f) {
  double sum = 0;
  for (int i = 0; i < q.size(); ++i) sum += q.weight[i] * f(q.position[i]);
  return sum;
}

double weight_sum(const LineQuadrature& q) {
  double sum = 0;
  for (double w : q.weight) sum += w;
  return sum;
}

TEST(LineQuadrature, SlicesAreTheMidpointsOfNEqualIntervalsWithWeightOneOverN) {
  for (int n : {1, 2, 3, 7, 50, 200}) {
    const LineQuadrature q = LineQuadrature::slices(n);
    ASSERT_EQ(q.size(), n);
    ASSERT_EQ(q.weight.size(), q.position.size());
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(q.position[i], (2.0 * i + 1.0) / (2.0 * n), kPosition) << "n " << n << " i " << i;
      EXPECT_DOUBLE_EQ(q.weight[i], 1.0 / n);
      // Symmetric about the middle of the line, strictly inside it.
      EXPECT_NEAR(q.position[i] + q.position[n - 1 - i], 1.0, kPosition);
      EXPECT_GT(q.position[i], 0.0);
      EXPECT_LT(q.position[i], 1.0);
      if (i > 0) {
        EXPECT_GT(q.position[i], q.position[i - 1]);
      }
    }
    EXPECT_NEAR(weight_sum(q), 1.0, n * 1e-16);
  }
  // One slice sits at the middle and carries the whole line.
  const LineQuadrature one = LineQuadrature::slices(1);
  EXPECT_EQ(one.position[0], 0.5);
  EXPECT_EQ(one.weight[0], 1.0);
}

TEST(LineQuadrature, NoSlicesIsAnEmptyRule) {
  EXPECT_EQ(LineQuadrature::slices(0).size(), 0);
  EXPECT_EQ(LineQuadrature::gauss(0).size(), 0);
}

TEST(LineQuadrature, GaussGivesTwoPointsPerCellWithWeightHalfACell) {
  const double offset = 1.0 / (2.0 * std::sqrt(3.0));
  for (int cells : {1, 2, 5, 64}) {
    const LineQuadrature q = LineQuadrature::gauss(cells);
    ASSERT_EQ(q.size(), 2 * cells);
    ASSERT_EQ(q.weight.size(), q.position.size());
    for (int i = 0; i < cells; ++i) {
      EXPECT_NEAR(q.position[2 * i], (i + 0.5 - offset) / cells, kPosition);
      EXPECT_NEAR(q.position[2 * i + 1], (i + 0.5 + offset) / cells, kPosition);
      EXPECT_DOUBLE_EQ(q.weight[2 * i], 1.0 / (2.0 * cells));
      EXPECT_DOUBLE_EQ(q.weight[2 * i + 1], 1.0 / (2.0 * cells));
      // Both points lie inside their own cell.
      EXPECT_GT(q.position[2 * i], static_cast<double>(i) / cells);
      EXPECT_LT(q.position[2 * i + 1], static_cast<double>(i + 1) / cells);
    }
    for (int k = 1; k < q.size(); ++k) EXPECT_GT(q.position[k], q.position[k - 1]);
    EXPECT_NEAR(weight_sum(q), 1.0, 2 * cells * 1e-16);
  }
}

TEST(LineQuadrature, MidpointRuleIsExactForLinearsButNotForQuadratics) {
  for (int n : {1, 3, 10}) {
    const LineQuadrature q = LineQuadrature::slices(n);
    EXPECT_NEAR(integrate(q, [](double) { return 1.0; }), 1.0, kIntegral);
    EXPECT_NEAR(integrate(q, [](double x) { return x; }), 0.5, kIntegral);
    EXPECT_NEAR(integrate(q, [](double x) { return 3.0 - 2.0 * x; }), 2.0, kIntegral);
    // The error on x² is exactly −1/(12n²): the rule is of second order, not higher.
    EXPECT_NEAR(integrate(q, [](double x) { return x * x; }), 1.0 / 3.0 - 1.0 / (12.0 * n * n),
                kIntegral);
  }
}

TEST(LineQuadrature, GaussRuleIsExactForCubicsButNotForQuartics) {
  for (int cells : {1, 2, 7}) {
    const LineQuadrature q = LineQuadrature::gauss(cells);
    EXPECT_NEAR(integrate(q, [](double) { return 1.0; }), 1.0, kIntegral);
    EXPECT_NEAR(integrate(q, [](double x) { return x; }), 0.5, kIntegral);
    EXPECT_NEAR(integrate(q, [](double x) { return x * x; }), 1.0 / 3.0, kIntegral);
    EXPECT_NEAR(integrate(q, [](double x) { return x * x * x; }), 0.25, kIntegral);
    EXPECT_NEAR(integrate(q, [](double x) { return 1 - 4 * x + 6 * x * x - 4 * x * x * x; }),
                1.0 - 2.0 + 2.0 - 1.0, kIntegral);
    const double c4 = std::pow(cells, 4);
    EXPECT_NEAR(integrate(q, [](double x) { return x * x * x * x; }), 0.2 - 1.0 / (180.0 * c4),
                kIntegral);
  }
}

}  // namespace
}  // namespace fibrecheck
