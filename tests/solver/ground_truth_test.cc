// The closed-form answers every solver must meet (DESIGN §7), run through the whole iterative
// solver. Each fixture states its problem and its known answer.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "iterative_solver.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

using testing::bending_stiffness;
using testing::compliance;

Result solve(const Scene& scene) {
  validate_scene(scene);
  return solve_iteratively(scene, SolverOptions::from_scene(scene));
}

const ContactResult* find_contact(const Result& r, const std::string& a, const std::string& b) {
  for (const ContactResult& c : r.contacts)
    if ((c.fibres[0] == a && c.fibres[1] == b) || (c.fibres[0] == b && c.fibres[1] == a)) return &c;
  return nullptr;
}

// One pinned fibre under one point load, no contacts: the sampled displacement is Eqs. 4.12–4.13
// in the load's direction, whatever the fibre's orientation; the axial part is dropped.
TEST(GroundTruth, OnePointLoadOnASkewFibre) {
  Scene s;
  const Eigen::Vector3d start(0.1, 0.2, 0.3), end(0.7, -0.1, 0.9);
  s.fibres.push_back(testing::fibre("F", start, end, 0.012, 70000));
  const Eigen::Vector3d t = (end - start).normalized();
  const Eigen::Vector3d transverse = t.unitOrthogonal();
  LoadSpec load;
  load.fibre = "F";
  load.position = 0.3;
  load.force = 2e-4 * transverse + 5e-5 * t;
  s.loads.push_back(load);
  s.output.samples = 11;
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged);
  const double L = (end - start).norm(), EI = bending_stiffness(0.012, 70000), a = 0.3 * L;
  for (int j = 0; j < 11; ++j) {
    const double x = L * j / 10.0, b = L - a;
    const double v = x <= a
                         ? 2e-4 * b * x * (L * L - b * b - x * x) / (6 * EI * L)
                         : 2e-4 * a * (L - x) * (L * L - a * a - (L - x) * (L - x)) / (6 * EI * L);
    EXPECT_NEAR((r.fibres[0].displacement[j] - v * transverse).norm(), 0.0, 1e-12 * (1 + v / 1e-3));
  }
  EXPECT_NEAR(r.axial_load_dropped, 5e-5, 1e-18);
  // Energy: ½ P v at the load.
  EXPECT_NEAR(r.strain_energy_exact, 0.5 * 2e-4 * 2e-4 * compliance(a, L, EI), 1e-15);
}

// Two pinned fibres crossing with overlap δ: P = δ / (C_A + C_B), C = a²b²/(3EIL) on each fibre.
// Swept over crossing positions, radii, moduli and lengths, for every update rule.
struct CrossingCase {
  double sa, sb, ra, rb, ea, eb, la, lb;
};

}  // namespace

void PrintTo(UpdateRule rule, std::ostream* os) {
  *os << to_string(rule);
}

