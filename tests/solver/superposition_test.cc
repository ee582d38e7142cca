// The beam model of all fibres at once (seed §4.3.1). Test problems: simply supported fibres
// (r = 0.01 mm, E = 80 000 MPa, EI = E·π·r⁴/4) under point loads, uniform loads and contact
// forces, each resolved into the fibre's planes (e1, e2) with the axial part dropped. Known
// answers, the textbook closed forms written out here (b = L − a):
//  - point load P at a (Eqs. 4.10–4.13): v = P·b·x(L² − b² − x²)/(6EIL) and M = P·b·x/L for
//    x ≤ a, the mirror image v = P·a·x'(L² − a² − x'²)/(6EIL), M = P·a·x'/L with x' = L − x beyond;
//  - uniform load q: v = q·x(L³ − 2Lx² + x³)/(24EI), M = q·x(L − x)/2;
//  - superposition: the sum of those over the loads, plane by plane;
//  - strain energy: U = ∫(M₁² + M₂²)/(2EI) dx = ½ΣP·v(a) + ½∫q·v dx (Clapeyron); for one load P
//    at a with q: U = ½P²a²b²/(3EIL) + P·q·a(L³ − 2La² + a³)/(24EI) + q²L⁵/(240EI);
//  - the trapezium rule of Eq. 4.34 on n intervals for a load P at mid-span (n even) is exact
//    plus h²P²L/(48EI), h = L/n (the Euler–Maclaurin term of the piecewise quadratic M²);
//  - N equal loads qL/N at the midpoints of N cells give at mid-span the moment qL²/8 exactly
//    (M is linear in the load position on each cell) and the deflection 5qL⁴/(384EI) times
//    1 + 0.4/N² (midpoint rule on the influence line, whose end slopes are ±L²/(16EI)).
#include "superposition.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_scenes.h"

