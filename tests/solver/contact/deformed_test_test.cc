// The warning a converged answer on the deformed fibres gets where it fails the seed's test.
#include "deformed_test.h"

#include <gtest/gtest.h>

namespace fibrecheck {
namespace {

Result converged(const std::string& geometry, double gap, double overlap) {
  Result r;
  r.status = Status::converged;
  r.geometry = geometry;
  r.deformed_test.gap_where_pushing = gap;
  r.deformed_test.overlap_where_free = overlap;
  return r;
}

TEST(SeedsTestWarning, OnlyAConvergedDeformedAnswerAboveTdIsWarned) {
  const double t_d = 1e-7;
  Result within = converged("deformed", 0.9e-7, 0.5e-7);
  warn_where_the_seeds_test_fails(t_d, within);
  EXPECT_TRUE(within.warnings.empty());
  for (const auto& [gap, overlap] : {std::pair{3.3e-5, 0.0}, std::pair{0.0, 7.75e-4}}) {
    Result above = converged("deformed", gap, overlap);
    warn_where_the_seeds_test_fails(t_d, above);
    ASSERT_EQ(above.warnings.size(), 1u);
    EXPECT_NE(above.warnings[0].find("seed's test"), std::string::npos);
  }
  Result linearised = converged("linearised", 3.3e-5, 0.0);
  warn_where_the_seeds_test_fails(t_d, linearised);
  EXPECT_TRUE(linearised.warnings.empty());
  Result stopped = converged("deformed", 3.3e-5, 0.0);
  stopped.status = Status::max_iterations;
  warn_where_the_seeds_test_fails(t_d, stopped);
  EXPECT_TRUE(stopped.warnings.empty());
}

}  // namespace
}  // namespace fibrecheck