namespace {

void PrintTo(const CrossingCase& k, std::ostream* os) {
  *os << "crossing at (" << k.sa << ", " << k.sb << ")";
}

class Crossing : public ::testing::TestWithParam<std::tuple<CrossingCase, UpdateRule>> {};

TEST_P(Crossing, ForceIsOverlapOverSummedCompliances) {
  const auto [k, rule] = GetParam();
  const double overlap = 1e-3;
  Scene s = testing::crossing(k.sa, k.sb, overlap, k.ra, k.rb, k.ea, k.eb, k.la, k.lb);
  const double C = compliance(k.sa * k.la, k.la, bending_stiffness(k.ra, k.ea)) +
                   compliance(k.sb * k.lb, k.lb, bending_stiffness(k.rb, k.eb));
  s.solver.rule = rule;
  if (rule == UpdateRule::seed) s.solver.c = 1.0 / C;  // 2/λmax = 2/C here
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_EQ(r.contacts[0].kind, "point");
  EXPECT_NEAR(r.contacts[0].total_force, overlap / C, 1e-4 * overlap / C);
  EXPECT_NEAR(r.contacts[0].points[0].position, k.sa, 1e-6);
  // Energy: ½Pδ, and the trapezium estimate close to it.
  EXPECT_NEAR(r.strain_energy_exact, 0.5 * overlap * overlap / C,
              1e-4 * 0.5 * overlap * overlap / C);
  EXPECT_NEAR(r.c_stable_limit, 2.0 / C, 1e-6 * 2.0 / C);
}

INSTANTIATE_TEST_SUITE_P(
    PositionsAndMaterials, Crossing,
    ::testing::Combine(
        ::testing::Values(CrossingCase{0.5, 0.5, 0.01, 0.01, 80000, 80000, 1, 1},
                          CrossingCase{0.3, 0.7, 0.01, 0.01, 80000, 80000, 1, 1},
                          CrossingCase{0.15, 0.42, 0.012, 0.008, 230000, 72000, 1.3, 0.8},
                          CrossingCase{0.77, 0.5, 0.005, 0.02, 3500, 80000, 2.0, 1.0}),
        ::testing::Values(UpdateRule::seed, UpdateRule::automatic, UpdateRule::accelerated)),
    [](const ::testing::TestParamInfo<Crossing::ParamType>& info) {
      const CrossingCase& k = std::get<0>(info.param);
      return "at_" + std::to_string(static_cast<int>(k.sa * 100)) + "_" +
             std::to_string(static_cast<int>(k.sb * 100)) + "_rule_" +
             to_string(std::get<1>(info.param));
    });

// Two parallel fibres touching along their length, uniform load q on A: contact line load
// q·EI_B/(EI_A + EI_B), deflection 5qL⁴/(384(EI_A + EI_B)); the slice forces sum to the line load.
TEST(GroundTruth, ParallelFibresShareAUniformLoad) {
  const double q = 1e-4;
  const Scene s = testing::parallel(q, 100);
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  const double EIa = bending_stiffness(0.01, 80000), EIb = bending_stiffness(0.008, 70000);
  const ContactResult* c = find_contact(r, "A", "B");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->kind, "line");
  EXPECT_NEAR(c->total_force, q * EIb / (EIa + EIb), 0.01 * q * EIb / (EIa + EIb));
  const double mid = 5 * q / (384 * (EIa + EIb));
  const int middle = s.output.samples / 2;
  EXPECT_NEAR(-r.fibres[0].displacement[middle].z(), mid, 1e-3 * mid);
  EXPECT_NEAR(-r.fibres[1].displacement[middle].z(), mid, 1e-3 * mid);
  EXPECT_EQ(std::count(r.stages.begin(), r.stages.end(), "slices"), 1);
  EXPECT_EQ(std::count(r.stages.begin(), r.stages.end(), "point_contacts"), 0);
}

// A very stiff fibre (E 10⁴ times larger) pressed across three others with different overlaps:
// each contact force solves W·P = δ exactly, with W from the beam formulas, and is close to
// δ_i / C_i of the soft fibre alone. The stiffness ratio must not break convergence.
TEST(GroundTruth, StiffFibrePressingOthers) {
  using testing::fibre;
  Scene s;
  const double r = 0.01, E = 80000, Es = 8e8;
  const double ys[3] = {-0.3, 0.05, 0.35}, overlaps[3] = {1e-3, 5e-4, 2e-3};
  s.fibres.push_back(fibre("S", {0.5, -0.5, 0}, {0.5, 0.5, 0}, r, Es));
  for (int i = 0; i < 3; ++i)
    s.fibres.push_back(fibre("F" + std::to_string(i), {0, ys[i], -(2 * r - overlaps[i])},
                             {1, ys[i], -(2 * r - overlaps[i])}, r, E));
  s.solver.overlap_tolerance = 1e-10;
  for (UpdateRule rule : {UpdateRule::automatic, UpdateRule::accelerated}) {
    s.solver.rule = rule;
    const Result res = solve(s);
    ASSERT_EQ(res.status, Status::converged) << res.message;
    // W_ij = C_S(y_i, y_j) + δ_ij C_F(L/2): the stiff fibre couples the three contacts.
    const double EIs = bending_stiffness(r, Es), EI = bending_stiffness(r, E);
    Eigen::Matrix3d W;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        W(i, j) = testing::unit_load_deflection(ys[i] + 0.5, ys[j] + 0.5, EIs);
        if (i == j) W(i, j) += compliance(0.5, 1.0, EI);
      }
    const Eigen::Vector3d P =
        W.ldlt().solve(Eigen::Vector3d(overlaps[0], overlaps[1], overlaps[2]));
    for (int i = 0; i < 3; ++i) {
      const ContactResult* c = find_contact(res, "S", "F" + std::to_string(i));
      ASSERT_NE(c, nullptr);
      EXPECT_NEAR(c->total_force, P[i], 1e-6 * P[i]);
      EXPECT_NEAR(c->total_force, overlaps[i] / compliance(0.5, 1.0, EI), 1e-3 * P[i]);
    }
  }
}

