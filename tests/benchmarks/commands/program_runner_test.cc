#include "program_runner.h"

#include <gtest/gtest.h>

namespace fibrecheck {
namespace {

// A grandchild holds 64 MB it has written (a shell variable) for a second: the resident peak
// counts it through the processes waited for, the proportional one through the process tree,
// where the grandchild's private pages count whole. Sampled, the proportional peak cannot exceed
// the resident one by more than the pages the two reckon apart (the page tables are in neither).
TEST(ProgramRunner, MeasuresThePeakMemoryOfTheWholeProcessTree) {
  const ProgramRun run = run_program(
      {"/bin/sh", "-c", "sh -c 'x=$(yes aaaaaaa | head -c 67108864); sleep 1'; exit 3"});
  EXPECT_EQ(run.exit_code, 3);
  EXPECT_GE(run.wall_time_s, 1.0);
  EXPECT_GE(run.peak_memory_mb, 64.0);
  EXPECT_GE(run.peak_proportional_memory_mb, 64.0);
  EXPECT_LE(run.peak_proportional_memory_mb, run.peak_memory_mb + 1.0);
}

TEST(ProgramRunner, SaysWhenAProgramCannotStart) {
  const ProgramRun run = run_program({"/nonexistent/program"});
  EXPECT_EQ(run.exit_code, 127);
}

}  // namespace
}  // namespace fibrecheck
