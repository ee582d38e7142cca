// The implicit reference meets the closed forms of DESIGN §7 exactly where its elements are
// nodally exact (point contacts), and agrees with the converged iterative solver on the same
// slices.
#include "reference_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "iterative_solver.h"
#include "load_path.h"
#include "result_difference.h"
#include "test_scenes.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

using testing::bending_stiffness;
using testing::compliance;

double force_between(const Result& r, const std::string& a, const std::string& b) {
  for (const ContactResult& c : r.contacts)
    if ((c.fibres[0] == a && c.fibres[1] == b) || (c.fibres[0] == b && c.fibres[1] == a))
      return c.total_force;
  return 0.0;
}

TEST(ReferenceSolver, CrossingForceIsOverlapOverSummedCompliances) {
  struct Case {
    double sa, sb, ra, rb, ea, eb;
  };
  for (const Case& k :
       {Case{0.5, 0.5, 0.01, 0.01, 80000, 80000}, Case{0.3, 0.7, 0.01, 0.01, 80000, 80000},
        Case{0.15, 0.42, 0.012, 0.008, 230000, 72000}}) {
    const double overlap = 1e-3;
    const Scene s = testing::crossing(k.sa, k.sb, overlap, k.ra, k.rb, k.ea, k.eb);
    const double C = compliance(k.sa, 1.0, bending_stiffness(k.ra, k.ea)) +
                     compliance(k.sb, 1.0, bending_stiffness(k.rb, k.eb));
    for (BeamSolver solver : {BeamSolver::direct, BeamSolver::cg_amg}) {
      ReferenceOptions options;
      options.beam_solver = solver;
      const Result r = solve_reference(s, options);
      ASSERT_EQ(r.status, Status::converged) << r.message;
      EXPECT_EQ(r.solver, "fem");
      EXPECT_NEAR(force_between(r, "A", "B"), overlap / C, 1e-8 * overlap / C)
          << k.sa << ", " << k.sb << (solver == BeamSolver::direct ? " MUMPS" : " CG");
      EXPECT_LT(std::fabs(r.max_overlap), 1e-12);
    }
  }
}

// The seed's compaction test case in the linearised model, whose closed form it is; on the deformed
// fibres (the scene's own geometry) the crossings slide along the walled fibres by a little and
// the forces move by less than 1e-3.
TEST(ReferenceSolver, CompactionTestCaseIsExact) {
  Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/compaction_test.json");
  const Result deformed = solve_reference(s);
  ASSERT_EQ(deformed.status, Status::converged) << deformed.message;
  s.contact.geometry = ContactGeometryModel::linearised;
  const Result r = solve_reference(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  const double EI = bending_stiffness(0.01, 80000);
  const double v = 2 * 0.01 - 0.0195;
  EXPECT_NEAR(force_between(r, "A1", "S1"), v / compliance(0.5, 1.0, EI),
              1e-8 * v / compliance(0.5, 1.0, EI));
  EXPECT_NEAR(force_between(r, "B2", "S2"), v / compliance(1.0 / 6, 1.0, EI),
              1e-8 * v / compliance(1.0 / 6, 1.0, EI));
  EXPECT_EQ(r.walls.size(), 4u);
  for (const char* a : {"A1", "B2"}) {
    const std::string b = std::string(a) == "A1" ? "S1" : "S2";
    EXPECT_NEAR(force_between(deformed, a, b), force_between(r, a, b),
                1e-3 * force_between(r, a, b));
  }
}

// Four fibres across one: the exact active set by enumeration, as for the iterative solver.
TEST(ReferenceSolver, SmallLcpMatchesEnumeration) {
  using testing::fibre;
  Scene s;
  const double r = 0.01, E = 80000, xs[3] = {0.2, 0.45, 0.8}, overlaps[3] = {2e-3, -1e-4, 1.5e-3};
  s.fibres.push_back(fibre("M", {0, 0, 0}, {1, 0, 0}, r, E));
  for (int i = 0; i < 3; ++i)
    s.fibres.push_back(fibre("C" + std::to_string(i), {xs[i], -0.5, 2 * r - overlaps[i]},
                             {xs[i], 0.5, 2 * r - overlaps[i]}, r, E * (1 + i)));
  s.contact.geometry = ContactGeometryModel::linearised;  // the LCP of small deflections
  const Result res = solve_reference(s);
  ASSERT_EQ(res.status, Status::converged) << res.message;
  const double EI = bending_stiffness(r, E);
  Eigen::Matrix3d W;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W(i, j) = testing::unit_load_deflection(xs[i], xs[j], EI);
      if (i == j) W(i, j) += compliance(0.5, 1.0, bending_stiffness(r, E * (1 + i)));
    }
  // C1 stays clear; C0 and C2 push: solve the 2×2 system of the active pair.
  Eigen::Matrix2d Waa;
  Waa << W(0, 0), W(0, 2), W(2, 0), W(2, 2);
  const Eigen::Vector2d P = Waa.ldlt().solve(Eigen::Vector2d(overlaps[0], overlaps[2]));
  EXPECT_NEAR(force_between(res, "M", "C0"), P[0], 1e-8 * P[0]);
  EXPECT_NEAR(force_between(res, "M", "C2"), P[1], 1e-8 * P[1]);
  EXPECT_EQ(force_between(res, "M", "C1"), 0.0);
  EXPECT_LT(overlaps[1] - (W(1, 0) * P[0] + W(1, 2) * P[1]), 0.0);  // C1 really stays clear
}

