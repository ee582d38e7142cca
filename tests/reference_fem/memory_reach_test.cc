// What the reference's contact problem would hold in memory, counted before it is assembled.

#include "memory_reach.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/SparseCore>

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

}  // namespace
}  // namespace fibrecheck
