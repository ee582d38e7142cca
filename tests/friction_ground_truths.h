#pragma once

// The Coulomb-friction ground truths (DESIGN §7) both solvers must meet, written once: each check
// takes the solver to run and asserts the closed form. The tests of either solver call them.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "result.h"
#include "scene.h"
#include "test_scenes.h"

namespace fibrecheck::testing {

using SolveScene = std::function<Result(const Scene&)>;

/// Fibre B across fibre A at both mid-spans, overlap 1e-3 mm (so pressed by N = δ/(C_A + C_B)),
/// μ as given, a side load H on B at the contact along A's axis (along which A cannot move: the
/// tangential compliance there is B's alone).
inline Scene sheared_crossing(double H, double mu) {
  Scene s = crossing(0.5, 0.5, 1e-3);
  s.name = "sheared_crossing";
  LoadSpec side;
  side.fibre = "B";
  side.position = 0.5;
  side.force = {H, 0, 0};
  s.loads.push_back(side);
  s.contact.friction = mu;
  return s;
}

struct CrossingFigures {
  double C;  ///< a²b²/(3EIL) of either fibre at mid-span, mm/N
  double N;  ///< the pressing force δ/(2C), N
};

inline CrossingFigures crossing_figures() {
  const double C = compliance(0.5, 1.0, bending_stiffness(0.01, 80000.0));
  return {C, 1e-3 / (2.0 * C)};
}

/// B's displacement along the side load at the contact (mid-span: sample 50 of 101).
inline double crossing_shift(const Result& r) {
  return r.fibres.at(1).displacement.at(50).x();
}

inline const ContactResult& only_contact(const Result& r) {
  EXPECT_EQ(r.contacts.size(), 1u);
  return r.contacts.at(0);
}

/// Sticks while H ≤ μN (no motion at the contact, friction H); otherwise slips with friction μN
/// and moves by (H − μN)·C; the normal force is the frictionless one throughout.
inline void check_crossing_stick_and_slip(const SolveScene& solve, double tolerance) {
  const CrossingFigures x = crossing_figures();
  const double mu = 0.3;
  for (double ratio : {0.5, 0.99, 1.01, 2.0, 5.0}) {
    SCOPED_TRACE("H / (mu N) = " + std::to_string(ratio));
    const double H = ratio * mu * x.N;
    const Result r = solve(sheared_crossing(H, mu));
    ASSERT_EQ(r.status, Status::converged) << r.message;
    const ContactResult& c = only_contact(r);
    EXPECT_NEAR(c.normal_force, x.N, tolerance * x.N);
    ASSERT_TRUE(r.friction.has_value());
    ASSERT_EQ(c.points.size(), 1u);
    if (ratio <= 1.0) {
      EXPECT_EQ(c.points[0].state, "stick");
      EXPECT_NEAR(c.friction_force, H, tolerance * H);
      EXPECT_NEAR(crossing_shift(r), 0.0, tolerance * mu * x.N * x.C);
    } else {
      EXPECT_EQ(c.points[0].state, "slip");
      EXPECT_NEAR(c.friction_force, mu * x.N, tolerance * mu * x.N);
      EXPECT_NEAR(crossing_shift(r), (H - mu * x.N) * x.C, tolerance * H * x.C);
      // A receives the friction along the side load: against B's motion, on B.
      EXPECT_GT(c.points[0].friction_force.x(), 0.0);
    }
  }
}

/// μ = 0 is frictionless exactly: no friction forces, no friction figures, the closed form; and a
/// vanishing μ through the frictional machinery gives the same normal force.
inline void check_zero_friction(const SolveScene& solve, double tolerance) {
  const CrossingFigures x = crossing_figures();
  const double H = 1e-6;
  const Result frictionless = solve(sheared_crossing(H, 0.0));
  ASSERT_EQ(frictionless.status, Status::converged) << frictionless.message;
  EXPECT_FALSE(frictionless.friction.has_value());
  const ContactResult& c = only_contact(frictionless);
  EXPECT_EQ(c.friction_force, 0.0);
  EXPECT_EQ(c.points.at(0).state, "");
  EXPECT_NEAR(crossing_shift(frictionless), H * x.C, tolerance * H * x.C);
  const Result tiny = solve(sheared_crossing(H, 1e-12));
  ASSERT_EQ(tiny.status, Status::converged) << tiny.message;
  EXPECT_NEAR(only_contact(tiny).normal_force, c.normal_force, tolerance * c.normal_force);
  EXPECT_NEAR(crossing_shift(tiny), crossing_shift(frictionless), tolerance * H * x.C);
}

/// μ → ∞ is bonded: however large the side load, the contact does not move; parallel fibres
/// sheared with a huge μ bend together as one beam of stiffness EI_A + EI_B.
inline void check_bonded_limit(const SolveScene& solve, double tolerance) {
  const CrossingFigures x = crossing_figures();
  const Result r = solve(sheared_crossing(100.0 * x.N, 1e6));
  ASSERT_EQ(r.status, Status::converged) << r.message;
  EXPECT_NEAR(crossing_shift(r), 0.0, tolerance * 100.0 * x.N * x.C);
  EXPECT_NEAR(only_contact(r).friction_force, 100.0 * x.N, tolerance * 100.0 * x.N);
}

/// Fibre A resting on B along their length, pressed by q (N/mm, −z) and sheared by h (N/mm, +y),
/// both uniform on A; μ as given.
inline Scene sheared_parallel(double q, double h, double mu, int slices = 100) {
  Scene s = parallel(q, slices);
  s.name = "sheared_parallel";
  LoadSpec side;
  side.fibre = "A";
  side.kind = LoadKind::distributed;
  side.force = {0, h, 0};
  s.loads.push_back(side);
  s.contact.friction = mu;
  return s;
}

/// Below h = μq the fibres move together, deflection 5hL⁴/(384(EI_A + EI_B)) and B carries
/// h·EI_B/(EI_A + EI_B); above, every slice slips with friction μ times the contact line force,
/// and each fibre bends under its own part: A under h − f, B under f (DESIGN §7).
inline void check_parallel_shear(const SolveScene& solve, double tolerance) {
  const double q = 1e-4, mu = 0.3;
  const double EIa = bending_stiffness(0.01, 80000.0), EIb = bending_stiffness(0.008, 70000.0);
  for (double ratio : {0.5, 2.0}) {
    SCOPED_TRACE("h / (mu q) = " + std::to_string(ratio));
    const double h = ratio * mu * q;
    const Result r = solve(sheared_parallel(q, h, mu));
    ASSERT_EQ(r.status, Status::converged) << r.message;
    const ContactResult& c = only_contact(r);
    const double line = c.normal_force;  // the sliced line force, within 1 % of q·EI_B/ΣEI
    EXPECT_NEAR(line, q * EIb / (EIa + EIb), 0.01 * q * EIb / (EIa + EIb));
    const double ya = r.fibres.at(0).displacement.at(50).y();
    const double yb = r.fibres.at(1).displacement.at(50).y();
    if (ratio < 1.0) {
      EXPECT_EQ(r.friction->slipping, 0);
      const double together = 5.0 * h / (384.0 * (EIa + EIb));
      EXPECT_NEAR(ya, together, 1e-3 * together);
      EXPECT_NEAR(yb, together, 1e-3 * together);
      EXPECT_NEAR(c.friction_force, h * EIb / (EIa + EIb), 0.01 * h * EIb / (EIa + EIb));
    } else {
      EXPECT_EQ(r.friction->sticking, 0);
      // Each slice slips with μ times its own normal force...
      EXPECT_NEAR(c.friction_force, mu * line, tolerance * mu * line);
      // ...and the deflections are those of the closed-form line loads (the slices' end effect,
      // 0.24 % of the line force at 100 slices, acts next to the supports and moves little).
      const double f = mu * q * EIb / (EIa + EIb);
      EXPECT_NEAR(ya, 5.0 * (h - f) / (384.0 * EIa), 1e-3 * 5.0 * h / (384.0 * EIa));
      EXPECT_NEAR(yb, 5.0 * f / (384.0 * EIb), 1e-3 * 5.0 * f / (384.0 * EIb));
    }
  }
}

/// A load path on the sheared crossing with the load factors given (the pressing comes from the
/// overlap, so N stays the same; only H changes).
inline Scene crossing_path(double H, std::initializer_list<double> factors, double mu = 0.3) {
  Scene s = sheared_crossing(H, mu);
  for (double f : factors) s.steps.push_back({1.0, f});
  return s;
}

/// Loaded to H1 = 3μN (slips: shift 2μN·C), then unloaded: the contact sticks while H stays within
/// 2μN below H1 — the hysteresis width — and slips back beyond it, with friction −μN.
inline void check_hysteresis(const SolveScene& solve, double tolerance) {
  const CrossingFigures x = crossing_figures();
  const double mu = 0.3, H1 = 3.0 * mu * x.N;
  const double loaded = (H1 - mu * x.N) * x.C;
  // Down to H1 − 2μN·(1 − ε): still stuck where the loading left it.
  const Result stuck = solve(crossing_path(H1, {1.0, 0.5, 1.0 / 3.0 + 0.01}));
  ASSERT_EQ(stuck.status, Status::converged) << stuck.message;
  ASSERT_EQ(stuck.steps.size(), 3u);
  EXPECT_NEAR(crossing_shift(stuck), loaded, tolerance * H1 * x.C);
  EXPECT_EQ(only_contact(stuck).points.at(0).state, "stick");
  // Beyond the width: slips back, friction μN the other way, shift (H − (−μN))·C.
  const double H = (1.0 / 3.0 - 0.1) * H1;
  const Result back = solve(crossing_path(H1, {1.0, 0.5, 1.0 / 3.0 - 0.1}));
  ASSERT_EQ(back.status, Status::converged) << back.message;
  EXPECT_EQ(only_contact(back).points.at(0).state, "slip");
  EXPECT_NEAR(crossing_shift(back), (H + mu * x.N) * x.C, tolerance * H1 * x.C);
  EXPECT_LT(only_contact(back).points.at(0).friction_force.x(), 0.0);
}

/// The order of loads matters: H = 0.8μN reached directly sticks where it started (no shift);
/// reached by way of 2μN it keeps the shift μN·C of the detour (both checked).
inline void check_path_dependence(const SolveScene& solve, double tolerance) {
  const CrossingFigures x = crossing_figures();
  const double mu = 0.3, H = 2.0 * mu * x.N;
  const Result direct = solve(crossing_path(H, {0.4}));
  const Result detour = solve(crossing_path(H, {1.0, 0.4}));
  ASSERT_EQ(direct.status, Status::converged) << direct.message;
  ASSERT_EQ(detour.status, Status::converged) << detour.message;
  EXPECT_NEAR(crossing_shift(direct), 0.0, tolerance * H * x.C);
  EXPECT_NEAR(crossing_shift(detour), mu * x.N * x.C, tolerance * H * x.C);
  EXPECT_NEAR(only_contact(direct).friction_force, 0.4 * H, tolerance * H);
  // At the end of the detour the friction holds B back from returning: −0.2μN on B.
  EXPECT_NEAR(only_contact(detour).friction_force, 0.2 * mu * x.N, tolerance * H);
}

}  // namespace fibrecheck::testing
