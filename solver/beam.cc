#include "beam.h"

#include <cassert>

namespace fibrecheck {

void superpose_deflection(const std::vector<BeamLoad>& loads, const std::vector<double>& points,
                          double L, double EI, std::vector<double>& deflection) {
  BeamSums s;
  for (const BeamLoad& l : loads) {
    const double b = L - l.a;
    s.Sb += l.P * b;
    s.Sb3 += l.P * b * b * b;
  }
  deflection.resize(points.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = points[i];
    // Loads strictly before x move from the "a ≥ x" sums to the "a < x" sums.
    for (; j < loads.size() && loads[j].a < x; ++j) {
      const double a = loads[j].a, b = L - a, P = loads[j].P;
      s.Sb -= P * b;
      s.Sb3 -= P * b * b * b;
      s.Sa += P * a;
      s.Sa3 += P * a * a * a;
    }
    deflection[i] = deflection_from_sums(s, x, L, EI);
  }
}

void superpose_moment(const std::vector<BeamLoad>& loads, const std::vector<double>& points,
                      double L, std::vector<double>& moment) {
  BeamSums s;
  for (const BeamLoad& l : loads) s.Sb += l.P * (L - l.a);
  moment.resize(points.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = points[i];
    for (; j < loads.size() && loads[j].a < x; ++j) {
      s.Sb -= loads[j].P * (L - loads[j].a);
      s.Sa += loads[j].P * loads[j].a;
    }
    moment[i] = moment_from_sums(s, x, L);
  }
}

double point_load_deflection(double P, double a, double x, double L, double EI) {
  if (x <= a) return P * x * (L - a) * (-a * a + 2 * L * a - x * x) / (6 * EI * L);  // Eq. 4.12
  return P * a * (L - x) * (-a * a + 2 * L * x - x * x) / (6 * EI * L);              // Eq. 4.13
}

double point_load_moment(double P, double a, double x, double L) {
  if (x <= a) return P * x * (1 - a / L);  // Eq. 4.10
  return P * a * (1 - x / L);              // Eq. 4.11
}

double point_compliance(double a, double L, double EI) {
  const double b = L - a;
  return a * a * b * b / (3 * EI * L);
}

}  // namespace fibrecheck
