// Stopping and divergence criteria (seed §4.3.6). Test problems: hand-made contact lists and
// residual/energy sequences. Known answers, from the definitions (thresholds from convergence.cc):
//  - residuals: overlap = max(0, max d); max_overlap = max d over all candidates (negative when
//    all are apart, 0 for none); gap_force = max(0, max −d over contacts with P > 0);
//  - energy window (n_i, t_U): settled on a push when n_i + 1 energies have been pushed (the
//    current one and the n_i before it) and every one is within t_U of the current (|ΔU| ≤ t_U);
//    never with t_U ≤ 0; an outlier keeps it unsettled until it has left the window, n_i + 1
//    pushes later;
//  - divergence monitor (tolerance t): the first residual r₀ sets the reference max(r₀, t);
//    growth when a residual exceeds 1e4 times it, or exceeds the scene's extent (its longest
//    fibre) and 100 times the very first residual, whatever the resets; stalled when the best
//    residual is more than max(5000, iteration/5) iterations old; reset() starts again from the
//    next residual.
#include "convergence.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fibrecheck {
namespace {

Contact with(double overlap, double force) {
  Contact c;
  c.overlap = overlap;
  c.force = force;
  return c;
}

using Verdict = DivergenceMonitor::Verdict;

TEST(Residuals, OverlapAndGapForceAreMeasuredSeparately) {
  // Largest overlap 3e-6 (a contact without force); the largest gap under force is 5e-7 (a larger
  // gap, 1e-3, carries no force and does not count).
  const Residuals r = measure_residuals(
      {with(-1e-3, 0.0), with(3e-6, 0.0), with(-5e-7, 2e-4), with(1e-6, 1e-4), with(-2e-7, 1e-9)});
  EXPECT_EQ(r.max_overlap, 3e-6);
  EXPECT_EQ(r.overlap, 3e-6);
  EXPECT_EQ(r.gap_force, 5e-7);
  EXPECT_EQ(r.total(), 3e-6);
}

TEST(Residuals, AllApartGivesANegativeMaxOverlapAndNoOverlap) {
  const Residuals r = measure_residuals({with(-4e-3, 0.0), with(-2e-3, 0.0)});
  EXPECT_EQ(r.max_overlap, -2e-3);
  EXPECT_EQ(r.overlap, 0.0);
  EXPECT_EQ(r.gap_force, 0.0);
  EXPECT_EQ(r.total(), 0.0);
  // A gap carrying force dominates the total when nothing overlaps.
  const Residuals g = measure_residuals({with(-4e-3, 0.0), with(-2e-3, 1e-5)});
  EXPECT_EQ(g.gap_force, 2e-3);
  EXPECT_EQ(g.total(), 2e-3);
}

TEST(Residuals, TouchingAndForcesAtTheEdge) {
  // Exactly touching with force: no residual. Zero force is no force; an overlap under force is
  // no gap.
  const Residuals touching =
      measure_residuals({with(0.0, 1e-4), with(-1e-3, 0.0), with(2e-9, 5.0)});
  EXPECT_EQ(touching.gap_force, 0.0);
  EXPECT_EQ(touching.max_overlap, 2e-9);
  EXPECT_EQ(touching.overlap, 2e-9);
  // The smallest positive force counts.
  EXPECT_EQ(measure_residuals({with(-1e-3, 1e-300)}).gap_force, 1e-3);
  // No contacts at all.
  const Residuals none = measure_residuals({});
  EXPECT_EQ(none.max_overlap, 0.0);
  EXPECT_EQ(none.overlap, 0.0);
  EXPECT_EQ(none.gap_force, 0.0);
}

TEST(Residuals, ManyContactsGiveTheSameAnswerAsFew) {
  // Above 4096 contacts the reduction may run in parallel: the answer must not change.
  std::vector<Contact> contacts;
  for (int k = 0; k < 10000; ++k)
    contacts.push_back(with(-1e-3 + 1e-7 * (k % 997), k % 3 == 0 ? 1e-4 : 0.0));
  contacts[7777] = with(4e-6, 0.0);
  contacts[8001] = with(-2e-3, 1e-5);
  const Residuals r = measure_residuals(contacts);
  EXPECT_EQ(r.max_overlap, 4e-6);
  EXPECT_EQ(r.gap_force, 2e-3);
}

TEST(Residuals, NonFiniteOverlapsAreNotHidden) {
  // The solver stops with `non_finite` when the residual is not finite; a NaN overlap must
  // therefore reach the residual rather than be skipped by max(). (Today a NaN overlap also
  // makes the exact energy NaN, which the solver checks as well.)
  std::vector<Contact> contacts = {with(NAN, 1e-4), with(NAN, 0.0)};
  EXPECT_FALSE(std::isfinite(measure_residuals(contacts).total()));
  contacts.push_back(with(1e-3, 0.0));
  EXPECT_FALSE(std::isfinite(measure_residuals(contacts).total()));
}

TEST(EnergyWindow, SettlesOnlyWhenTheWindowIsFullAndWithinTolerance) {
  // n_i = 3, t_U = 0.5: four equal energies are needed; the fourth push settles.
  EnergyWindow window(3, 0.5);
  EXPECT_FALSE(window.push(1.0));
  EXPECT_FALSE(window.push(1.0));
  EXPECT_FALSE(window.push(1.0));
  EXPECT_TRUE(window.push(1.0));
  EXPECT_TRUE(window.push(1.0));
}

TEST(EnergyWindow, ToleranceIsInclusiveAndMeasuredFromTheCurrentEnergy) {
  // Binary-exact numbers: |1.5 − 1| = 0.5 exactly is within t_U = 0.5.
  {
    EnergyWindow window(2, 0.5);
    window.push(1.5);
    window.push(1.25);
    EXPECT_TRUE(window.push(1.0));
  }
  // 1.5 + 2⁻⁵⁰ is just outside.
  {
    EnergyWindow window(2, 0.5);
    window.push(1.5 + std::ldexp(1.0, -50));
    window.push(1.25);
    EXPECT_FALSE(window.push(1.0));
  }
  // All within t_U of each neighbour but not of the current one: a drift is not settled.
  {
    EnergyWindow window(3, 0.5);
    window.push(0.0);
    window.push(0.375);
    window.push(0.75);
    EXPECT_FALSE(window.push(1.125));
  }
  // Energies far from zero: only differences count.
  {
    EnergyWindow window(2, 1e-9);
    window.push(1e6);
    window.push(1e6);
    EXPECT_TRUE(window.push(1e6));
  }
}

TEST(EnergyWindow, ASingleOutlierResetsIt) {
  EnergyWindow window(3, 0.1);
  for (int i = 0; i < 4; ++i) window.push(2.0);
  EXPECT_TRUE(window.push(2.0));
  EXPECT_FALSE(window.push(5.0));  // the outlier itself
  // While the outlier is among the last four energies nothing settles…
  EXPECT_FALSE(window.push(2.0));
  EXPECT_FALSE(window.push(2.0));
  EXPECT_FALSE(window.push(2.0));
  // …and once it has left the window it does.
  EXPECT_TRUE(window.push(2.0));
}

TEST(EnergyWindow, ZeroToleranceIsOff) {
  EnergyWindow off(2, 0.0);
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(off.push(1.0));
  EnergyWindow negative(2, -1.0);
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(negative.push(1.0));
  // A window of one: the previous energy and the current one.
  EnergyWindow one(1, 0.1);
  EXPECT_FALSE(one.push(1.0));
  EXPECT_TRUE(one.push(1.05));
}

TEST(EnergyWindow, NonFiniteEnergiesNeverSettle) {
  // A NaN or infinite energy is not "within t_U" of anything. (The solver checks the exact energy
  // for non-finite values before it pushes, so this does not reach a result today.)
  EnergyWindow window(2, 0.5);
  window.push(1.0);
  window.push(1.0);
  EXPECT_FALSE(window.push(NAN));
  EnergyWindow nans(2, 0.5);
  nans.push(NAN);
  nans.push(NAN);
  EXPECT_FALSE(nans.push(NAN));
  EnergyWindow inf(2, 0.5);
  inf.push(INFINITY);
  inf.push(INFINITY);
  EXPECT_FALSE(inf.push(INFINITY));  // ∞ − ∞ is NaN
  // One NaN among finite energies is an outlier like any other.
  EnergyWindow mixed(2, 0.5);
  mixed.push(1.0);
  mixed.push(NAN);
  EXPECT_FALSE(mixed.push(1.0));
}

TEST(DivergenceMonitor, GeometricGrowthIsGrowthOnceItPassesTenThousandTimesTheStart) {
  // r_k = 2^k from r₀ = 1: 2¹³ = 8192 ≤ 1e4 is fine, 2¹⁴ = 16384 > 1e4 is growth.
  DivergenceMonitor monitor(1e-7);
  for (int k = 0; k <= 13; ++k)
    EXPECT_EQ(monitor.observe(k + 1, std::ldexp(1.0, k)), Verdict::fine) << k;
  EXPECT_EQ(monitor.observe(15, std::ldexp(1.0, 14)), Verdict::growth);
}

TEST(DivergenceMonitor, GrowthThresholdIsStrictAndStartsFromTheTolerance) {
  {
    DivergenceMonitor monitor(1e-7);
    monitor.observe(1, 0.5);
    EXPECT_EQ(monitor.observe(2, 0.5e4), Verdict::fine);  // exactly 1e4 × r₀
    EXPECT_EQ(monitor.observe(3, std::nextafter(0.5e4, INFINITY)), Verdict::growth);
  }
  // Starting at zero residual (everything just touching) the reference is the tolerance.
  {
    DivergenceMonitor monitor(1e-6);
    EXPECT_EQ(monitor.observe(1, 0.0), Verdict::fine);
    EXPECT_EQ(monitor.observe(2, 0.9e-2), Verdict::fine);
    EXPECT_EQ(monitor.observe(3, 1.1e-2), Verdict::growth);
  }
  // An infinite residual is growth.
  {
    DivergenceMonitor monitor(1e-6);
    monitor.observe(1, 1.0);
    EXPECT_EQ(monitor.observe(2, INFINITY), Verdict::growth);
  }
}

// Fibres flying apart: a residual beyond the scene's extent is growth long before 1e4 times a
// large first overlap, but never within a hundred times the first residual.
TEST(DivergenceMonitor, GrowthBeyondTheSceneIsGrowth) {
  {
    DivergenceMonitor monitor(1e-7, 1.0);  // fibres 1 mm long
    monitor.observe(1, 6e-3);              // a compacted tow's first overlaps
    EXPECT_EQ(monitor.observe(2, 0.6), Verdict::fine);
    EXPECT_EQ(monitor.observe(3, 1.0), Verdict::fine);  // exactly the extent
    EXPECT_EQ(monitor.observe(4, std::nextafter(1.0, INFINITY)), Verdict::growth);
  }
  {
    DivergenceMonitor monitor(1e-7, 1.0);
    monitor.observe(1, 0.05);  // a first residual the extent does not dwarf: 100 times it
    EXPECT_EQ(monitor.observe(2, 5.0), Verdict::fine);
    EXPECT_EQ(monitor.observe(3, 5.5), Verdict::growth);
  }
  {
    DivergenceMonitor monitor(1e-7, 1e4);  // an extent beyond 1e4 times the start changes nothing
    monitor.observe(1, 1e-3);
    EXPECT_EQ(monitor.observe(2, 10.0), Verdict::fine);
    EXPECT_EQ(monitor.observe(3, 10.5), Verdict::growth);
  }
  {
    // A reset (each linearised problem of the deformed contact is judged on its own) starts the
    // 1e4 afresh, not the extent: the residual cannot creep past the fibres' length in steps.
    DivergenceMonitor monitor(1e-7, 1.0);
    monitor.observe(1, 6e-3);
    EXPECT_EQ(monitor.observe(2, 0.9), Verdict::fine);
    monitor.reset();
    EXPECT_EQ(monitor.observe(3, 0.95), Verdict::fine);
    EXPECT_EQ(monitor.observe(4, 1.5), Verdict::growth);
    monitor.reset();
    EXPECT_EQ(monitor.observe(5, 1.5), Verdict::growth);
  }
}

TEST(DivergenceMonitor, ATightToleranceDoesNotMakeAStartFromTouchingGrowth) {
  // t_d = 1e-11 mm on fibres 1 mm long: a step that starts just touching (1e-12 mm) and pushes
  // its overlaps to 1e-5 mm on the way is judged against 1e-8 of the extent, not against t_d;
  // above 1e4 times that, 1e-4 mm, is growth.
  DivergenceMonitor monitor(1e-11, 1.0);
  monitor.observe(1, 1e-12);
  EXPECT_EQ(monitor.observe(2, 1e-5), Verdict::fine);
  EXPECT_EQ(monitor.observe(3, 1e-4), Verdict::fine);
  EXPECT_EQ(monitor.observe(4, std::nextafter(1e-4, INFINITY)), Verdict::growth);
  DivergenceMonitor without_extent(1e-11);  // no extent given: t_d alone, as before
  without_extent.observe(1, 1e-12);
  EXPECT_EQ(without_extent.observe(2, 2e-7), Verdict::growth);
}

TEST(DivergenceMonitor, BoundedOscillationIsStalledAfterFiveThousandIterations) {
  // Alternating 1, 2, 1, 2, … from iteration 0: the best (1) is never beaten; at iteration 5000
  // it is exactly 5000 old (fine), at 5001 more (stalled).
  DivergenceMonitor monitor(1e-7);
  for (long i = 0; i <= 5000; ++i)
    ASSERT_EQ(monitor.observe(i, i % 2 ? 2.0 : 1.0), Verdict::fine) << i;
  EXPECT_EQ(monitor.observe(5001, 2.0), Verdict::stalled);
}

TEST(DivergenceMonitor, EqualResidualsAreNoProgress) {
  // A constant residual never beats the best strictly: stalled as well.
  DivergenceMonitor monitor(1e-7);
  Verdict last = Verdict::fine;
  long when = -1;
  for (long i = 1; i <= 10000 && last == Verdict::fine; ++i) {
    last = monitor.observe(i, 3e-5);
    when = i;
  }
  EXPECT_EQ(last, Verdict::stalled);
  EXPECT_EQ(when, 5002);  // best at 1, 5002 − 1 > 5000
}

TEST(DivergenceMonitor, PatienceGrowsToAFifthOfTheIterationCount) {
  // Best at iteration 100 000: patience max(5000, i/5) = i/5, stalled once i − 100 000 > i/5,
  // i.e. from i = 125 001 on (125 000: 25 000 > 25 000 is false).
  DivergenceMonitor monitor(1e-7);
  EXPECT_EQ(monitor.observe(100000, 1.0), Verdict::fine);
  EXPECT_EQ(monitor.observe(110000, 1.5), Verdict::fine);
  EXPECT_EQ(monitor.observe(125000, 1.5), Verdict::fine);
  EXPECT_EQ(monitor.observe(125001, 1.5), Verdict::stalled);
}

TEST(DivergenceMonitor, DecreasingResidualStaysFine) {
  // Slowly decreasing (each a new best), even with bounded wiggles and for 30 000 iterations.
  DivergenceMonitor monitor(1e-7);
  for (long i = 1; i <= 30000; ++i) {
    const double r = 1.0 / i * (i % 2 ? 1.0 : 1.0 + 0.5 / i);
    ASSERT_EQ(monitor.observe(i, r), Verdict::fine) << i;
  }
  // A new best within the patience restarts the count.
  DivergenceMonitor slow(1e-7);
  slow.observe(0, 1.0);
  for (long i = 1; i <= 20000; ++i)
    ASSERT_EQ(slow.observe(i, i % 4000 == 0 ? 1.0 - 1e-6 * i : 1.0), Verdict::fine) << i;
}

TEST(DivergenceMonitor, ResetStartsAgainFromTheNextResidual) {
  DivergenceMonitor monitor(1e-7);
  monitor.observe(1, 1e-3);
  // After a reset the reference is the next residual: 1.0, so 5e3 is no growth …
  monitor.reset();
  EXPECT_EQ(monitor.observe(2, 1.0), Verdict::fine);
  EXPECT_EQ(monitor.observe(3, 5e3), Verdict::fine);
  // … while without a reset it would have been (5e3 > 1e4 · 1e-3).
  DivergenceMonitor kept(1e-7);
  kept.observe(1, 1e-3);
  kept.observe(2, 1.0);
  EXPECT_EQ(kept.observe(3, 5e3), Verdict::growth);
  // The stall count restarts too: best at 1, reset at 5000, fine until 5000 + 5000.
  DivergenceMonitor stalled(1e-7);
  stalled.observe(1, 1.0);
  for (long i = 2; i < 5000; ++i) stalled.observe(i, 2.0);
  stalled.reset();
  for (long i = 5000; i <= 10000; ++i) ASSERT_EQ(stalled.observe(i, 2.0), Verdict::fine) << i;
  EXPECT_EQ(stalled.observe(10001, 2.0), Verdict::stalled);
}

}  // namespace
}  // namespace fibrecheck