// Same slices, same line contact: the reference and the converged iterative solver give the same
// deflections; the line force is the closed form within the slices' discretisation error.
TEST(ReferenceSolver, ParallelFibresOnSlicesAgreeWithTheIterativeSolver) {
  const double q = 1e-4;
  const Scene s = testing::parallel(q, 40);
  const Result fem = solve_reference(s);
  ASSERT_EQ(fem.status, Status::converged) << fem.message;
  const Result it = solve_iteratively(s, SolverOptions::from_scene(s));
  ASSERT_EQ(it.status, Status::converged);
  double largest = 0.0, difference = 0.0;
  for (std::size_t f = 0; f < 2; ++f)
    for (std::size_t j = 0; j < fem.fibres[f].displacement.size(); ++j) {
      largest = std::max(largest, fem.fibres[f].displacement[j].norm());
      difference = std::max(difference,
                            (fem.fibres[f].displacement[j] - it.fibres[f].displacement[j]).norm());
    }
  EXPECT_LT(difference, 1e-6 * largest);
  const double EIa = bending_stiffness(0.01, 80000), EIb = bending_stiffness(0.008, 70000);
  EXPECT_NEAR(force_between(fem, "A", "B"), q * EIb / (EIa + EIb), 0.02 * q * EIb / (EIa + EIb));
}

/// Largest difference of the contact forces (relative to the largest force) and of the sampled
/// displacements (relative to the largest displacement) between two results of one scene.
struct Difference {
  double force = 0.0, displacement = 0.0;
};

Difference compare(const Result& x, const Result& y) {
  std::map<std::tuple<std::string, std::string, long long>, Eigen::Vector3d> forces;
  double largest_force = 0.0;
  for (const Result* r : {&x, &y})
    for (const ContactResult& c : r->contacts)
      for (const ContactPoint& p : c.points) {
        const auto key = std::make_tuple(c.fibres[0], c.fibres[1], std::llround(p.position * 1e9));
        auto it = forces.try_emplace(key, Eigen::Vector3d::Zero()).first;
        it->second += (r == &x ? 1.0 : -1.0) * p.force;
        largest_force = std::max(largest_force, p.force.norm());
      }
  Difference d;
  for (const auto& [key, f] : forces) d.force = std::max(d.force, f.norm());
  d.force /= largest_force;
  d.displacement = testing::displacement_difference(x, y);
  return d;
}

