// The comparison metrics of DESIGN §6 against values worked out by hand on made-up results:
// deflection max‖Δu‖ / max‖u_truth‖, force the worst relative pair error (pairs matched whichever
// way round their fibres are listed; a pair on one side only counts with the other's force as
// zero), energy |ΔU| / U, the line distribution as the largest gap of the cumulative forces; and
// the split of a comparison: where slicing is exact (no continuous reference) it is zero.
#include "metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "comparison.h"
#include "input_error.h"

namespace fibrecheck {
namespace {

/// A contact point at `position` carrying `force` along z, all of it normal.
ContactPoint point(double position, double force) {
  ContactPoint p;
  p.position = position;
  p.force = p.normal_force = {0, 0, force};
  return p;
}

Result base() {
  Result r;
  r.scene = "made_up";
  r.status = Status::converged;
  FibreResult a, b;
  a.id = "A";
  b.id = "B";
  a.displacement = {{0, 0, 0}, {0, 0, -2e-3}, {0, 0, 0}};
  b.displacement = {{0, 0, 0}, {0, 1e-3, 0}, {0, 0, 0}};
  r.fibres = {a, b};
  ContactResult line;
  line.fibres = {"A", "B"};
  line.kind = "line";
  line.points = {point(0.25, 1e-4), point(0.75, 1e-4)};
  line.total_force = 2e-4;
  ContactResult wall;
  wall.fibres = {"A", "floor"};
  wall.kind = "wall";
  wall.points = {point(0.5, 5e-5)};
  wall.total_force = 5e-5;
  r.contacts = {line, wall};
  r.strain_energy_exact = 4e-8;
  return r;
}

TEST(Metrics, AgainstHandComputedValues) {
  const Result truth = base();
  Result run = base();
  run.fibres[0].displacement[1] = {0, 3e-4, -2e-3};  // ‖Δu‖ = 3e-4 at the largest ‖u‖ = 2e-3
  run.contacts[0].fibres = {"B", "A"};               // the same pair, listed the other way
  run.contacts[0].points = {point(0.25, 1.5e-4), point(0.75, 0.6e-4)};
  run.contacts[0].total_force = 2.1e-4;  // 5 % high
  run.contacts[1].total_force = 4e-5;    // 20 % low
  run.strain_energy_exact = 4.4e-8;      // 10 % high
  const ErrorReport r = measure_errors(run, truth, "test");
  EXPECT_NEAR(r.errors.deflection, 3e-4 / 2e-3, 1e-12);
  EXPECT_NEAR(r.errors.force, 0.2, 1e-12);
  EXPECT_NEAR(r.errors.energy, 0.1, 1e-12);
  EXPECT_NEAR(r.errors.worst(), 0.2, 1e-12);
  ASSERT_EQ(r.pairs.size(), 2u);
  EXPECT_NEAR(r.pairs[0].error, 0.05, 1e-12);
  // Cumulative forces: run 1.5e-4 then 2.1e-4, truth 1e-4 then 2e-4; the largest gap is at s =
  // 0.25, 0.5e-4, over the truth's total 2e-4.
  EXPECT_NEAR(r.pairs[0].distribution_error, 0.25, 1e-12);
  // The wall pair: one point each at s = 0.5 with the same force: no difference in the shape.
  EXPECT_NEAR(r.pairs[1].distribution_error, 0.0, 1e-12);
}

TEST(Metrics, APairOnOneSideOnlyIsAWholeError) {
  const Result truth = base();
  Result run = base();
  run.contacts.pop_back();  // the wall contact missed
  EXPECT_NEAR(measure_errors(run, truth, "test").errors.force, 1.0, 1e-12);
  EXPECT_EQ(measure_errors(truth, truth, "test").errors.worst(), 0.0);
}

TEST(Metrics, ResultsOfDifferentScenesAreBadInput) {
  Result other = base();
  other.fibres[1].id = "C";
  EXPECT_THROW(measure_errors(other, base(), "test"), InputError);
  other = base();
  other.fibres[0].displacement.pop_back();
  EXPECT_THROW(measure_errors(other, base(), "test"), InputError);
}

TEST(Metrics, ObservedOrderOfAPowerLaw) {
  std::vector<double> n = {2, 4, 8, 16}, e;
  for (double x : n) e.push_back(3.0 * std::pow(x, -2.0));
  EXPECT_NEAR(observed_order(n, e), 2.0, 1e-12);
  EXPECT_TRUE(std::isnan(observed_order({4}, {0.1})));
}

// The split: user = truth + 1 % force; the reference on slices equals the continuous one, so the
// whole error is iteration error and the slicing error is zero; without a continuous reference
// (point contacts) the truth is the sliced reference and the slicing error is zero too.
TEST(Comparison, ErrorSplitsIntoIterationAndSlicing) {
  const Result truth = base();
  Result user = base();
  user.contacts[0].total_force *= 1.01;
  const Comparison with = compare_results("made_up", user, truth, truth, truth);
  ASSERT_TRUE(with.comparable) << with.reason;
  EXPECT_NEAR(with.total.errors.force, 0.01, 1e-12);
  EXPECT_NEAR(with.iteration.errors.force, 0.01, 1e-12);
  EXPECT_EQ(with.slicing.errors.worst(), 0.0);
  EXPECT_EQ(with.agreement.errors.worst(), 0.0);
  const Comparison without = compare_results("made_up", user, truth, truth, std::nullopt);
  EXPECT_NEAR(without.total.errors.force, 0.01, 1e-12);
  EXPECT_EQ(without.slicing.errors.worst(), 0.0);
  // A sliced reference 2 % off the continuous one is the slicing error.
  Result sliced = base();
  sliced.contacts[0].total_force *= 0.98;
  const Comparison split = compare_results("made_up", user, sliced, sliced, truth);
  EXPECT_NEAR(split.slicing.errors.force, 0.02, 1e-12);
  EXPECT_NEAR(split.total.errors.force, 0.01, 1e-12);
  // The truth's extrapolated force, where it has one, is what the user's run is measured against.
  Result extrapolated = truth;
  extrapolated.contacts[0].extrapolated_force = 2.1e-4;
  EXPECT_NEAR(compare_results("made_up", user, truth, truth, extrapolated).total.pairs[0].error,
              std::fabs(2.02e-4 - 2.1e-4) / 2.1e-4, 1e-12);
}

// The effectivity index is measured only above what the truth can tell: three times the
// agreement of two converged solutions, never below 1e-10; below it, NaN.
TEST(Effectivity, IsMeasuredOnlyAboveWhatTheTruthCanTell) {
  const Errors floor = measurable_above({1e-9, 0.0, 2e-12});
  EXPECT_DOUBLE_EQ(floor.deflection, 3e-9);
  EXPECT_DOUBLE_EQ(floor.force, 1e-10);
  EXPECT_DOUBLE_EQ(floor.energy, 1e-10);
  const Errors index = effectivity({2e-9, 4e-6, 1e-9}, {2.5e-9, 2e-6, 5e-9}, floor);
  EXPECT_TRUE(std::isnan(index.deflection));  // 2.5e-9 is within 3e-9
  EXPECT_DOUBLE_EQ(index.force, 2.0);
  EXPECT_DOUBLE_EQ(index.energy, 0.2);
}

}  // namespace
}  // namespace fibrecheck
