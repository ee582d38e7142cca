#include "estimate_section.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "csv_file.h"

namespace fibrecheck {

namespace {

/// Effectivity indices outside this band are called out in the table.
constexpr double kLowest = 0.5, kHighest = 3.0;

/// One run's estimate and the iteration error measured for it.
struct EstimatedRun {
  std::string scene, source, method;
  double parameter = NAN;
  Errors estimate, truth;
};

/// The true error of a run is known where its effectivity index was measured (the harness keeps
/// estimate and index): their quotient; NaN where the error is within what the truth can tell.
double true_error(double estimate, double index) {
  return std::isfinite(index) && index > 0.0 ? estimate / index : NAN;
}

Errors true_errors(const Errors& estimate, const Errors& index) {
  return {true_error(estimate.deflection, index.deflection),
          true_error(estimate.force, index.force), true_error(estimate.energy, index.energy)};
}

std::vector<EstimatedRun> estimated_runs(const std::vector<StoredComparison>& comparisons,
                                         const std::vector<ToleranceStudyScene>& studies) {
  std::vector<EstimatedRun> runs;
  for (const StoredComparison& c : comparisons) {
    const ComparisonRecord& s = c.summary;
    if (s.comparable && std::isfinite(s.estimate.force))
      runs.push_back(
          {s.scene, "compare", s.rule, NAN, s.estimate, true_errors(s.estimate, s.effectivity)});
  }
  for (const ToleranceStudyScene& s : studies)
    for (const TolerancePoint& p : s.points)
      if (p.status == "converged" && std::isfinite(p.estimate.force))
        runs.push_back({s.scene, "tolerance study", p.method, p.parameter, p.estimate,
                        true_errors(p.estimate, p.effectivity)});
  return runs;
}

/// The range of the effectivity indices of one metric over runs, "min–max" (one value for one
/// run, "–" where no run has a measured index), and how many lie outside the band.
struct Range {
  double low = INFINITY, high = -INFINITY;
  int measured = 0, outside = 0;
  void add(double estimate, double truth) {
    if (!std::isfinite(truth) || !std::isfinite(estimate)) return;
    const double index = estimate / truth;
    low = std::min(low, index);
    high = std::max(high, index);
    ++measured;
    outside += index < kLowest || index > kHighest;
  }
  std::string text() const {
    if (measured == 0) return "–";
    if (measured == 1 || fixed3(low) == fixed3(high)) return fixed3(low);
    return fixed3(low) + "–" + fixed3(high);
  }
};

Table effectivity_table(const std::vector<EstimatedRun>& runs) {
  Table t;
  t.label = "effectivity";
  t.caption =
      "Effectivity of the iterative method's estimate of its own iteration error (estimate / "
      "error measured against the reference on the same slices), the range over the runs whose "
      "error is above what the reference can tell (runs: all, measured: with such an error in "
      "force), and the runs whose deflection or force index falls outside 0.5–3.";
  t.header = {"Scene",        "Runs from", "Runs",   "Measured",
              "Deflection",   "Force",     "Energy", "Largest measured force error",
              "Outside 0.5–3"};
  for (std::size_t i = 0; i < runs.size();) {
    std::size_t j = i;
    Range deflection, force, energy;
    double largest = 0.0;
    for (; j < runs.size() && runs[j].scene == runs[i].scene && runs[j].source == runs[i].source;
         ++j) {
      deflection.add(runs[j].estimate.deflection, runs[j].truth.deflection);
      force.add(runs[j].estimate.force, runs[j].truth.force);
      energy.add(runs[j].estimate.energy, runs[j].truth.energy);
      if (std::isfinite(runs[j].truth.force)) largest = std::max(largest, runs[j].truth.force);
    }
    t.rows.push_back({runs[i].scene, runs[i].source, std::to_string(j - i),
                      std::to_string(force.measured), deflection.text(), force.text(),
                      energy.text(), sci(largest),
                      std::to_string(deflection.outside + force.outside)});
    i = j;
  }
  return t;
}

/// Estimated against true error, one series per metric, with the lines of effectivity 1, 0.5 and 3.
void estimate_figure(ReportPage& page, const std::vector<EstimatedRun>& runs) {
  std::ostringstream series[3];
  int plotted = 0;
  for (const EstimatedRun& r : runs) {
    const double estimates[3] = {r.estimate.deflection, r.estimate.force, r.estimate.energy};
    const double truths[3] = {r.truth.deflection, r.truth.force, r.truth.energy};
    for (int m = 0; m < 3; ++m)
      if (std::isfinite(truths[m]) && estimates[m] > 0.0) {
        series[m] << truths[m] << " " << estimates[m] << "\n";
        ++plotted;
      }
  }
  if (plotted == 0) return;
  std::vector<Gnuplot::Series> data;
  for (auto& s : series) data.push_back({s.str().empty() ? "nan nan\n" : s.str()});
  page.figure(
      "estimate_vs_true",
      "The iterative method's estimate of its iteration error against the error measured against "
      "the reference on the same slices, every run of the comparisons and tolerance studies with "
      "an error above what the reference can tell; the solid line is a perfect estimate, the "
      "dashed lines "
      "effectivity 0.5 and 3.",
      "set logscale xy\nset xlabel 'iteration error measured (relative)'\nset ylabel 'iteration "
      "error estimated (relative)'\nset format x '10^{%L}'\nset format y '10^{%L}'\nset key top "
      "left\nset grid\nset size square\n"
      "plot x with lines lw 1 lc rgb '#000000' notitle, 0.5*x with lines dt 2 lc rgb '#666666' "
      "notitle, 3*x with lines dt 2 lc rgb '#666666' notitle, @DATA0@ using 1:2 with points pt 7 "
      "ps 1.1 lc 1 title 'deflection', @DATA1@ using 1:2 with points pt 5 ps 0.9 lc 2 title "
      "'force', @DATA2@ using 1:2 with points pt 9 ps 1.0 lc 3 title 'energy'",
      data);
}

}  // namespace

void write_estimate_section(ReportPage& page, const std::vector<StoredComparison>& comparisons,
                            const std::vector<ToleranceStudyScene>& studies) {
  const std::vector<EstimatedRun> runs = estimated_runs(comparisons, studies);
  if (runs.empty()) return;
  page.section("Error estimates",
               "Every iterative run estimates its own iteration error from its final state: the "
               "overlaps it leaves at the contacts that push are the residual of the contact "
               "problem, and one solve of the residual equation on that pushing set, with the "
               "contacts near switching checked, gives the correction to the exact answer of its "
               "sliced problem; on the deformed fibres the crossings then step to the closest "
               "points and the normals turn to the corrected fibres, and with Coulomb friction the "
               "frictions are unknowns too (Newton steps of the frictional problem). The "
               "effectivity index is that estimate over the error measured against the reference "
               "on the same slices; 1 is a perfect estimate. It is measured only where the error "
               "is more than three times the disagreement of two converged solutions (the "
               "iterative method converged far, and the reference): below that, the error is the "
               "truth's own. A run converged to round-off can still lie further from the reference "
               "than that, by what round-off in its overlaps moves the forces of an "
               "ill-conditioned line contact (about 5e-9 in force on 100 slices of two parallel "
               "fibres, whose compliance has a condition number of 5e7): no estimate from the "
               "state sees it, and such a run falls below 0.5.");
  page.table(effectivity_table(runs));
  estimate_figure(page, runs);
  std::vector<std::vector<std::string>> rows;
  for (const EstimatedRun& r : runs) {
    const char* metrics[3] = {"deflection", "force", "energy"};
    const double estimates[3] = {r.estimate.deflection, r.estimate.force, r.estimate.energy};
    const double truths[3] = {r.truth.deflection, r.truth.force, r.truth.energy};
    for (int m = 0; m < 3; ++m)
      rows.push_back({r.scene, r.source, r.method, cell(r.parameter), metrics[m],
                      cell(estimates[m]), cell(truths[m]), cell(estimates[m] / truths[m])});
  }
  page.csv(
      "effectivity",
      {"scene", "source", "method", "parameter", "metric", "estimate", "true_error", "effectivity"},
      rows);
}

}  // namespace fibrecheck
