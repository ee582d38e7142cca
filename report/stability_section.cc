#include "stability_section.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "atomic_file.h"
#include "csv_file.h"

namespace fibrecheck {

namespace {

/// The section's three tables, their rows still to come.
struct StabilityTables {
  Table steps, stiffness, catalogue;
};

StabilityTables stability_tables() {
  StabilityTables t;
  t.steps.label = "stability";
  t.steps.caption =
      "Rule seed with c as a fraction of its stable limit c_crit: how each run ended and "
      "after how many iterations (divergence is detected, not waited out).";
  t.steps.header = {"Scene", "c / c_crit", "c (N/mm)", "Status", "Criterion", "Iterations"};
  t.stiffness.label = "stiffness";
  t.stiffness.caption =
      "The Young's modulus of every second fibre multiplied by a ratio: iterations, time "
      "and the worst relative error against the reference at the same ratio, per rule.";
  t.stiffness.header = {"Scene", "Ratio", "Method", "Status", "Iterations", "Time (s)", "Error"};
  t.catalogue.label = "catalogue";
  t.catalogue.caption =
      "Stability on the extreme catalogue (scenes/extreme/): each scene run once by each solver "
      "as it stands (the iterative solver with the scene's rule, the default where it names "
      "none; the reference on the scene's slices), its status against the one the scene "
      "expects (beyond_reach: it would need more memory than the machine has), and the worst "
      "relative "
      "error against the scene's closed-form forces and deflections.";
  t.catalogue.header = {"Scene",      "Solver",   "Expected", "Status",
                        "Iterations", "Time (s)", "Error",    "As expected"};
  return t;
}

void catalogue_rows(Table& t, const StabilityStudyScene& s) {
  for (const CataloguePoint& p : s.catalogue) {
    const bool ok = p.failures.empty();
    t.rows.push_back(
        {s.scene,
         p.solver == "iterative" && !p.rule.empty() ? p.solver + " (" + p.rule + ")" : p.solver,
         p.expected_status, p.status, count(p.iterations), seconds(p.time_s), sci(p.error),
         ok ? "yes" : "no: " + p.failures});
  }
}

void stiffness_rows(Table& t, const StabilityStudyScene& s) {
  for (const StiffnessPoint& p : s.stiffness)
    t.rows.push_back({s.scene, sci(p.ratio), p.method, p.status, count(p.iterations),
                      seconds(p.time_s),
                      p.method == "reference" ? "(truth)" : sci(p.errors.worst())});
}

/// Iterations against c / c_crit: converged, diverged (where detected) and capped runs.
void step_figure(ReportPage& page, const StabilityStudyScene& s) {
  std::ostringstream converged, diverged, other;
  for (const StepPoint& p : s.steps) {
    std::ostringstream& into = p.status == "converged"  ? converged
                               : p.status == "diverged" ? diverged
                                                        : other;
    into << p.fraction << " " << std::max(1L, p.iterations) << "\n";
  }
  page.figure(
      "stability_" + file_name_slug(s.scene),
      "Iterations of the seed's rule on " + s.scene +
          " against c / c_crit: converged runs, and the iteration at which divergence "
          "was detected; c_crit = " +
          sci(s.c_crit) + " N/mm.",
      "set logscale y\nset xlabel 'c / c_{crit}'\nset ylabel 'iterations'\nset format y "
      "'10^{%L}'\nset xrange [0:*]\nset offsets 0, graph 0.05, graph 0.1, 0\nset key "
      "top center\nset grid\nset arrow from 1, graph 0 to 1, graph 1 "
      "nohead dt 2 lc rgb '#666666'\nplot @DATA0@ using 1:2 with linespoints pt 7 ps "
      "1.5 lw 2 title 'converged', @DATA1@ using 1:2 with points pt 2 ps 2 lw 3 title "
      "'diverged (iteration detected)', @DATA2@ using 1:2 with points pt 6 ps 2 title "
      "'iteration cap'",
      {{rows_or_nan(converged.str())}, {rows_or_nan(diverged.str())}, {rows_or_nan(other.str())}});
}

// Where rule seed stops converging: the smallest c/c_crit at which a run diverged, and the largest
// below it at which one converged, over the scenes studied (a run capped at a small c is slow,
// not unstable).
std::optional<std::string> stability_finding(const std::vector<StabilityStudyScene>& studies) {
  double unstable = INFINITY;
  for (const StabilityStudyScene& s : studies)
    for (const StepPoint& p : s.steps)
      if (p.status == "diverged") unstable = std::min(unstable, p.fraction);
  double stable = 0.0;
  for (const StabilityStudyScene& s : studies)
    for (const StepPoint& p : s.steps)
      if (p.status == "converged" && p.fraction < unstable) stable = std::max(stable, p.fraction);
  if (!(stable > 0.0)) return std::nullopt;
  std::ostringstream out;
  out << "The seed's force update converged up to $c = " << seconds(stable)
      << "\\,c_\\mathrm{crit}$";
  if (std::isfinite(unstable))
    out << " and diverged from $c = " << seconds(unstable) << "\\,c_\\mathrm{crit}$";
  out << " on the scenes studied ([#tab:stability]): the limit $c_\\mathrm{crit} = "
         "2/\\lambda_{\\max}$ each run estimates is the one to keep to.";
  return out.str();
}
}  // namespace

void write_stability_section(ReportPage& page, const std::vector<StabilityStudyScene>& studies) {
  if (studies.empty()) return;
  page.section(
      "Stability of the force update",
      "The seed's update $P' = P + c\\,d$ (§4.3.2) is a projected Richardson iteration on "
      "the contact compliance W; its step is c·D (c/n per slice, Eq. 4.28), stable for c "
      "below $c_\\mathrm{crit} = 2/\\lambda_{\\max}(D^{1/2}WD^{1/2})$, which every run estimates.");
  StabilityTables t = stability_tables();
  std::vector<std::vector<std::string>> rows;
  for (const StabilityStudyScene& s : studies) {
    if (!s.catalogue.empty()) {
      catalogue_rows(t.catalogue, s);
      continue;
    }
    for (const StepPoint& p : s.steps) {
      t.steps.rows.push_back(
          {s.scene, seconds(p.fraction), sci(p.c), p.status, p.criterion, count(p.iterations)});
      rows.push_back(
          {s.scene, cell(p.fraction), cell(p.c), count(p.iterations), p.status, p.criterion});
    }
    stiffness_rows(t.stiffness, s);
    step_figure(page, s);
  }
  if (!t.steps.rows.empty()) page.table(t.steps);
  if (auto finding = stability_finding(studies)) page.finding(*finding);
  if (!t.stiffness.rows.empty()) page.table(t.stiffness);
  if (!t.catalogue.rows.empty()) page.appendix_table("The extreme catalogue", t.catalogue);
  page.csv("stability", {"scene", "c_over_c_crit", "c", "iterations", "status", "criterion"}, rows);
}

}  // namespace fibrecheck