// The same slices: the reference equals the iterative solver converged far below its usual
// tolerance (1e-13 mm), on the committed scenes, in both contact models. Linearised, contacts take
// place and normal from the undeformed fibres in both, so there is one answer to agree on, to
// 1e-6. On the deformed fibres each solver settles the normals by its own sequence of linearised
// problems, the iterative one when its residual has fallen below a tenth of what the last update
// left, the reference to 1e-3 of t_d: 1e-5 (measured 1.2e-6 on the tow). Contact by contact on the
// crossing and the
// tow; on the parallel fibres the deflections, the energy and the line's total force, since there
// the share of each slice next to a pinned end barely moves the fibres and the iteration settles
// it last (slices 0–5 and 94–99 still differ by up to 2e-3 of the largest at 1e-13 mm, 2e-4 at
// 1e-14 mm; the middle 60 slices by 6e-6).
TEST(ReferenceSolver, CommittedScenesOnSlicesAgreeWithTheConvergedIterativeSolver) {
  for (const ContactGeometryModel model :
       {ContactGeometryModel::linearised, ContactGeometryModel::deformed})
    for (const char* name : {"two_fibres_crossing", "parallel_fibres", "small_tow_19"}) {
      SCOPED_TRACE(to_string(model));
      const double agree = model == ContactGeometryModel::linearised ? 1e-6 : 1e-5;
      Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/" + name + ".json");
      s.contact.geometry = model;
      s.solver.overlap_tolerance = 1e-13;
      s.solver.rule = UpdateRule::accelerated;
      const Result it = solve_iteratively(s, SolverOptions::from_scene(s));
      ASSERT_EQ(it.status, Status::converged) << name << ": " << it.message;
      const Result fem = solve_reference(s);
      ASSERT_EQ(fem.status, Status::converged) << name << ": " << fem.message;
      const Difference d = compare(fem, it);
      if (std::string(name) == "parallel_fibres") {
        ASSERT_EQ(fem.contacts.size(), 1u);
        ASSERT_EQ(it.contacts.size(), 1u);
        // The end slices' differences (≤ 2e-3 of a slice force, a dozen slices of 100) bound the
        // total's: ≤ 5e-5 (measured 1e-5).
        EXPECT_NEAR(fem.contacts[0].total_force, it.contacts[0].total_force,
                    5e-5 * it.contacts[0].total_force);
      } else {
        EXPECT_LT(d.force, agree) << name;
      }
      EXPECT_LT(d.displacement, agree) << name;
      EXPECT_NEAR(fem.strain_energy, it.strain_energy, agree * it.strain_energy) << name;
      // The complementarity conditions hold to round-off.
      EXPECT_LT(fem.max_overlap, 1e-10) << name;
      EXPECT_LT(fem.gap_force_residual, 1e-10) << name;
      ASSERT_TRUE(fem.finite_elements.has_value()) << name;
      EXPECT_GT(fem.finite_elements->active_set_iterations, 0) << name;
    }
}