namespace fibrecheck {
namespace {

using V = Eigen::Vector3d;
using testing::fibre;

const double EI = testing::bending_stiffness(0.01, 80000);

/// A load on one fibre in its two planes (N), at a (mm).
struct PlaneLoad {
  double a, p1, p2;
};

struct Field {
  double v1 = 0, v2 = 0, m1 = 0, m2 = 0;
};

double point_deflection(double P, double a, double x, double L) {
  const double b = L - a;
  if (x <= a) return P * b * x * (L * L - b * b - x * x) / (6 * EI * L);
  const double xr = L - x;
  return P * a * xr * (L * L - a * a - xr * xr) / (6 * EI * L);
}

double point_moment(double P, double a, double x, double L) {
  return x <= a ? P * (L - a) * x / L : P * a * (L - x) / L;
}

double uniform_deflection(double q, double x, double L) {
  return q * x * (L * L * L - 2 * L * x * x + x * x * x) / (24 * EI);
}

double uniform_moment(double q, double x, double L) {
  return q * x * (L - x) / 2;
}

Field textbook(const std::vector<PlaneLoad>& loads, double q1, double q2, double x, double L) {
  Field f;
  for (const PlaneLoad& l : loads) {
    f.v1 += point_deflection(l.p1, l.a, x, L);
    f.v2 += point_deflection(l.p2, l.a, x, L);
    f.m1 += point_moment(l.p1, l.a, x, L);
    f.m2 += point_moment(l.p2, l.a, x, L);
  }
  f.v1 += uniform_deflection(q1, x, L);
  f.v2 += uniform_deflection(q2, x, L);
  f.m1 += uniform_moment(q1, x, L);
  f.m2 += uniform_moment(q2, x, L);
  return f;
}

/// ∫₀ᴸ (M₁² + M₂²)/(2EI) dx, exactly: M is at most quadratic between loads, so M² is a quartic
/// there and three Gauss points per piece integrate it exactly.
double bending_energy(const std::vector<PlaneLoad>& loads, double q1, double q2, double L) {
  std::vector<double> breaks = {0.0, L};
  for (const PlaneLoad& l : loads) breaks.push_back(l.a);
  std::sort(breaks.begin(), breaks.end());
  const double g = std::sqrt(0.6);
  double U = 0;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double mid = 0.5 * (breaks[k] + breaks[k + 1]), half = 0.5 * (breaks[k + 1] - breaks[k]);
    for (const auto& [t, w] :
         {std::pair{-g, 5.0 / 9}, std::pair{0.0, 8.0 / 9}, std::pair{g, 5.0 / 9}}) {
      const Field f = textbook(loads, q1, q2, mid + t * half, L);
      U += w * half * (f.m1 * f.m1 + f.m2 * f.m2) / (2 * EI);
    }
  }
  return U;
}

Scene one_fibre(double L, V end_direction = V::UnitX()) {
  Scene s;
  s.fibres.push_back(fibre("F", V::Zero(), L * end_direction.normalized()));
  return s;
}

void add_point(Scene& s, const std::string& id, double position, V force) {
  LoadSpec l;
  l.fibre = id;
  l.position = position;
  l.force = force;
  s.loads.push_back(l);
}

void add_uniform(Scene& s, const std::string& id, V force_per_length) {
  LoadSpec l;
  l.fibre = id;
  l.kind = LoadKind::distributed;
  l.force = force_per_length;
  s.loads.push_back(l);
}

// Deflections here are ≲ 0.1 mm and moments ≲ 1e-4 N·mm; the running sums subtract terms of the
// same size as the result (L²·Sb − Sb3 …), so a few hundred ulp: 1e-12 relative to the largest.
constexpr double kRelative = 1e-12;

TEST(Superposition, PointAndUniformLoadsInBothPlanesAreTheTextbookSums) {
  // Along x: e1 = y, e2 = z. L = 1.5 mm, so no formula may assume a unit length.
  const double L = 1.5;
  Scene s = one_fibre(L);
  add_point(s, "F", 0.2, {0, 2e-4, -1e-4});
  add_point(s, "F", 0.55, {0, -1e-4, 3e-4});
  add_point(s, "F", 0.8, {0, 0, -2e-4});
  add_uniform(s, "F", {0, 1e-4, -5e-5});
  const std::vector<PlaneLoad> loads = {
      {0.2 * L, 2e-4, -1e-4}, {0.55 * L, -1e-4, 3e-4}, {0.8 * L, 0, -2e-4}};
  const auto fibres = make_fibres(s);
  ASSERT_NEAR((fibres[0].e1 - V::UnitY()).norm(), 0.0, 1e-15);
  const Superposition superposition(fibres, s);
  const std::vector<double> stations = {0, 0.1, 0.2, 0.3, 0.5, 0.55, 0.7, 0.8, 0.95, 1};
  std::vector<V> u;
  std::vector<Eigen::Vector2d> moment;
  superposition.fibre_field(0, {}, true, stations, u, &moment);
  ASSERT_EQ(u.size(), stations.size());
  ASSERT_EQ(moment.size(), stations.size());
  double v_scale = 0, m_scale = 0;
  for (double s_ : stations) {
    const Field f = textbook(loads, 1e-4, -5e-5, s_ * L, L);
    v_scale = std::max({v_scale, std::fabs(f.v1), std::fabs(f.v2)});
    m_scale = std::max({m_scale, std::fabs(f.m1), std::fabs(f.m2)});
  }
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const Field f = textbook(loads, 1e-4, -5e-5, stations[i] * L, L);
    EXPECT_NEAR(u[i].x(), 0.0, kRelative * v_scale) << stations[i];  // no axial displacement
    EXPECT_NEAR(u[i].y(), f.v1, kRelative * v_scale) << stations[i];
    EXPECT_NEAR(u[i].z(), f.v2, kRelative * v_scale) << stations[i];
    EXPECT_NEAR(moment[i][0], f.m1, kRelative * m_scale) << stations[i];
    EXPECT_NEAR(moment[i][1], f.m2, kRelative * m_scale) << stations[i];
  }
  // The supports do not move and carry no moment.
  EXPECT_TRUE(u.front() == V::Zero());
  EXPECT_NEAR(u.back().norm(), 0.0, kRelative * v_scale);
  EXPECT_NEAR(moment.back().norm(), 0.0, kRelative * m_scale);
  // Without the external loads nothing moves.
  superposition.fibre_field(0, {}, false, stations, u, &moment);
  for (std::size_t i = 0; i < stations.size(); ++i) {
    EXPECT_TRUE(u[i] == V::Zero());
    EXPECT_TRUE(moment[i] == Eigen::Vector2d::Zero());
  }
}

