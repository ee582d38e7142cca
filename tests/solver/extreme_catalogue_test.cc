// The extreme catalogue (scenes/extreme/) through the iterative solver with each scene's own
// settings (the default rule where the scene names none): the status the scene expects, its
// closed-form forces and deflections within their stated tolerances, and never a non-finite
// number in the result, whatever the status.

#include "extreme_catalogue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "expected_outcome.h"
#include "iterative_solver.h"
#include "scene.h"

namespace fibrecheck {
namespace {

class ExtremeCatalogue : public ::testing::TestWithParam<std::string> {};

TEST_P(ExtremeCatalogue, IterativeSolverGivesTheExpectedOutcome) {
  const Scene scene = read_scene(testing::extreme_scene_path(GetParam()));
  ASSERT_TRUE(scene.expected.has_value()) << "a catalogue scene says what it expects";
  const Result r = solve_iteratively(scene, SolverOptions::from_scene(scene));
  const OutcomeCheck check = check_outcome(*scene.expected, r, "iterative");
  for (const std::string& failure : check.failures) ADD_FAILURE() << failure;
  EXPECT_EQ(testing::first_non_finite(r), "");
  // Numerical trouble is reported, not waited out: a diverging run stops long before the cap.
  if (r.status == Status::diverged) {
    EXPECT_LT(r.iterations, 1000) << r.message;
  }
}

// The same scene on the deformed fibres, whatever contact model it names: the status it expects,
// no non-finite number, and a converged answer that passes the seed's own test (gaps at pushing
// contacts and overlaps elsewhere within 1e-3 of the smallest radius, where t_d allows).
TEST_P(ExtremeCatalogue, DeformedContactKeepsTheExpectedStatus) {
  Scene scene = read_scene(testing::extreme_scene_path(GetParam()));
  scene.contact.geometry = ContactGeometryModel::deformed;
  const Result r = solve_iteratively(scene, SolverOptions::from_scene(scene));
  EXPECT_EQ(to_string(r.status), expected_status(*scene.expected, "iterative")) << r.message;
  EXPECT_EQ(testing::first_non_finite(r), "");
  if (r.status != Status::converged) return;
  double smallest = INFINITY;
  for (const FibreSpec& f : scene.fibres) smallest = std::min(smallest, f.radius);
  const double bound = std::max(1e-3 * smallest, 2.0 * scene.overlap_tolerance());
  EXPECT_LE(r.deformed_test.gap_where_pushing, bound);
  EXPECT_LE(r.deformed_test.overlap_where_free, bound);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ExtremeCatalogue,
                         ::testing::ValuesIn(testing::extreme_catalogue()),
                         testing::catalogue_test_name);

}  // namespace
}  // namespace fibrecheck
