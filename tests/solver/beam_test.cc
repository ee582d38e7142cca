// Beam superposition (seed §4.3.1, Eqs. 4.10–4.13). Test problem: a simply supported beam,
// L = 1 mm, EI = 6.2832e-4 N·mm² (r = 0.01 mm, E = 80 GPa); the closed forms are the textbook
// ones, written out here independently of the code under test.
#include "beam.h"

#include <gtest/gtest.h>

#include <random>

namespace fibrecheck {
namespace {

constexpr double L = 1.0;
const double EI = 80000.0 * M_PI * 1e-8 / 4.0;

double textbook_deflection(double P, double a, double x) {
  const double b = L - a;
  if (x <= a) return P * b * x * (L * L - b * b - x * x) / (6 * EI * L);
  const double xr = L - x;  // mirror image
  return P * a * xr * (L * L - a * a - xr * xr) / (6 * EI * L);
}

TEST(Beam, SinglePointLoadMatchesEquations4_12And4_13) {
  for (double a : {0.1, 0.37, 0.5, 0.83}) {
    for (double x : {0.0, 0.05, 0.2, a, 0.61, 0.99, 1.0}) {
      const double expected = textbook_deflection(2e-4, a, x);
      EXPECT_NEAR(point_load_deflection(2e-4, a, x, L, EI), expected,
                  1e-14 + 1e-12 * std::fabs(expected))
          << "a = " << a << ", x = " << x;
    }
  }
}

TEST(Beam, SinglePointLoadMomentMatchesEquations4_10And4_11) {
  const double P = 3e-4, a = 0.3;
  EXPECT_NEAR(point_load_moment(P, a, a, L), P * a * (L - a) / L, 1e-18);
  EXPECT_NEAR(point_load_moment(P, a, 0.1, L), P * 0.1 * (L - a) / L, 1e-18);
  EXPECT_NEAR(point_load_moment(P, a, 0.9, L), P * a * (L - 0.9) / L, 1e-18);
  EXPECT_EQ(point_load_moment(P, a, 0.0, L), 0.0);
  EXPECT_NEAR(point_load_moment(P, a, L, L), 0.0, 1e-20);
}

TEST(Beam, ComplianceAtTheLoadIsA2B2Over3EIL) {
  for (double a : {0.05, 0.25, 0.5, 0.9}) {
    const double deflection = point_load_deflection(1.0, a, a, L, EI);
    EXPECT_NEAR(point_compliance(a, L, EI), deflection, 1e-12 * deflection);
    EXPECT_NEAR(point_compliance(a, L, EI), a * a * (L - a) * (L - a) / (3 * EI * L), 1e-12);
  }
  EXPECT_EQ(point_compliance(0.0, L, EI), 0.0);
}

struct Load {
  double a, P;
};

// The running sums swept over sorted points, as the superposition sweeps them.
void sweep(const std::vector<Load>& loads, const std::vector<double>& x, std::vector<double>& v,
           std::vector<double>& m) {
  RunningSums<double> sums;
  for (const Load& l : loads) sums.add_right(l.P, L - l.a);
  std::size_t moved = 0;
  for (double at : x) {
    for (; moved < loads.size() && loads[moved].a < at; ++moved)
      sums.move_left(loads[moved].P, loads[moved].a, L - loads[moved].a);
    v.push_back(sums.scaled_deflection(at, L) / (6.0 * EI * L));
    m.push_back(sums.moment(at, L));
  }
}

TEST(Beam, RunningSumsEqualTheLoadByLoadSum) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> where(0.0, L), force(-1e-4, 1e-4);
  for (int k : {1, 2, 7, 64}) {
    std::vector<Load> loads(k);
    for (Load& l : loads) l = {where(rng), force(rng)};
    loads.push_back({0.5, 1e-4});  // a load exactly at an evaluation point
    std::sort(loads.begin(), loads.end(), [](auto& p, auto& q) { return p.a < q.a; });
    std::vector<double> x;
    for (int i = 0; i <= 40; ++i) x.push_back(i / 40.0);
    std::vector<double> v, m;
    sweep(loads, x, v, m);
    for (std::size_t i = 0; i < x.size(); ++i) {
      double v_ref = 0.0, m_ref = 0.0;
      for (const Load& l : loads) {
        v_ref += textbook_deflection(l.P, l.a, x[i]);
        m_ref += point_load_moment(l.P, l.a, x[i], L);
      }
      EXPECT_NEAR(v[i], v_ref, 1e-13) << "k = " << k << ", x = " << x[i];
      EXPECT_NEAR(m[i], m_ref, 1e-16) << "k = " << k << ", x = " << x[i];
    }
  }
}

TEST(Beam, UniformLoadClosedForms) {
  const double q = 1e-4;
  EXPECT_NEAR(uniform_load_deflection(q, 0.5, L, EI), 5 * q / (384 * EI), 1e-15);
  EXPECT_NEAR(uniform_load_moment(q, 0.5, L), q / 8, 1e-18);
  // ∫v dx by three-point Gauss–Legendre, exact for the quartic.
  double integral = 0.0;
  const double nodes[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)},
               weights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int i = 0; i < 3; ++i)
    integral += 0.5 * L * weights[i] * uniform_load_deflection(q, 0.5 * L * (1 + nodes[i]), L, EI);
  EXPECT_NEAR(uniform_load_deflection_integral(q, L, EI), integral, 1e-9 * integral);
  // Many equal point loads approach the uniform load.
  std::vector<Load> loads;
  const int k = 2000;
  for (int i = 0; i < k; ++i) loads.push_back({(i + 0.5) / k, q / k});
  std::vector<double> v, m;
  sweep(loads, {0.5}, v, m);
  EXPECT_NEAR(v[0], 5 * q / (384 * EI), 1e-6 * v[0]);
}

}  // namespace
}  // namespace fibrecheck