TEST(Superposition, SkewFibreResolvesLoadsIntoItsOwnFrameAndDropsTheAxialPart) {
  // Along (1, 1, 0)/√2, off the tow axis x: e1 = (−1, 1, 0)/√2 (y projected off the fibre),
  // e2 = t × e1 = z. The axial part of each load is dropped.
  const double L = 1.0;
  Scene s = one_fibre(L, V(1, 1, 0));
  const V t = V(1, 1, 0) / std::sqrt(2.0), e1 = V(-1, 1, 0) / std::sqrt(2.0), e2 = V::UnitZ();
  const V P(1e-4, 2e-4, -3e-4), q(-5e-5, 1e-4, 2e-5);
  add_point(s, "F", 0.35, P);
  add_uniform(s, "F", q);
  const auto fibres = make_fibres(s);
  ASSERT_FALSE(fibres[0].along_tow_axis);
  ASSERT_NEAR((fibres[0].e1 - e1).norm(), 0.0, 1e-15);
  ASSERT_NEAR((fibres[0].e2 - e2).norm(), 0.0, 1e-15);
  const Superposition superposition(fibres, s);
  const std::vector<double> stations = {0.1, 0.35, 0.6, 0.9};
  std::vector<V> u;
  std::vector<Eigen::Vector2d> moment;
  superposition.fibre_field(0, {}, true, stations, u, &moment);
  const std::vector<PlaneLoad> loads = {{0.35, P.dot(e1), P.dot(e2)}};
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const Field f = textbook(loads, q.dot(e1), q.dot(e2), stations[i], L);
    const V expected = f.v1 * e1 + f.v2 * e2;
    EXPECT_NEAR((u[i] - expected).norm(), 0.0, kRelative * expected.norm()) << stations[i];
    EXPECT_NEAR(u[i].dot(t), 0.0, 1e-17) << stations[i];  // e1, e2 ⊥ t to 1e-16
    EXPECT_NEAR(moment[i][0], f.m1, kRelative * std::fabs(f.m1)) << stations[i];
    EXPECT_NEAR(moment[i][1], f.m2, kRelative * std::fabs(f.m2)) << stations[i];
  }
  // Dropped: |P·t| + |q·t|·L.
  EXPECT_NEAR(superposition.axial_load_dropped({}, {}),
              std::fabs(P.dot(t)) + std::fabs(q.dot(t)) * L, 1e-18);
}

TEST(Superposition, LoadsAtTheSupportsMoveNothing) {
  Scene s = one_fibre(1.0);
  add_point(s, "F", 0.0, {0, 1e-3, -1e-3});
  add_point(s, "F", 1.0, {0, -2e-3, 1e-3});
  const Superposition superposition(make_fibres(s), s);
  std::vector<V> u;
  std::vector<Eigen::Vector2d> moment;
  superposition.fibre_field(0, {}, true, {0, 0.25, 0.5, 1}, u, &moment);
  // The sums cancel to rounding: a load at a = 0 still enters b·x(L² − b² − x²) with b = L.
  for (std::size_t i = 0; i < u.size(); ++i) {
    EXPECT_NEAR(u[i].norm(), 0.0, 1e-15);
    EXPECT_NEAR(moment[i].norm(), 0.0, 1e-18);
  }
  EXPECT_NEAR(superposition.trapezium_energy({}, 10), 0.0, 1e-30);
}