// Under the linearised contact a slice pushes when its overlap along the undeformed normal does,
// however far the displaced centres slide apart. On this compacted tow (largest deflection 0.72 r)
// fibres that overlapped before compaction slide sideways past each other by more than the
// candidate margin: measured on the displaced centres they were no longer candidates, and the
// reference's answer left overlaps of 4e-4 mm along their normals, 0.3–0.4 off the iterative
// solver's forces. Both solvers converged tightly solve the same problem: they agree to round-off
// (measured 2e-11), so 1e-6 is the bound of the linearised committed scenes above.
TEST(ReferenceSolver, LinearisedTowWhoseFibresSlideApartAgreesWithTheIterativeSolver) {
  TowOptions tow;
  tow.fibres = 150;
  tow.slices = 50;
  tow.seed = 1;
  tow.compaction = 0.8;
  Scene s = generate_tow(tow);
  s.contact.geometry = ContactGeometryModel::linearised;
  s.solver.overlap_tolerance = 1e-12;
  s.solver.force_tolerance = 1e-8;
  const Result it = solve_iteratively(s, SolverOptions::from_scene(s));
  ASSERT_EQ(it.status, Status::converged) << it.message;
  const Result fem = solve_reference(s);
  ASSERT_EQ(fem.status, Status::converged) << fem.message;
  const Difference d = compare(fem, it);
  EXPECT_LT(d.force, 1e-6);
  EXPECT_LT(d.displacement, 1e-6);
  EXPECT_NEAR(fem.strain_energy, it.strain_energy, 1e-6 * it.strain_energy);
}

// The continuous line contact's cells: n·2^K, and down to n/4 (whole, at least 4 cells) below.
TEST(ReferenceSolver, ContinuousCellsHalveDownToTheCoarsest) {
  const auto cells = [](int n, int K) { return continuous_cells(testing::parallel(1e-4, n), K); };
  const auto coarsest = [](int n) { return coarsest_refinement(testing::parallel(1e-4, n)); };
  EXPECT_EQ(coarsest(100), -2);
  EXPECT_EQ(cells(100, -2), 25);
  EXPECT_EQ(cells(100, 1), 200);
  EXPECT_EQ(coarsest(50), -1);
  EXPECT_EQ(cells(50, -1), 25);
  EXPECT_EQ(coarsest(8), -1);  // 4 cells, not 2
  EXPECT_EQ(coarsest(5), 0);
  EXPECT_EQ(coarsest(6), 0);  // 3 cells would be too few
  EXPECT_THROW(cells(50, -2), std::invalid_argument);
}

// Continuous line contact: parallel fibres pressed together along their whole length share the
// load by stiffness, p = q·EI_B/(EI_A + EI_B) (DESIGN §7). Enforced at the Gauss points of n·2^K
// cells, the line force converges at first order (the share of the line next to the pinned ends,
// where a force moves nothing, is what the points resolve) and the deflection much faster.
TEST(ReferenceSolver, ContinuousLineContactConvergesUnderRefinement) {
  const double q = 1e-4;
  const double EIa = bending_stiffness(0.01, 80000), EIb = bending_stiffness(0.008, 70000);
  const double p = q * EIb / (EIa + EIb), w = 5.0 * p / (384.0 * EIb);
  ReferenceOptions options;
  options.line_contact = LineContact::continuous;
  std::vector<double> force_error, deflection_error;
  for (int K = 0; K <= 2; ++K) {
    options.refine = K;
    const Result r = solve_reference(testing::parallel(q, 10), options);
    ASSERT_EQ(r.status, Status::converged) << r.message;
    force_error.push_back(std::fabs(force_between(r, "A", "B") - p) / p);
    const auto& u = r.fibres[1].displacement;
    deflection_error.push_back(std::fabs(std::fabs(u[u.size() / 2].z()) - w) / w);
  }
  for (int K = 1; K <= 2; ++K) {
    const double order = std::log2(force_error[K - 1] / force_error[K]);
    EXPECT_NEAR(order, 1.0, 0.05) << "K = " << K;
    EXPECT_LT(deflection_error[K], deflection_error[K - 1]);
  }
  EXPECT_LT(deflection_error[1], 1e-6);
  // The default mesh (one cell per slice of the scene, here 100) is within its first-order
  // error, 1.6e-4; one refinement (400 Gauss points) halves it, with every point pushing: the
  // overlaps are resolved to the round-off of the finite elements, not to a threshold at which
  // every other point may stay out and the line force is 3e-3 low.
  options.refine = 0;
  const Result r = solve_reference(testing::parallel(q, 100), options);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  EXPECT_LT(std::fabs(force_between(r, "A", "B") - p), 2e-4 * p);
  options.refine = 1;
  const Result fine = solve_reference(testing::parallel(q, 100), options);
  ASSERT_EQ(fine.status, Status::converged) << fine.message;
  ASSERT_EQ(fine.contacts.size(), 1u);
  EXPECT_EQ(fine.contacts[0].points.size(), 400u);
  EXPECT_LT(std::fabs(force_between(fine, "A", "B") - p), 1e-4 * p);
  EXPECT_LT(fine.max_overlap, 1e-12);  // the scene's tolerance, met by the FE solution itself
  EXPECT_TRUE(fine.warnings.empty());
  // Refined until the extrapolated line force settles to 1e-4, from the coarsest cells (25 for
  // 100 slices): the extrapolation meets the closed form far inside 1e-4 (6e-8 measured) and
  // observes the first order.
  options.refine = 0;
  options.refine_until_converged = true;
  options.refinement_tolerance = 1e-4;
  const Result settled = solve_reference(testing::parallel(q, 100), options);
  ASSERT_EQ(settled.status, Status::converged) << settled.message;
  ASSERT_EQ(settled.contacts.size(), 1u);
  ASSERT_TRUE(settled.contacts[0].extrapolated_force.has_value());
  EXPECT_LT(std::fabs(*settled.contacts[0].extrapolated_force - p), 1e-6 * p);
  EXPECT_GT(std::fabs(settled.contacts[0].total_force - p), 1e-5 * p);  // the last level is not
  EXPECT_NEAR(settled.finite_elements->line_force_order, 1.0, 0.05);
  EXPECT_LE(settled.finite_elements->line_force_error_estimate, 1e-4);
  EXPECT_EQ(settled.finite_elements->refinement, 1);
  EXPECT_NE(settled.message.find("extrapolated at refinement"), std::string::npos)
      << settled.message;
}

