#pragma once

// Contact measured on the deformed fibres (DESIGN §7): closed forms both solvers must meet.

#include <Eigen/Core>
#include <cmath>

#include "test_scenes.h"

namespace fibrecheck::testing {

/// Two parallel fibres A and B along x, length 1 mm, pinned at both ends, B's centre offset `c0`
/// (in the y–z plane) from A's — just clear at the supports, |c0| > rA + rB — one slice at
/// mid-span and a point load F on B at mid-span. C = L³/(48EI) is each fibre's mid-span compliance
/// in every direction across it. Equilibrium and just-touching on the displaced centres:
/// v = c0 + C_B·F, n = v/‖v‖, P = (rA + rB − ‖v‖)/(C_A + C_B), u_B = C_B(F + P n), u_A = −C_A P n.
/// The linearised contact (normal n0 = c0/‖c0‖) gives P = (rA + rB − n0·v)/(C_A + C_B).
struct OffsetParallel {
  Eigen::Vector3d c0;  ///< mm
  Eigen::Vector3d CF;  ///< C_B·F, mm (the load's own deflection of B at mid-span)
  double ra = 0.01, rb = 0.01;
  double ea = 80000.0, eb = 80000.0;

  double C_a() const { return 1.0 / (48.0 * bending_stiffness(ra, ea)); }
  double C_b() const { return 1.0 / (48.0 * bending_stiffness(rb, eb)); }
  Eigen::Vector3d force() const { return CF / C_b(); }  ///< F, N
  Eigen::Vector3d v() const { return c0 + CF; }
  Eigen::Vector3d normal() const { return v().normalized(); }
  double P() const { return (ra + rb - v().norm()) / (C_a() + C_b()); }
  double P_linearised() const { return (ra + rb - c0.normalized().dot(v())) / (C_a() + C_b()); }
  Eigen::Vector3d u_a() const { return -C_a() * P() * normal(); }
  Eigen::Vector3d u_b() const { return C_b() * (force() + P() * normal()); }

  Scene scene(ContactGeometryModel model = ContactGeometryModel::deformed) const {
    Scene s;
    s.name = "offset_parallel";
    s.fibres.push_back(fibre("A", {0, 0, 0}, {1, 0, 0}, ra, ea));
    s.fibres.push_back(fibre("B", c0, c0 + Eigen::Vector3d(1, 0, 0), rb, eb));
    LoadSpec load;
    load.fibre = "B";
    load.kind = LoadKind::point;
    load.position = 0.5;
    load.force = force();
    s.loads.push_back(load);
    s.contact.slices = 1;
    s.contact.geometry = model;
    s.solver.overlap_tolerance = 1e-12;
    s.output.samples = 101;  // sample 50 at mid-span
    return s;
  }
};

/// The cases of the closed form: offsets straight above and aslant, loads that turn the normal by
/// 13° to 32°, unequal radii and moduli.
inline std::vector<OffsetParallel> offset_parallel_cases() {
  const double r = 0.01;
  std::vector<OffsetParallel> cases;
  cases.push_back({{0, 0, 2.001 * r}, {0, 0.4 * r, -0.3 * r}});
  cases.push_back({{0, 1.2 * r, 1.65 * r}, {0, -0.2 * r, -0.5 * r}});
  cases.push_back({{0, 0, 2.01 * r}, {0, 1.0 * r, -0.4 * r}});
  OffsetParallel unequal{{0, 0, 2.6 * r}, {0, 0.5 * r, -0.6 * r}};
  unequal.rb = 1.5 * r;
  unequal.eb = 2.0 * 80000.0;
  cases.push_back(unequal);
  return cases;
}

/// Two fibres crossing at right angles, A along x and B along y over A's mid-span, overlapping by
/// δ = 0.001 mm; B is pushed at its mid-span along A by H, so that its crossing point moves to
/// x = 1/2 + C_B·H. On the deformed fibres the crossing slides with it: P = δ/(C_A(a) + C_B) with
/// A's compliance a²b²/(3EIL) at the slid place a = 1/2 + C_B·H (its normal stays along z).
struct PushedCrossing {
  double H = 0.0;  ///< N, along x
  double delta = 0.001;
  double C_b() const { return 1.0 / (48.0 * bending_stiffness(0.01, 80000.0)); }
  double slid() const { return 0.5 + C_b() * H; }
  double P() const {
    return delta / (compliance(slid(), 1.0, bending_stiffness(0.01, 80000.0)) + C_b());
  }
  Scene scene(ContactGeometryModel model = ContactGeometryModel::deformed) const {
    Scene s = crossing(0.5, 0.5, delta);
    s.contact.geometry = model;
    LoadSpec load;
    load.fibre = "B";
    load.kind = LoadKind::point;
    load.position = 0.5;
    load.force = Eigen::Vector3d(H, 0, 0);
    s.loads.push_back(load);
    s.solver.overlap_tolerance = 1e-12;
    return s;
  }
};

}  // namespace fibrecheck::testing
