#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

namespace fibrecheck {

/// A power law p/E = k(Vfⁿ − Vf0ⁿ) fitted by least squares (n = 3 for van Wyk, fitted for Toll):
/// k dimensionless, Vf0 the volume fraction where the pressure vanishes, R² of the pressures.
struct PowerLawFit {
  bool valid = false;
  double k = NAN, n = NAN, vf0 = NAN, r2 = NAN;
  int points = 0;
};

/// Fits p/E = k(Vfⁿ − Vf0ⁿ) at the given n (pressures and modulus in MPa): linear least squares in
/// Vfⁿ; R² of the pressures. Needs two points with different Vf.
PowerLawFit fit_power_law(const std::vector<double>& vf, const std::vector<double>& pressure,
                          double modulus, double n);
/// The largest exponent Toll's law is fitted with. A fit that ends there asks for a steeper law
/// than any power within reach: its n is a bound, not a measurement.
constexpr double kTollLargestExponent = 30.0;
/// Toll's law: the n in [1, kTollLargestExponent] (steps of 0.01) with the best R². Needs three
/// points.
PowerLawFit fit_toll(const std::vector<double>& vf, const std::vector<double>& pressure,
                     double modulus);

/// {k, vf0, r2, points}, and n where the law's exponent was fitted (Toll's; van Wyk's is 3).
nlohmann::json to_json(const PowerLawFit& fit, bool with_exponent);
/// Without n the exponent is van Wyk's 3.
void from_json(const nlohmann::json& j, PowerLawFit& fit);

}  // namespace fibrecheck
