#pragma once

#include <vector>

namespace fibrecheck {

/// A point load on a simply supported beam: force P (N) at distance a (mm) from the first support.
struct BeamLoad {
  double a;
  double P;
};

/// Running sums of one plane's point loads, for evaluating the superposition of Eqs. 4.10–4.13 at
/// any point in O(1) once the loads are sorted by a. With b = L − a:
///   v(x) = [x(L²·Sb − Sb3 − x²·Sb) + (L − x)(Sa·(2Lx − x²) − Sa3)] / (6EIL)
///   M(x) = [x·Sb + (L − x)·Sa] / L
/// where Sb, Sb3 sum P·b, P·b³ over loads with a ≥ x (Eqs. 4.10, 4.12) and Sa, Sa3 sum P·a, P·a³
/// over loads with a < x (Eqs. 4.11, 4.13).
struct BeamSums {
  double Sa = 0, Sa3 = 0, Sb = 0, Sb3 = 0;
};

/// 6EIL times the deflection at x: the bracket of the formula above. T is double, or an Eigen
/// array holding the sums of several bending planes at once (superposition.cc).
template <class T>
inline T scaled_deflection_from_sums(const T& Sa, const T& Sa3, const T& Sb, const T& Sb3, double x,
                                     double L) {
  return x * (L * L * Sb - Sb3 - x * x * Sb) + (L - x) * (Sa * (2 * L * x - x * x) - Sa3);
}

/// The same for one plane's sums.
inline double scaled_deflection_from_sums(const BeamSums& s, double x, double L) {
  return scaled_deflection_from_sums(s.Sa, s.Sa3, s.Sb, s.Sb3, x, L);
}

/// Deflection at x (mm, in the direction of positive P) from the running sums.
inline double deflection_from_sums(const BeamSums& s, double x, double L, double EI) {
  return scaled_deflection_from_sums(s, x, L) / (6.0 * EI * L);
}

/// Bending moment at x (N·mm) from the running sums; T as above.
template <class T>
inline T moment_from_sums(const T& Sa, const T& Sb, double x, double L) {
  return (x * Sb + (L - x) * Sa) / L;
}

/// The same for one plane's sums.
inline double moment_from_sums(const BeamSums& s, double x, double L) {
  return moment_from_sums(s.Sa, s.Sb, x, L);
}

/// Deflection at each x of `points` (sorted ascending) under `loads` (sorted by a), by the prefix
/// sums above: O(k + n). Writes into `deflection` (resized to points.size()).
void superpose_deflection(const std::vector<BeamLoad>& loads, const std::vector<double>& points,
                          double L, double EI, std::vector<double>& deflection);

/// Bending moment at each sorted x under sorted loads, O(k + n).
void superpose_moment(const std::vector<BeamLoad>& loads, const std::vector<double>& points,
                      double L, std::vector<double>& moment);

/// The same deflection summed load by load, O(k·n) — the textbook form of Eqs. 4.12–4.13, kept as
/// the reference for tests and benchmarks.
double point_load_deflection(double P, double a, double x, double L, double EI);
/// Eqs. 4.10–4.11 for one load.
double point_load_moment(double P, double a, double x, double L);

// The uniform-load formulas are inline: the superposition evaluates them at every station.

/// Uniform load q (N/mm) over the whole span: v(x) = q·x(L³ − 2Lx² + x³)/(24EI).
inline double uniform_load_deflection(double q, double x, double L, double EI) {
  return q * x * (L * L * L - 2 * L * x * x + x * x * x) / (24 * EI);
}
/// Uniform load moment: M(x) = q·x(L − x)/2.
inline double uniform_load_moment(double q, double x, double L) {
  return q * x * (L - x) / 2;
}
/// ∫₀ᴸ v dx under a uniform load q: qL⁵/(120EI).
inline double uniform_load_deflection_integral(double q, double L, double EI) {
  return q * L * L * L * L * L / (120 * EI);
}

/// Compliance at the load point, a²b²/(3EIL) (mm/N) — DESIGN §7.
double point_compliance(double a, double L, double EI);

}  // namespace fibrecheck
