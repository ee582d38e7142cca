#pragma once

#include <type_traits>

namespace fibrecheck {

/// Running sums of point loads on a simply supported beam of length L, for evaluating the
/// superposition of Eqs. 4.10–4.13 at any point x in O(1) once the loads are sorted by their
/// distance a from the first support. With b = L − a:
///   v(x) = [x(L²·Sb − Sb3 − x²·Sb) + (L − x)(Sa·(2Lx − x²) − Sa3)] / (6EIL)
///   M(x) = [x·Sb + (L − x)·Sa] / L
/// where Sb, Sb3 sum P·b, P·b³ over the loads with a ≥ x (Eqs. 4.10, 4.12) and Sa, Sa3 sum P·a,
/// P·a³ over the loads with a < x (Eqs. 4.11, 4.13). Sweeping x from 0 to L moves each load once
/// from the right sums to the left ones: k loads at n sorted points cost O(k + n).
/// T is double for one bending plane, or an Eigen array holding several planes (lane by lane, the
/// same arithmetic).
template <class T>
struct RunningSums {
  static T zero() {
    if constexpr (std::is_arithmetic_v<T>)
      return T(0);
    else
      return T::Zero();
  }
  T Sa = zero(), Sa3 = zero(), Sb = zero(), Sb3 = zero();

  /// Adds a load P at distance b from the second support to the "a ≥ x" sums.
  void add_right(const T& P, double b) {
    Sb += P * b;
    Sb3 += P * b * b * b;
  }
  /// Moves a load from the "a ≥ x" sums to the "a < x" sums.
  void move_left(const T& P, double a, double b) {
    Sb -= P * b;
    Sb3 -= P * b * b * b;
    Sa += P * a;
    Sa3 += P * a * a * a;
  }
  /// The same for the moments alone, which need no cubes.
  void move_left_moment(const T& P, double a, double b) {
    Sb -= P * b;
    Sa += P * a;
  }
  /// 6EIL·v(x): the bracket of the formula above (Eqs. 4.12–4.13).
  T scaled_deflection(double x, double L) const {
    return x * (L * L * Sb - Sb3 - x * x * Sb) + (L - x) * (Sa * (2 * L * x - x * x) - Sa3);
  }
  /// M(x) (Eqs. 4.10–4.11).
  T moment(double x, double L) const { return (x * Sb + (L - x) * Sa) / L; }
};

/// Deflection at x (mm, along P) under one point load P (N) at a (mm): Eqs. 4.12–4.13 as printed.
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
