// The reference against an outside solver: each scene's contact problem, as the reference solved
// it, is exported and solved again by Siconos (fibrecheck-siconos, its own program), and every
// Siconos solver's answer must agree with the reference's where the answer is unique.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "textile_scenes.h"
#include "contact_problem.h"
#include "contact_problem_check.h"
#include "friction_ground_truths.h"
#include "reference_solver.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

struct Exported {
  Result result;
  ContactProblem problem;
  nlohmann::json answers;  ///< fibrecheck-siconos' output
  std::string printed;     ///< and what it printed
  int exit_code = -1;
};

/// The reference on `scene`, its final step's problem written to a file, then fibrecheck-siconos
/// on that file with every solver that takes it.
Exported cross_check(const Scene& scene, const std::string& name, double tolerance = 1e-12) {
  validate_scene(scene);
  Exported e;
  ReferenceOptions options;
  options.contact_problem = [&](const ContactProblem& p) { e.problem = p; };
  e.result = solve_reference(scene, options);
  const std::string problem = ::testing::TempDir() + "siconos_" + name + ".problem.json";
  const std::string answers = ::testing::TempDir() + "siconos_" + name + ".answers.json";
  write_contact_problem(problem, e.problem);
  std::ostringstream command;
  command.precision(17);
  const std::string printed = ::testing::TempDir() + "siconos_" + name + ".printed.txt";
  command << "'" << FIBRECHECK_SICONOS_PROGRAM << "' --tolerance " << tolerance << " '" << problem
          << "' --out '" << answers << "' > '" << printed << "'";
  const int status = std::system(command.str().c_str());
  e.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(answers);
  if (in) in >> e.answers;
  std::ifstream text(printed);
  e.printed.assign(std::istreambuf_iterator<char>(text), std::istreambuf_iterator<char>());
  return e;
}

/// What must hold on every CPU, whichever floating-point kernels built the problem:
///  - the reference's own answer solves the problem (residual within `residual_mm`);
///  - every answer fibrecheck-siconos calls converged really solves it (its residual, computed
///    here from its reaction, within `residual_mm`) and agrees with the reference's within
///    `relative`; every answer it calls not converged really does not (residual above its
///    tolerance), and then the program's exit code says so (3);
///  - each solver in `robust` converges, and at least two independent ones do.
/// A solver left out of `robust` may fail on some CPUs: it is then shown as failed, not hidden.
void expect_agreement(const Exported& e, double relative, double residual_mm, std::size_t solvers,
                      const std::vector<std::string>& robust) {
  ASSERT_EQ(e.result.status, Status::converged) << e.result.message;
  ASSERT_TRUE(e.answers.contains("answers"));
  EXPECT_EQ(e.answers["answers"].size(), solvers);
  const ProblemResidual own = problem_residual(e.problem, e.problem.reaction);
  EXPECT_LE(own.overlap_mm, residual_mm);
  EXPECT_LE(own.slip_mm, residual_mm);
  const double program_tolerance =
      e.answers["residual_tolerance"].get<double>() * residual_scale(e.problem);
  int converged = 0;
  bool all = true;
  for (const auto& a : e.answers["answers"]) {
    const std::string name = a["solver"].get<std::string>();
    SCOPED_TRACE(a["siconos_solver"].get<std::string>());
    const std::vector<double> values = a["reaction"];
    const Eigen::VectorXd reaction =
        Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
    const ProblemResidual residual = problem_residual(e.problem, reaction);
    const bool says_converged = a["converged"].get<bool>();
    all &= says_converged;
    const bool is_robust = std::find(robust.begin(), robust.end(), name) != robust.end();
    if (is_robust) {
      EXPECT_TRUE(says_converged) << name << " is expected to solve this problem";
    }
    if (!says_converged) {
      EXPECT_GT(std::max(residual.overlap_mm, residual.slip_mm), program_tolerance)
          << "called not converged, yet its answer solves the problem";
      continue;
    }
    ++converged;
    EXPECT_LE(residual.overlap_mm, std::min(residual_mm, program_tolerance));
    EXPECT_LE(residual.slip_mm, std::min(residual_mm, program_tolerance));
    EXPECT_LE(a["against_reference"]["relative"].get<double>(), relative);
    EXPECT_EQ(a["against_reference"]["frictions_not_unique"].get<int>(), 0);
  }
  EXPECT_GE(converged, 2);
  EXPECT_EQ(e.exit_code, all ? 0 : 3);
}