// Fibres A (x), B and C (y) crossing A at 0.3 of A (B above, C below), a floor under A, and an
// external load on B; forces chosen by hand, including a tangential part on the A–B contact.
struct CoupledScene {
  Scene scene;
  std::vector<Contact> contacts;
  std::vector<V> force_on_a;

  CoupledScene() {
    scene.fibres = {fibre("A", {0, 0, 0}, {1, 0, 0}),
                    fibre("B", {0.3, -0.6, 0.02}, {0.3, 0.4, 0.02}),
                    fibre("C", {0.3, -0.4, -0.02}, {0.3, 0.6, -0.02})};
    WallSpec floor;
    floor.id = "floor";
    floor.point = {0, 0, -0.01};
    scene.walls.push_back(floor);
    add_point(scene, "B", 0.25, {0, 0, -2e-4});
    Contact ab, ac, wall;
    ab.a = 0, ab.b = 1, ab.s_a = 0.3, ab.s_b = 0.6;
    ac.a = 0, ac.b = 2, ac.s_a = 0.3, ac.s_b = 0.4, ac.normal = -V::UnitZ();
    wall.kind = ContactKind::wall, wall.a = 0, wall.b = 0, wall.s_a = 0.7, wall.slice = 3;
    contacts = {ab, ac, wall};
    force_on_a = {V(0, 1e-5, -1e-4), V(0, 0, 5e-5), V(0, 0, 3e-5)};
  }
};

TEST(Superposition, ContactDisplacementsSuperposeContactForcesAndSceneLoads) {
  const CoupledScene k;
  const auto fibres = make_fibres(k.scene);
  // Frames: A along x has (e1, e2) = (y, z); B and C along y have e1 = z (y cannot be projected
  // off them), e2 = y × z = x.
  ASSERT_NEAR((fibres[1].e1 - V::UnitZ()).norm(), 0.0, 1e-15);
  ASSERT_NEAR((fibres[1].e2 - V::UnitX()).norm(), 0.0, 1e-15);
  Superposition superposition(fibres, k.scene);
  superposition.attach(k.contacts);
  // A: both contacts at 0.3 (one station) and the wall at 0.7. B receives −F_AB at 0.6, C −F_AC
  // at 0.4; B also carries the external −2e-4 z at 0.25 (its e1 = z, so −2e-4 in plane 1).
  const std::vector<PlaneLoad> on_a = {{0.3, 1e-5, -1e-4}, {0.3, 0, 5e-5}, {0.7, 0, 3e-5}};
  const std::vector<PlaneLoad> on_b_contact = {{0.6, 1e-4, 0}};
  std::vector<PlaneLoad> on_b = on_b_contact;
  on_b.push_back({0.25, -2e-4, 0});
  const std::vector<PlaneLoad> on_c = {{0.4, -5e-5, 0}};
  for (bool external : {true, false}) {
    std::vector<V> u_a, u_b;
    superposition.contact_displacements(k.contacts, k.force_on_a, external, u_a, u_b);
    ASSERT_EQ(u_a.size(), 3u);
    const Field a03 = textbook(on_a, 0, 0, 0.3, 1), a07 = textbook(on_a, 0, 0, 0.7, 1);
    const Field b06 = textbook(external ? on_b : on_b_contact, 0, 0, 0.6, 1);
    const Field c04 = textbook(on_c, 0, 0, 0.4, 1);
    const double scale = std::fabs(b06.v1);
    EXPECT_NEAR((u_a[0] - V(0, a03.v1, a03.v2)).norm(), 0.0, kRelative * scale);
    EXPECT_TRUE(u_a[1] == u_a[0]);  // one station, one displacement
    EXPECT_NEAR((u_a[2] - V(0, a07.v1, a07.v2)).norm(), 0.0, kRelative * scale);
    EXPECT_NEAR((u_b[0] - V(b06.v2, 0, b06.v1)).norm(), 0.0, kRelative * scale) << external;
    EXPECT_NEAR((u_b[1] - V(c04.v2, 0, c04.v1)).norm(), 0.0, kRelative * scale);
    // fibre_field agrees with contact_displacements at the contacts.
    std::vector<V> field;
    superposition.fibre_field(1, k.force_on_a, external, {0.6}, field);
    EXPECT_NEAR((field[0] - u_b[0]).norm(), 0.0, kRelative * scale);
  }
  // Attaching no contacts removes them: only B's scene load is left.
  superposition.attach({});
  std::vector<V> field;
  superposition.fibre_field(0, {}, true, {0.3}, field);
  EXPECT_TRUE(field[0] == V::Zero());
  superposition.fibre_field(1, {}, true, {0.6}, field);
  EXPECT_NEAR(field[0].z(), point_deflection(-2e-4, 0.25, 0.6, 1), kRelative * 1e-2);
}

