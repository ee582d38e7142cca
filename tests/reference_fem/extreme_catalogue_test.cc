// The extreme catalogue (scenes/extreme/) through the reference: the status the scene expects
// (`beyond_reach`: it would need more memory than a machine has), its closed forms within their
// tolerances, finite numbers whatever the status; and where both solvers converge, the same
// deflections as the iterative solver to 1e-4 of the largest (both solve the same contact model;
// the scenes' tolerances put the iterative solver's overlaps far below that).

#include "extreme_catalogue.h"

#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include "expected_outcome.h"
#include "input_error.h"
#include "iterative_solver.h"
#include "reference_solver.h"
#include "result_difference.h"
#include "scene.h"

namespace fibrecheck {
namespace {

class ExtremeCatalogue : public ::testing::TestWithParam<std::string> {};

TEST_P(ExtremeCatalogue, ReferenceGivesTheExpectedOutcome) {
  const Scene scene = read_scene(testing::extreme_scene_path(GetParam()));
  ASSERT_TRUE(scene.expected.has_value());
  ReferenceOptions options;
  options.communicator = MPI_COMM_SELF;
  const Result r = solve_reference(scene, options);
  const OutcomeCheck check = check_outcome(*scene.expected, r, "reference");
  for (const std::string& failure : check.failures) ADD_FAILURE() << failure;
  EXPECT_EQ(testing::first_non_finite(r), "");
  if (r.status != Status::converged) return;
  const Result it = solve_iteratively(scene, SolverOptions::from_scene(scene));
  if (it.status != Status::converged) return;
  ASSERT_EQ(r.fibres.size(), it.fibres.size());
  EXPECT_LE(testing::displacement_difference(r, it), 1e-4)
      << "the solvers disagree on " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Scenes, ExtremeCatalogue,
                         ::testing::ValuesIn(testing::extreme_catalogue()),
                         testing::catalogue_test_name);

}  // namespace
}  // namespace fibrecheck

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