// Tolerances: a single contact or a line of slices has a well-conditioned W (its condition is
// that of the fibres' Green's functions at the contact points), Siconos is asked for a relative
// error of 1e-12, and the reference is exact to the round-off of its finite elements: 1e-8
// leaves four orders for the conditioning. Residuals in mm against overlaps of 1e-3 mm.
//
// Which solvers must converge: the Gauss–Seidel methods (PGS, NSGS: each contact solved exactly
// in turn against a positive definite W) and the Newton methods with their line search converge
// from any start on these problems. Lemke's complementary pivoting does not have to: its path is
// decided by ratio tests between nearly equal pivots, so the last bits of W — which follow the
// BLAS kernels that built it — can send it to a wrong vertex that Siconos still reports as solved.

TEST(SiconosCrossCheck, FrictionlessCrossingAsAnLcp) {
  const Exported e = cross_check(testing::sheared_crossing(0.0, 0.0), "crossing_lcp");
  expect_agreement(e, 1e-8, 1e-12, 3, {"pgs", "newton"});  // and lemke
  EXPECT_EQ(e.problem.offset.back(), 1);
}

TEST(SiconosCrossCheck, CrossingSticksAndSlipsIn3d) {
  const testing::CrossingFigures f = testing::crossing_figures();
  for (const double ratio : {0.5, 2.0}) {
    SCOPED_TRACE(ratio);
    const double mu = 0.3;
    const Exported e = cross_check(testing::sheared_crossing(ratio * mu * f.N, mu),
                                   "crossing_" + std::to_string(ratio));
    expect_agreement(e, 1e-8, 1e-12, 2, {"nsgs", "newton"});  // 3-D: two tangents
    ASSERT_EQ(e.problem.contacts.size(), 1u);
    EXPECT_EQ(e.problem.contacts[0].tangents, 2);
    // Both solvers found the closed form: friction H below μN, μN above.
    for (const auto& a : e.answers["answers"]) {
      if (!a["converged"].get<bool>()) continue;
      const std::vector<double> r = a["reaction"];
      EXPECT_NEAR(r[0], f.N, 1e-9 * f.N);
      EXPECT_NEAR(std::hypot(r[1], r[2]), std::min(ratio, 1.0) * mu * f.N, 1e-8 * f.N);
    }
  }
}

TEST(SiconosCrossCheck, ParallelFibresShearedIn2dAnd3d) {
  // Slices: one tangent each (2-D nsgs and lemke, 3-D newton with a padded direction). The line of
  // slices couples every contact to every other through both fibres: Gauss–Seidel converges
  // slowly, and its error measure (relative to ‖q‖) of 1e-12 still leaves 1.3e-7 in the forces;
  // 1e-15 leaves 1e-9.
  const double q = 1e-4, mu = 0.2;
  for (const double ratio : {0.5, 2.0}) {
    SCOPED_TRACE(ratio);
    const Exported e = cross_check(testing::sheared_parallel(q, ratio * mu * q, mu, 20),
                                   "parallel_" + std::to_string(ratio), 1e-15);
    expect_agreement(e, 1e-7, 1e-10, 3, {"nsgs", "newton"});  // and lemke
    EXPECT_GE(e.problem.contacts.size(), 20u);
  }
}