TEST(Superposition, ExactEnergyIsHalfThePowerOfTheLoadsAndMatchesItsClosedForm) {
  // One load P at a with a uniform q, L = 1.2, in both planes (e1 = y, e2 = z) and with opposite
  // signs in the second: the closed form of the header, plane by plane.
  const double L = 1.2, s_a = 0.35, a = s_a * L, b = L - a;
  const double P[2] = {1.5e-4, 2e-4}, q[2] = {-6e-5, -1e-4};
  Scene s = one_fibre(L);
  add_point(s, "F", s_a, {0, P[0], -P[1]});
  add_uniform(s, "F", {0, q[0], -q[1]});
  const Superposition superposition(make_fibres(s), s);
  std::vector<V> u_a, u_b;
  double U = 0;
  superposition.contact_displacements({}, {}, true, u_a, u_b, &U);
  double closed = 0;
  for (int k = 0; k < 2; ++k)
    closed += 0.5 * P[k] * P[k] * a * a * b * b / (3 * EI * L) +
              P[k] * q[k] * a * (L * L * L - 2 * L * a * a + a * a * a) / (24 * EI) +
              q[k] * q[k] * std::pow(L, 5) / (240 * EI);
  EXPECT_NEAR(U, closed, 1e-12 * closed);
  EXPECT_NEAR(U, bending_energy({{a, P[0], -P[1]}}, q[0], -q[1], L), 1e-12 * closed);
  // Uniform loads alone, in both planes: (q₁² + q₂²)L⁵/(240EI).
  Scene only_q = one_fibre(L);
  add_uniform(only_q, "F", {0, 3e-5, -4e-5});
  const Superposition uniform(make_fibres(only_q), only_q);
  uniform.contact_displacements({}, {}, true, u_a, u_b, &U);
  const double q_closed = (9e-10 + 16e-10) * std::pow(L, 5) / (240 * EI);
  EXPECT_NEAR(U, q_closed, 1e-12 * q_closed);
  // No loads at all: zero.
  uniform.contact_displacements({}, {}, false, u_a, u_b, &U);
  EXPECT_EQ(U, 0.0);
}