// A load path through the reference: compacting a crossing by F brings B to F·h above A and
// shortens it to F·L_B, P(F) = (r_A + r_B − F·h)/(C_A + C_B(F)) (as the iterative solver's test).
TEST(ReferenceSolver, CompactionStepsMeetTheClosedForm) {
  Scene s = testing::crossing(0.3, 0.6, 1e-4);
  s.steps = {{1.0, 1.0}, {0.999, 1.0}, {0.995, 1.0}};
  const Result r = solve_reference(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 3u);
  const double F = 0.995, h = 0.02 - 1e-4, EI = bending_stiffness(0.01, 80000);
  const double CA = compliance(0.3, 1.0, EI), CB = std::pow(0.6 * F * 0.4 * F, 2) / (3.0 * EI * F);
  const double P = (0.02 - F * h) / (CA + CB);
  EXPECT_NEAR(force_between(r, "A", "B"), P, 1e-8 * P);
  for (const StepResult& step : r.steps) EXPECT_EQ(step.status, Status::converged);
}

// Each step of a load path starts its active set from the forces the step before ended with. A
// frictionless step has one answer whatever the start, so the last step of a compaction path is
// the same as that step solved alone, to round-off: forces carried over from another
// configuration must not stay in the answer.
TEST(ReferenceSolver, LoadStepStartsFromTheLastStepsForces) {
  TowOptions o;
  o.fibres = 19;
  o.slices = 20;
  o.seed = 2;
  o.volume_fraction = 0.35;
  o.steps = 2;
  o.first_compaction = 0.74;
  o.compaction = 0.7;
  const Scene path = generate_tow(o);
  Scene alone = scene_at_step(path, path.steps.back());
  alone.steps.clear();
  const Result along = solve_reference(path), single = solve_reference(alone);
  ASSERT_EQ(along.status, Status::converged) << along.message;
  ASSERT_EQ(single.status, Status::converged) << single.message;
  ASSERT_EQ(along.contacts.size(), single.contacts.size());
  double largest = 0.0;
  for (const ContactResult& c : single.contacts) largest = std::max(largest, c.total_force);
  ASSERT_GT(largest, 0.0);
  for (std::size_t k = 0; k < single.contacts.size(); ++k)
    EXPECT_NEAR(along.contacts[k].total_force, single.contacts[k].total_force, 1e-9 * largest);
}

