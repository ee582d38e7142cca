#pragma once

// Scenes with known answers, built in code so that tests can vary their parameters. Their closed
// forms are those of small deflections: the scenes use the linearised contact (place and normal
// of the undeformed fibres), whose answers they give exactly; the deformed contact has its own
// closed forms (deformed_contact_ground_truths.h).

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
  s.contact.geometry = ContactGeometryModel::linearised;
  s.name = "crossing";
  const double h = ra + rb - overlap;
  s.fibres.push_back(fibre("A", {0, 0, 0}, {La, 0, 0}, ra, ea));
  s.fibres.push_back(fibre("B", {sa * La, -sb * Lb, h}, {sa * La, (1 - sb) * Lb, h}, rb, eb));
  s.solver.overlap_tolerance = 1e-9;
  return s;
}

/// Fibre F (length 1 along x, r = 0.01, E = 80 000) with a point load P (−z) at mid-span, `walls`
/// walls in one plane a gap g below it ("floor", "second_floor"), and 51 slices so that a
/// station sits at mid-span: R = P − g/C(L/2) if g < P·C(L/2).
inline Scene pressed_onto_wall(double P, double gap, int walls = 1) {
  Scene s;
  s.contact.geometry = ContactGeometryModel::linearised;
  s.fibres.push_back(fibre("F", {0, 0, 0}, {1, 0, 0}));
  const char* ids[2] = {"floor", "second_floor"};
  for (int i = 0; i < walls; ++i) {
    WallSpec wall;
    wall.id = ids[i];
    wall.point = {0, 0, -0.01 - gap};
    wall.normal = {0, 0, 1};
    s.walls.push_back(wall);
  }
  LoadSpec load;
  load.fibre = "F";
  load.force = {0, 0, -P};
  s.loads.push_back(load);
  s.contact.slices = 51;
  return s;
}

/// Fibre B resting (just touching) across fibre A at 0.3 of A and 0.6 of B, with a point load P
/// (−z) on B at the crossing: A receives R = P·C_B/(C_A + C_B).
inline Scene loaded_crossing(double P) {
  Scene s = crossing(0.3, 0.6, 0.0);
  LoadSpec load;
  load.fibre = "B";
  load.position = 0.6;
  load.force = {0, 0, -P};
  s.loads.push_back(load);
  return s;
}

/// Fibres A (along x) and B (along y) whose pinned supports at the origin overlap.
inline Scene overlapping_supports() {
  Scene s;
  s.contact.geometry = ContactGeometryModel::linearised;
  s.fibres.push_back(fibre("A", {0, 0, 0}, {1, 0, 0}));
  s.fibres.push_back(fibre("B", {0, 0, 0.015}, {0, 1, 0.015}));
  return s;
}

/// Fibre A resting on fibre B along their whole length (both along x), a uniform load q (N/mm)
/// pressing A onto B.
inline Scene parallel(double q, int slices, double ra = 0.01, double rb = 0.008,
                      double ea = 80000.0, double eb = 70000.0) {
  Scene s;
  s.contact.geometry = ContactGeometryModel::linearised;
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