TEST(Superposition, ExactEnergyWithContactsIsTheBendingEnergyOfEveryFibre) {
  // Clapeyron: ½ΣP·v over every load of every fibre (both sides of each contact) equals
  // Σ∫M²/(2EI), integrated exactly from the textbook moments.
  const CoupledScene k;
  Superposition superposition(make_fibres(k.scene), k.scene);
  superposition.attach(k.contacts);
  std::vector<V> u_a, u_b;
  double U = 0;
  superposition.contact_displacements(k.contacts, k.force_on_a, true, u_a, u_b, &U);
  const double expected =
      bending_energy({{0.3, 1e-5, -1e-4}, {0.3, 0, 5e-5}, {0.7, 0, 3e-5}}, 0, 0, 1) +
      bending_energy({{0.6, 1e-4, 0}, {0.25, -2e-4, 0}}, 0, 0, 1) +
      bending_energy({{0.4, -5e-5, 0}}, 0, 0, 1);
  EXPECT_NEAR(U, expected, 1e-12 * expected);
  // ½ΣP·v from the displacements returned (scene load on B evaluated separately).
  std::vector<V> at_load;
  superposition.fibre_field(1, k.force_on_a, true, {0.25}, at_load);
  double work = 0.5 * V(0, 0, -2e-4).dot(at_load[0]);
  for (std::size_t c = 0; c < k.contacts.size(); ++c) {
    work += 0.5 * k.force_on_a[c].dot(u_a[c]);
    if (k.contacts[c].kind != ContactKind::wall) work -= 0.5 * k.force_on_a[c].dot(u_b[c]);
  }
  EXPECT_NEAR(U, work, 1e-12 * expected);
}

TEST(Superposition, TrapeziumEnergyIsTheHandTrapeziumSum) {
  const double L = 1.5;
  Scene s = one_fibre(L);
  add_point(s, "F", 0.23, {0, 2e-4, -1e-4});
  add_point(s, "F", 0.61, {0, 0, 3e-4});
  add_uniform(s, "F", {0, -4e-5, 6e-5});
  const std::vector<PlaneLoad> loads = {{0.23 * L, 2e-4, -1e-4}, {0.61 * L, 0, 3e-4}};
  const Superposition superposition(make_fibres(s), s);
  for (int n : {1, 2, 7, 50}) {
    double sum = 0;
    for (int j = 0; j <= n; ++j) {
      const Field f = textbook(loads, -4e-5, 6e-5, j * L / n, L);
      sum += (j == 0 || j == n ? 0.5 : 1.0) * (f.m1 * f.m1 + f.m2 * f.m2);
    }
    const double hand = sum * (L / n) / (2 * EI);
    EXPECT_NEAR(superposition.trapezium_energy({}, n), hand, 1e-12 * hand + 1e-30) << n;
  }
}

TEST(Superposition, TrapeziumEnergyOverestimatesAMidSpanLoadByItsEulerMaclaurinTerm) {
  // U_n = P²L³/(96EI) + h²P²L/(48EI), h = L/n, n even; the error falls as 1/n².
  const double L = 1.0, P = 3e-4;
  Scene s = one_fibre(L);
  add_point(s, "F", 0.5, {0, 0, -P});
  const Superposition superposition(make_fibres(s), s);
  const double exact = P * P * L * L * L / (96 * EI);
  for (int n : {2, 10, 50, 400}) {
    const double h = L / n;
    EXPECT_NEAR(superposition.trapezium_energy({}, n), exact + h * h * P * P * L / (48 * EI),
                1e-12 * exact)
        << n;
  }
  std::vector<V> u_a, u_b;
  double U = 0;
  superposition.contact_displacements({}, {}, true, u_a, u_b, &U);
  EXPECT_NEAR(U, exact, 1e-12 * exact);
}

TEST(Superposition, TrapeziumEnergyCountsContactForces) {
  const CoupledScene k;
  Superposition superposition(make_fibres(k.scene), k.scene);
  superposition.attach(k.contacts);
  const int n = 40;
  const std::vector<std::vector<PlaneLoad>> per_fibre = {
      {{0.3, 1e-5, -1e-4}, {0.3, 0, 5e-5}, {0.7, 0, 3e-5}},
      {{0.6, 1e-4, 0}, {0.25, -2e-4, 0}},
      {{0.4, -5e-5, 0}}};
  double hand = 0;
  for (const auto& loads : per_fibre) {
    double sum = 0;
    for (int j = 0; j <= n; ++j) {
      const Field f = textbook(loads, 0, 0, double(j) / n, 1);
      sum += (j == 0 || j == n ? 0.5 : 1.0) * (f.m1 * f.m1 + f.m2 * f.m2);
    }
    hand += sum / n / (2 * EI);
  }
  EXPECT_NEAR(superposition.trapezium_energy(k.force_on_a, n), hand, 1e-12 * hand);
}

