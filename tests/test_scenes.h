#pragma once

// Scenes with known answers, built in code so that tests can vary their parameters.

#include <algorithm>
#include <cmath>

#include "scene.h"

namespace fibrecheck::testing {

inline double bending_stiffness(double radius, double modulus) {
  return modulus * M_PI * std::pow(radius, 4) / 4.0;
}

/// Compliance of a simply supported beam at its load point: a²b²/(3EIL).
inline double compliance(double a, double L, double EI) {
  const double b = L - a;
  return a * a * b * b / (3.0 * EI * L);
}

/// Deflection at x of a simply supported beam of length 1 mm under a unit load at a, both in mm:
/// Eq. 4.13 with the nearer end chosen so it holds on either side (Maxwell's reciprocity).
inline double unit_load_deflection(double a, double x, double EI) {
  const double lo = std::min(a, x), hi = std::max(a, x);
  return (1 - hi) * lo * (1 - lo * lo - (1 - hi) * (1 - hi)) / (6 * EI);
}

inline FibreSpec fibre(const std::string& id, Eigen::Vector3d start, Eigen::Vector3d end,
                       double radius = 0.01, double modulus = 80000.0) {
  FibreSpec f;
  f.id = id;
  f.start = start;
  f.end = end;
  f.radius = radius;
  f.youngs_modulus = modulus;
  return f;
}

/// Fibre A along x (length La) and fibre B along y (length Lb) crossing at fraction sa of A and sb
/// of B, with centreline distance rA + rB − overlap.
inline Scene crossing(double sa, double sb, double overlap, double ra = 0.01, double rb = 0.01,
                      double ea = 80000.0, double eb = 80000.0, double La = 1.0, double Lb = 1.0) {
  Scene s;
  s.name = "crossing";
  const double h = ra + rb - overlap;
  s.fibres.push_back(fibre("A", {0, 0, 0}, {La, 0, 0}, ra, ea));
  s.fibres.push_back(fibre("B", {sa * La, -sb * Lb, h}, {sa * La, (1 - sb) * Lb, h}, rb, eb));
  s.solver.overlap_tolerance = 1e-9;
  return s;
}

/// Fibre A resting on fibre B along their whole length (both along x), a uniform load q (N/mm)
/// pressing A onto B.
inline Scene parallel(double q, int slices, double ra = 0.01, double rb = 0.008,
                      double ea = 80000.0, double eb = 70000.0) {
  Scene s;
  s.name = "parallel";
  s.fibres.push_back(fibre("A", {0, 0, ra + rb}, {1, 0, ra + rb}, ra, ea));
  s.fibres.push_back(fibre("B", {0, 0, 0}, {1, 0, 0}, rb, eb));
  LoadSpec load;
  load.fibre = "A";
  load.kind = LoadKind::distributed;
  load.force = {0, 0, -q};
  s.loads.push_back(load);
  s.contact.slices = slices;
  s.solver.rule = UpdateRule::accelerated;
  s.solver.overlap_tolerance = 1e-12;
  return s;
}

}  // namespace fibrecheck::testing
