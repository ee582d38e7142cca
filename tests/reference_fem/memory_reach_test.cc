// What the reference would hold in memory — its contact problem and its finite elements — counted
// before either is made.

#include "memory_reach.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/SparseCore>
#include <string>

#include "reference_solver.h"

namespace fibrecheck {
namespace {

TEST(MemoryReach, CountsTheSquareOfTheContactsOnEveryFibre) {
  // Two fibres, 3 and 5 stations, 4 and 6 contacts on them; with friction 12 and 6 components.
  const double entry = sizeof(Eigen::Triplet<double>) + sizeof(double) + sizeof(int);
  const MemoryNeed frictionless = contact_problem_memory({3, 5}, {4, 6}, {});
  EXPECT_DOUBLE_EQ(frictionless.influence, 2 * 8.0 * (9 + 25));
  EXPECT_DOUBLE_EQ(frictionless.compliance, entry * (16 + 36));
  const MemoryNeed frictional = contact_problem_memory({3, 5}, {4, 6}, {12, 6});
  EXPECT_DOUBLE_EQ(frictional.influence, frictionless.influence);
  EXPECT_DOUBLE_EQ(frictional.compliance, entry * (16 + 36 + 144 + 36));
  EXPECT_DOUBLE_EQ(frictional.total(), frictional.influence + frictional.compliance);
}

TEST(MemoryReach, WithinReachIsPartOfTheMachine) {
  const double physical =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  const double reach = memory_within_reach(MPI_COMM_SELF);
  EXPECT_GT(reach, 0.0);
  EXPECT_LE(reach, 0.9 * physical);
}

TEST(MemoryReach, SaysWhatItWouldNeedAgainstWhatThereIs) {
  const MemoryNeed need{2.0 * (1 << 30), 6.0 * (1 << 30)};
  const std::string message = beyond_reach_message(need, 4.0 * (1 << 30), "A", 1000);
  for (const char* part : {"8 GiB", "influence matrices 2 GiB", "compliance matrix 6 GiB",
                           "fibre A", "1000 contact stations", "4 GiB", "--slices"})
    EXPECT_NE(message.find(part), std::string::npos) << part << " not in: " << message;
  // Frictionless, the saddle points could hold it: the message says how.
  EXPECT_EQ(message.find("--contact-assembly saddle_point"), std::string::npos);
  const std::string frictionless = beyond_reach_message(need, 4.0 * (1 << 30), "A", 1000, true);
  EXPECT_NE(frictionless.find("--contact-assembly saddle_point"), std::string::npos)
      << frictionless;
}

// Finite elements beyond the machine: the 100 000-slice parallel fibres with elements 64 times
// finer than the slices would take 2 × 6.4 million elements, about 100 million unknowns and some
// 70 GB. The reference says so before it meshes anything (no unknowns), rather than exhausting
// the machine in Gmsh or MUMPS.
TEST(MemoryReach, FiniteElementsBeyondTheMachineAreNotMeshed) {
  const double unknowns = 2 * 8 * 6.4e6;
  if (finite_element_memory(unknowns) <= memory_within_reach(MPI_COMM_SELF))
    GTEST_SKIP() << "this machine would hold these finite elements";
  const Scene scene =
      read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/extreme/parallel_100000_slices.json");
  ReferenceOptions options;
  options.refine = 6;
  const Result r = solve_reference(scene, options);
  EXPECT_EQ(r.status, Status::beyond_reach) << r.message;
  EXPECT_NE(r.message.find("finite elements"), std::string::npos) << r.message;
  ASSERT_TRUE(r.finite_elements.has_value());
  EXPECT_EQ(r.finite_elements->unknowns, 0);
}

}  // namespace
}  // namespace fibrecheck