// Energy: the trapezium rule Σ∫M²/2EI (Eq. 4.34) converges to ½ΣP·v at second order as the
// slices grow.
TEST(GroundTruth, TrapeziumEnergyConvergesToExactEnergy) {
  double previous_error = INFINITY;
  for (int n : {8, 16, 32, 64, 128}) {
    Scene s = testing::crossing(0.375, 0.625, 1e-3);  // load points on the grid for n ≥ 8
    s.contact.slices = n;
    const Result r = solve(s);
    ASSERT_EQ(r.status, Status::converged);
    const double error = std::fabs(r.strain_energy - r.strain_energy_exact) / r.strain_energy_exact;
    EXPECT_LT(error, previous_error / 3.0) << "n = " << n;  // second order: ~4× per doubling
    previous_error = error;
  }
  EXPECT_LT(previous_error, 2e-4);  // n = 128
}

// Eq. 4.28: each slice carries 1/n of the line force, so the stable step c shrinks as 1/n (the
// operator W grows as n) while the summed force stays the same.
TEST(GroundTruth, SliceForcesScaleAsOneOverN) {
  const double q = 1e-4;
  double limit_times_n = 0.0, total = 0.0;
  for (int n : {25, 50, 100}) {
    const Result r = solve(testing::parallel(q, n));
    ASSERT_EQ(r.status, Status::converged) << "n = " << n;
    const ContactResult& c = r.contacts.at(0);
    double middle_force = 0.0;
    for (const ContactPoint& p : c.points)
      if (std::fabs(p.position - 0.5) < 0.5 / n + 1e-12)
        middle_force = std::max(middle_force, p.force.norm());
    // A slice near mid-span carries about total/n.
    EXPECT_NEAR(middle_force * n, c.total_force, 0.05 * c.total_force) << "n = " << n;
    if (total > 0) {
      EXPECT_NEAR(c.total_force, total, 0.03 * total) << "n = " << n;
    }
    total = c.total_force;
    if (limit_times_n > 0) {
      EXPECT_NEAR(r.c_stable_limit * n, limit_times_n, 0.1 * limit_times_n);
    }
    limit_times_n = r.c_stable_limit * n;
  }
}

// The seed's test case (committed scene): slanted fibres pressed from both sides do not bend, so
// each straight fibre carries P = v / C(a), 30.16e-3·v at L/2 and 97.7e-3·v at L/6.
TEST(GroundTruth, CompactionTestCase) {
  Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/compaction_test.json");
  // The closed form is that of small deflections; on the deformed fibres the crossings slide a
  // little along the slopes of the bent fibres (by 1e-4 mm at a = 1/6, where A's compliance
  // changes by 9.6 per mm) and the forces differ by up to 7e-4.
  const Result deformed = solve(s);
  s.contact.geometry = ContactGeometryModel::linearised;
  const Result r = solve(s);
  ASSERT_EQ(deformed.status, Status::converged) << deformed.message;
  ASSERT_EQ(deformed.contacts.size(), r.contacts.size());
  for (const ContactResult& c : r.contacts) {
    const ContactResult* same = find_contact(deformed, c.fibres[0], c.fibres[1]);
    ASSERT_NE(same, nullptr) << c.fibres[0] << "–" << c.fibres[1];
    EXPECT_NEAR(same->total_force, c.total_force, 1e-3 * c.total_force);
  }
  ASSERT_EQ(r.status, Status::converged) << r.message;
  const double EI = bending_stiffness(0.01, 80000);
  EXPECT_NEAR(1.0 / compliance(0.5, 1.0, EI), 30.16e-3, 0.01e-3);
  struct Expected {
    const char* straight;
    const char* slanted;
    double a;
  };
  for (const Expected& e : {Expected{"A1", "S1", 0.5}, Expected{"B1", "S1", 0.5},
                            Expected{"A2", "S2", 1.0 / 6}, Expected{"B2", "S2", 1.0 / 6}}) {
    const int i = s.fibre_index(e.straight), j = s.fibre_index(e.slanted);
    const double v = 2 * 0.01 - std::fabs(s.fibres[i].start.z() - s.fibres[j].start.z());
    const ContactResult* c = find_contact(r, e.straight, e.slanted);
    ASSERT_NE(c, nullptr) << e.straight;
    EXPECT_NEAR(c->total_force, v / compliance(e.a, 1.0, EI), 1e-6 * c->total_force) << e.straight;
  }
  // The slanted fibres do not bend.
  for (const char* id : {"S1", "S2"})
    for (const Eigen::Vector3d& u : r.fibres[s.fibre_index(id)].displacement)
      EXPECT_LT(u.norm(), 1e-12);
}