TEST(Superposition, AxialLoadDroppedSumsTheAxialPartsOfSkewLoads) {
  // A along x (L = 1.5), B along y crossing it: |external point·x| + |q·x|·L + |F_AB·x| + |F_AB·y|
  // + |F_wall·x| = 3e-4 + 2e-5·1.5 + 1e-4 + 2e-4 + 4e-5.
  Scene s;
  s.fibres = {fibre("A", {0, 0, 0}, {1.5, 0, 0}), fibre("B", {0.5, -0.5, 0.02}, {0.5, 0.5, 0.02})};
  WallSpec floor;
  floor.id = "floor";
  s.walls.push_back(floor);
  add_point(s, "A", 0.3, {3e-4, 1e-4, 0});
  add_point(s, "A", 0.6, {0, 0, -1e-4});  // no axial part
  add_uniform(s, "A", {-2e-5, 0, 1e-5});
  Superposition superposition(make_fibres(s), s);
  EXPECT_NEAR(superposition.axial_load_dropped({}, {}), 3e-4 + 3e-5, 1e-19);
  Contact ab, wall;
  ab.a = 0, ab.b = 1, ab.s_a = 1.0 / 3, ab.s_b = 0.5;
  wall.kind = ContactKind::wall, wall.a = 0, wall.b = 0, wall.s_a = 0.5;
  const std::vector<Contact> contacts = {ab, wall};
  superposition.attach(contacts);
  const std::vector<V> force_on_a = {V(1e-4, 2e-4, -5e-4), V(4e-5, 0, 1e-4)};
  EXPECT_NEAR(superposition.axial_load_dropped(contacts, force_on_a),
              3e-4 + 3e-5 + 1e-4 + 2e-4 + 4e-5, 1e-19);
  // Forces across both fibres drop nothing.
  EXPECT_NEAR(superposition.axial_load_dropped(contacts, {V(0, 0, -5e-4), V(0, 0, 1e-4)}),
              3e-4 + 3e-5, 1e-19);
}

TEST(Superposition, ManyEqualPointLoadsApproachTheUniformLoad) {
  const int N = 2000;
  const double L = 1.0, q = 1e-4;
  Scene s = one_fibre(L);
  for (int i = 0; i < N; ++i) add_point(s, "F", (i + 0.5) / N, {0, 0, -q * L / N});
  const Superposition superposition(make_fibres(s), s);
  std::vector<V> u;
  std::vector<Eigen::Vector2d> moment;
  superposition.fibre_field(0, {}, true, {0.5}, u, &moment);
  const double v_uniform = 5 * q * std::pow(L, 4) / (384 * EI);
  // Midpoint rule on the influence line: 1 + 0.4/N², the next term O(1/N⁴) and rounding of 2000
  // loads (~1e-13) far below the 0.02/N² = 5e-9 allowed.
  const double relative = -u[0].z() / v_uniform - 1;
  EXPECT_NEAR(relative, 0.4 / (double(N) * N), 0.02 / (double(N) * N));
  EXPECT_NEAR(u[0].x(), 0.0, 1e-20);
  EXPECT_NEAR(u[0].y(), 0.0, 1e-20);
  // The moment is exact: the influence line of M(L/2) is linear on every cell.
  EXPECT_NEAR(-moment[0][1], q * L * L / 8, 1e-12 * q * L * L / 8);
  // And the exact energy tends to q²L⁵/(240EI) the same way (to 1e-6).
  std::vector<V> u_a, u_b;
  double U = 0;
  superposition.contact_displacements({}, {}, true, u_a, u_b, &U);
  const double U_uniform = q * q * std::pow(L, 5) / (240 * EI);
  EXPECT_NEAR(U, U_uniform, 1e-6 * U_uniform);
}

}  // namespace
}  // namespace fibrecheck