// A point load on fibre B where it rests (just touching) across fibre A: the two beams share it
// by their compliances, R = P·C_B/(C_A + C_B), with the contact where the chords cross.
TEST(ReferenceSolver, LoadedCrossingSharesTheLoadByCompliance) {
  const double P = 1e-4;
  const Scene s = testing::loaded_crossing(P);
  const double EI = bending_stiffness(0.01, 80000);
  const double CA = compliance(0.3, 1.0, EI), CB = compliance(0.6, 1.0, EI);
  const Result r = solve_reference(s);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  EXPECT_NEAR(force_between(r, "A", "B"), P * CB / (CA + CB), 1e-8 * P);
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_NEAR(r.contacts[0].points[0].position, 0.3, 1e-12);
  // The exact energy ½ΣP·v of the two loads on the two beams.
  const double R = P * CB / (CA + CB);
  EXPECT_NEAR(r.strain_energy_exact, 0.5 * (R * R * CA + (P - R) * (P - R) * CB),
              1e-8 * 0.5 * P * P * CB);
}

// A fibre pressed onto a wall by a point load at mid-span: R = P − g/C(L/2).
TEST(ReferenceSolver, FibrePressedOntoAWall) {
  const double EI = bending_stiffness(0.01, 80000), C = compliance(0.5, 1.0, EI);
  const double P = 1e-4, gap = 0.5 * P * C;
  const Result r = solve_reference(testing::pressed_onto_wall(P, gap));
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.walls.size(), 1u);
  EXPECT_NEAR(r.walls[0].force, P - gap / C, 1e-8 * P);
}

// Two walls in the same plane constrain the same motion twice: the contact problem has many
// answers (any split between the walls) but one total, R = P − g/C(L/2) — no singular-system
// failure.
TEST(ReferenceSolver, TwoWallsInOnePlaneShareTheReaction) {
  const double EI = bending_stiffness(0.01, 80000), C = compliance(0.5, 1.0, EI);
  const double P = 1e-4, gap = 0.5 * P * C;
  const Result r = solve_reference(testing::pressed_onto_wall(P, gap, 2));
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_EQ(r.walls.size(), 2u);
  EXPECT_NEAR(r.walls[0].force + r.walls[1].force, P - gap / C, 1e-8 * P);
}

// An overlap at two pinned supports cannot be resolved: said at once, with no crash on the
// singular system and nothing non-finite in the result.
TEST(ReferenceSolver, OverlapAtTwoPinnedSupportsIsUnresolvable) {
  const Result r = solve_reference(testing::overlapping_supports());
  EXPECT_EQ(r.status, Status::unresolvable);
  EXPECT_NE(r.message.find("A and B"), std::string::npos) << r.message;
  EXPECT_TRUE(std::isfinite(r.strain_energy) && std::isfinite(r.max_overlap));
  for (const FibreResult& f : r.fibres)
    for (const Eigen::Vector3d& u : f.displacement) EXPECT_TRUE(u.allFinite());
}

// The tow needs a second outer iteration (new candidates appear on the deformed fibres): capped
// at one, the run says so, with a finite result on the last candidates.
TEST(ReferenceSolver, OuterIterationCapGivesMaxIterations) {
  const Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/small_tow_19.json");
  ReferenceOptions options;
  options.max_outer_iterations = 1;
  const Result r = solve_reference(s, options);
  EXPECT_EQ(r.status, Status::max_iterations);
  EXPECT_EQ(r.criterion, Criterion::max_iterations);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_NE(r.message.find("outer iterations"), std::string::npos) << r.message;
  EXPECT_TRUE(std::isfinite(r.strain_energy) && std::isfinite(r.max_overlap));
  EXPECT_FALSE(r.contacts.empty());
}