// Fibre B rests across fibre A at 0.3 of A's length (just touching); a point load P on B at the
// crossing presses it onto A. Small-deflection contact keeps the contact where the fibres cross, so
// the two beams share P by their compliances: R = P·C_B/(C_A + C_B) reaches A.
TEST(GroundTruth, LoadedCrossingSharesTheLoadByCompliance) {
  const double P = 1e-4;
  Scene s = testing::loaded_crossing(P);
  s.solver.overlap_tolerance = 1e-13;
  const double EI = testing::bending_stiffness(0.01, 80000);
  const double CA = compliance(0.3, 1.0, EI), CB = compliance(0.6, 1.0, EI);
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_NEAR(r.contacts[0].total_force, P * CB / (CA + CB), 1e-8 * P);
  EXPECT_NEAR(r.contacts[0].points[0].position, 0.3, 1e-12);
}

// A fibre with a point load P at mid-span above a wall with gap g < P·C: the mid-span slice
// touches the wall and carries R = P − g/C(L/2); nothing else touches.
TEST(GroundTruth, FibrePressedOntoAWall) {
  const double EI = bending_stiffness(0.01, 80000), C = compliance(0.5, 1.0, EI);
  const double P = 1e-4, gap = 0.5 * P * C;
  Scene s = testing::pressed_onto_wall(P, gap);
  s.solver.overlap_tolerance = 1e-11;
  const Result r = solve(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.walls.size(), 1u);
  EXPECT_NEAR(r.walls[0].force, P - gap / C, 1e-6 * P);
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_EQ(r.contacts[0].kind, "wall");
  EXPECT_EQ(r.contacts[0].points.size(), 1u);
  EXPECT_NEAR(r.walls[0].pressure, r.walls[0].force / r.walls[0].area, 1e-15);
}

// Small LCPs: the exact active set by enumeration. Four fibres across one fibre, some touching
// and some not after it deflects: the iteration must find the solution of the complementarity
// problem that enumeration of all 2⁴ active sets finds.
TEST(GroundTruth, SmallLcpMatchesEnumeration) {
  using testing::fibre;
  Scene s;
  const double r = 0.01, E = 80000;
  const double xs[4] = {0.2, 0.4, 0.6, 0.8};
  const double overlaps[4] = {2e-3, -1e-4, 1.5e-3, 1e-5};
  s.contact.geometry = ContactGeometryModel::linearised;  // the LCP of the undeformed normals
  s.fibres.push_back(fibre("M", {0, 0, 0}, {1, 0, 0}, r, E));
  for (int i = 0; i < 4; ++i)
    s.fibres.push_back(fibre("C" + std::to_string(i), {xs[i], -0.5, 2 * r - overlaps[i]},
                             {xs[i], 0.5, 2 * r - overlaps[i]}, r, E * (1 + i)));
  s.solver.overlap_tolerance = 1e-11;
  s.solver.rule = UpdateRule::accelerated;
  const Result res = solve(s);
  ASSERT_EQ(res.status, Status::converged) << res.message;
  const double EI = bending_stiffness(r, E);
  Eigen::Matrix4d W;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      W(i, j) = testing::unit_load_deflection(xs[i], xs[j], EI);
      if (i == j) W(i, j) += compliance(0.5, 1.0, bending_stiffness(r, E * (1 + i)));
    }
  const Eigen::Vector4d d(overlaps[0], overlaps[1], overlaps[2], overlaps[3]);
  Eigen::Vector4d best = Eigen::Vector4d::Constant(NAN);
  for (int mask = 0; mask < 16; ++mask) {
    std::vector<int> active;
    for (int i = 0; i < 4; ++i)
      if (mask & (1 << i)) active.push_back(i);
    Eigen::Vector4d P = Eigen::Vector4d::Zero();
    if (!active.empty()) {
      Eigen::MatrixXd Waa(active.size(), active.size());
      Eigen::VectorXd da(active.size());
      for (std::size_t p = 0; p < active.size(); ++p) {
        da[p] = d[active[p]];
        for (std::size_t q = 0; q < active.size(); ++q) Waa(p, q) = W(active[p], active[q]);
      }
      const Eigen::VectorXd Pa = Waa.ldlt().solve(da);
      for (std::size_t p = 0; p < active.size(); ++p) P[active[p]] = Pa[p];
    }
    const Eigen::Vector4d left = d - W * P;  // remaining overlap
    if ((P.array() >= 0).all() && (left.array() <= 1e-15).all()) best = P;
  }
  ASSERT_TRUE(best.allFinite());
  for (int i = 0; i < 4; ++i) {
    const ContactResult* c = find_contact(res, "M", "C" + std::to_string(i));
    const double force = c ? c->total_force : 0.0;
    EXPECT_NEAR(force, best[i], 1e-6 * best.maxCoeff()) << "contact " << i;
  }
}

}  // namespace
}  // namespace fibrecheck
