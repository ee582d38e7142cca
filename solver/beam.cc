#include "beam.h"

namespace fibrecheck {

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