// The beams for ParaView: a .vtu file with the deflections, moments and displacement vectors.
TEST(ReferenceSolver, WritesTheBeamsForParaView) {
  ReferenceOptions options;
  options.vtu = (std::filesystem::temp_directory_path() / "fibrecheck_reference_test.vtu").string();
  const Result r = solve_reference(testing::crossing(0.3, 0.7, 1e-3), options);
  ASSERT_EQ(r.status, Status::converged);
  std::ifstream in(options.vtu);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* field :
       {"<VTKFile", "UnstructuredGrid", "\"w1\"", "\"M2\"", "\"displacement\"", "\"fibre\""})
    EXPECT_NE(text.find(field), std::string::npos) << field;
  std::filesystem::remove(options.vtu);
}

// Every energy the reference reports is its own elements': with linear elements on a coarse mesh
// (a uniform load q on one fibre, 10 slices, samples at the slice nodes, so 10 equal elements)
// the moment is only the interpolant of M(x) = q·x(L − x)/2, exact at the nodes. Then
//  - ∫M_h²/(2EI) and ½∫q·w_h are Σ_e h(M_i² + M_i·M_j + M_j²)/(6EI), below q²L⁵/(240EI), which
//    the beam formulas give;
//  - the trapezium rule of Eq. 4.34 at the slice spacing reads the nodal moments, exact.
TEST(ReferenceSolver, EnergiesComeFromItsOwnElements) {
  const double q = 1e-4;
  const int n = 10;
  Scene s;
  s.name = "uniform";
  s.fibres.push_back(testing::fibre("F", {0, 0, 0}, {1, 0, 0}));
  LoadSpec load;
  load.fibre = "F";
  load.kind = LoadKind::distributed;
  load.force = {0, 0, -q};
  s.loads.push_back(load);
  s.contact.slices = n;
  s.output.samples = n + 1;
  const double EI = bending_stiffness(0.01, 80000);
  auto M = [&](double x) { return q * x * (1 - x) / 2; };
  double elements = 0.0, trapezium = 0.0;
  for (int e = 0; e < n; ++e) {
    const double Mi = M(e / double(n)), Mj = M((e + 1) / double(n));
    elements += (Mi * Mi + Mi * Mj + Mj * Mj) / (6 * EI * n);
    trapezium += 0.5 * (Mi * Mi + Mj * Mj) / (2 * EI * n);
  }
  const double formula = q * q / (240 * EI);
  ASSERT_GT(formula - elements, 1e-3 * formula);

  ReferenceOptions linear;
  linear.degree = 1;
  const Result r = solve_reference(s, linear);
  ASSERT_EQ(r.status, Status::converged) << r.message;
  ASSERT_TRUE(r.finite_elements.has_value());
  EXPECT_EQ(r.finite_elements->unknowns, 4 * (n + 1));
  EXPECT_NEAR(r.strain_energy_exact, elements, 1e-10 * formula);
  EXPECT_NEAR(r.finite_elements->strain_energy_elements, elements, 1e-10 * formula);
  EXPECT_NEAR(r.strain_energy, trapezium, 1e-10 * formula);
  // Quadratic elements (the default) hold M exactly: the formula's energy.
  const Result exact = solve_reference(s);
  ASSERT_EQ(exact.status, Status::converged) << exact.message;
  EXPECT_NEAR(exact.strain_energy_exact, formula, 1e-10 * formula);
  EXPECT_NEAR(exact.finite_elements->strain_energy_elements, formula, 1e-10 * formula);
  EXPECT_NEAR(exact.strain_energy, trapezium, 1e-10 * formula);
}

}  // namespace
}  // namespace fibrecheck