TEST(SiconosCrossCheck, CompactedTowWithFriction) {
  TowOptions options;
  options.fibres = 7;
  options.slices = 10;
  options.seed = 2;
  options.volume_fraction = 0.35;
  options.compaction = 0.75;
  options.friction = 0.2;
  const Scene tow = generate_tow(options);
  const Exported e = cross_check(tow, "tow7");
  // Walls and slices between nearly parallel fibres. The reference's Tresca fixed point stops when
  // Coulomb's law holds to 1e-3 of the scene's tolerance in slip (1e-10 mm here): the overlaps and
  // slips agree to that, 5.5e-8 of the largest |q|, the forces to 1e-8.
  expect_agreement(e, 1e-6, 1e-9, 3, {"nsgs", "newton"});  // and lemke
  int pushing = 0;
  for (std::size_t j = 0; j < e.problem.contacts.size(); ++j)
    pushing += e.problem.reaction[e.problem.offset[j]] > 0.0 ? 1 : 0;
  EXPECT_GE(pushing, 3);  // a real frictional problem, not an empty one
}

// On these wedges the semismooth Newton method of a Tresca problem with disks cycles (it left
// 3.8e-7 mm after 100 steps, and the reference ended max_iterations); Newton's method on
// Coulomb's law from where it stopped settles. Both Siconos solvers, from their own starts, find
// the reference's answer (measured 6.7e-8 apart); its residual is that of the problem the last
// geometric update linearised (1.7e-10 mm measured).
TEST(SiconosCrossCheck, BinderFibresPressingATowWithFriction) {
  const Exported e = cross_check(testing::binder_fibres_pressing_a_tow(), "binder");
  expect_agreement(e, 1e-6, 1e-9, 2, {"nsgs", "newton"});
  int crossings = 0;
  for (const ProblemContact& c : e.problem.contacts) crossings += c.tangents == 2 ? 1 : 0;
  EXPECT_GE(crossings, 3);
}

TEST(SiconosCrossCheck, AnAnswerSiconosCallsSolvedButIsNotIsShownAsFailed) {
  // Nonsmooth Gauss–Seidel asked by Siconos' own measure for only 1e-2 stops after a few sweeps on
  // the line of slices and returns info = 0 ("solved"); its answer's residual is percent-level.
  const double q = 1e-4, mu = 0.2;
  const Exported e =
      cross_check(testing::sheared_parallel(q, 0.5 * mu * q, mu, 20), "parallel_loose", 1e-2);
  ASSERT_TRUE(e.answers.contains("answers"));
  bool shown = false;
  for (const auto& a : e.answers["answers"]) {
    if (a["solver"] != "nsgs") continue;
    shown = true;
    EXPECT_EQ(a["info"].get<int>(), 0);
    EXPECT_TRUE(a["siconos_says_converged"].get<bool>());
    EXPECT_FALSE(a["converged"].get<bool>());
    EXPECT_GT(a["residual"]["relative"].get<double>(), 1e-6);
  }
  EXPECT_TRUE(shown);
  EXPECT_EQ(e.exit_code, 3);
  EXPECT_NE(e.printed.find("NOT converged"), std::string::npos) << e.printed;
  EXPECT_NE(e.printed.find("Siconos info 0 (it says converged)"), std::string::npos) << e.printed;
}

TEST(SiconosCrossCheck, UnreadableProblemIsRejected) {
  const std::string path = ::testing::TempDir() + "siconos_bad.problem.json";
  std::ofstream(path) << "{\"format\": \"fibrecheck-contact-problem\", \"version\": 1, \"mu\": "
                         "0.1, \"contacts\": [{\"tangents\": 3}], \"W\": {}, \"q\": []}";
  const std::string command =
      std::string("'") + FIBRECHECK_SICONOS_PROGRAM + "' -q '" + path + "' 2>/dev/null";
  const int status = std::system(command.c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2);
}

}  // namespace
}  // namespace fibrecheck
