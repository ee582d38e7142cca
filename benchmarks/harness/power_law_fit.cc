#include "power_law_fit.h"

#include <cmath>

#include "json_number.h"

namespace fibrecheck {

PowerLawFit fit_power_law(const std::vector<double>& vf, const std::vector<double>& pressure,
                          double modulus, double n) {
  PowerLawFit f;
  f.n = n;
  f.points = static_cast<int>(vf.size());
  if (vf.size() < 2 || !(modulus > 0.0)) return f;
  const double m = static_cast<double>(vf.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0, mean_p = 0;
  for (std::size_t i = 0; i < vf.size(); ++i) {
    const double x = std::pow(vf[i], n), y = pressure[i] / modulus;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    mean_p += pressure[i] / m;
  }
  const double det = m * sxx - sx * sx;
  if (!(std::fabs(det) > 1e-300)) return f;
  const double a = (m * sxy - sx * sy) / det, b = (sy - a * sx) / m;
  double residual = 0.0, total = 0.0;
  for (std::size_t i = 0; i < vf.size(); ++i) {
    const double predicted = modulus * (a * std::pow(vf[i], n) + b);
    residual += (pressure[i] - predicted) * (pressure[i] - predicted);
    total += (pressure[i] - mean_p) * (pressure[i] - mean_p);
  }
  f.valid = true;
  f.k = a;
  f.vf0 = (a != 0.0 && -b / a > 0.0) ? std::pow(-b / a, 1.0 / n) : NAN;
  f.r2 = total > 0.0 ? 1.0 - residual / total : NAN;
  return f;
}

PowerLawFit fit_toll(const std::vector<double>& vf, const std::vector<double>& pressure,
                     double modulus) {
  PowerLawFit best;
  best.points = static_cast<int>(vf.size());
  if (vf.size() < 3) return best;
  const int last = static_cast<int>(std::lround(100.0 * kTollLargestExponent));
  for (int i = 100; i <= last; ++i) {
    const PowerLawFit f = fit_power_law(vf, pressure, modulus, 0.01 * i);
    if (f.valid && std::isfinite(f.r2) && (!best.valid || f.r2 > best.r2)) best = f;
  }
  return best;
}

nlohmann::json to_json(const PowerLawFit& f, bool with_exponent) {
  nlohmann::json j = {{"k", number_or_null(f.k)},
                      {"vf0", number_or_null(f.vf0)},
                      {"r2", number_or_null(f.r2)},
                      {"points", f.points}};
  if (with_exponent) j["n"] = number_or_null(f.n);
  return j;
}

void from_json(const nlohmann::json& j, PowerLawFit& f) {
  f.k = number_at(j, "k");
  f.vf0 = number_at(j, "vf0");
  f.r2 = number_at(j, "r2");
  f.n = j.contains("n") ? number_at(j, "n") : 3.0;
  f.points = j.at("points").get<int>();
  f.valid = std::isfinite(f.k);
}

}  // namespace fibrecheck
