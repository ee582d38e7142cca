#include "slice_section.h"

#include <sstream>

#include "atomic_file.h"
#include "csv_file.h"

namespace fibrecheck {

namespace {

std::string describe_truth(double estimate) {
  if (!(estimate >= 0.0)) return "exact for its slices (point contacts only, or no line contact)";
  return "its extrapolated line force within an estimated " + sci(estimate) + " (relative)";
}

/// The scene's part of the table's caption: rule, tolerance, ground truth, observed orders.
std::string caption_of(const SliceStudyScene& s) {
  std::ostringstream caption;
  caption << " " << s.scene << ": rule " << s.rule << ", t_d = " << sci(s.tolerance)
          << " mm, ground truth " << describe_truth(s.truth_error_estimate) << "; observed order "
          << seconds(s.order.deflection) << " (deflection), " << seconds(s.order.force)
          << " (force), " << seconds(s.order.energy) << " (energy).";
  return caption.str();
}

/// Rows "n error" of the points whose error is above zero (a logarithmic axis).
std::string error_rows(const SliceStudyScene& s, double Errors::*error) {
  std::ostringstream out;
  for (const SliceStudyPoint& p : s.points)
    if (p.errors.*error > 0) out << static_cast<double>(p.slices) << " " << p.errors.*error << "\n";
  return out.str();
}

void error_figure(ReportPage& page, const SliceStudyScene& s) {
  page.figure("slices_" + file_name_slug(s.scene),
              "Relative error of the iterative method on " + s.scene +
                  " against the continuous reference, per slice count n (rule " + s.rule +
                  "), with the observed orders of convergence.",
              "set logscale xy\nset autoscale xfix\nset offsets graph 0.04, graph 0.04, 0, 0\n"
              "set xtics (1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096)\n"
              "set xlabel 'slices n'\nset ylabel 'relative error'\nset format "
              "y '10^{%L}'\nset key top right\nset grid\nplot @DATA0@ using 1:2 with "
              "linespoints pt 7 lw 2 title 'deflection, order " +
                  seconds(s.order.deflection) +
                  "', @DATA1@ using 1:2 with linespoints pt 5 lw 2 title 'force, order " +
                  seconds(s.order.force) +
                  "', @DATA2@ using 1:2 with linespoints pt 9 lw 2 "
                  "title 'energy, order " +
                  seconds(s.order.energy) + "'",
              {{error_rows(s, &Errors::deflection)},
               {error_rows(s, &Errors::force)},
               {error_rows(s, &Errors::energy)}});
}

}  // namespace

void write_slice_section(ReportPage& page, const std::vector<SliceStudyScene>& studies) {
  if (studies.empty()) return;
  page.section("Accuracy against the number of slices",
               "A line contact between nearly parallel fibres is approximated by n cross-section "
               "slices (Figures 4.11–4.12, Eq. 4.28). Each scene was solved by the iterative "
               "method with its own rule and tolerance at each n and measured against the "
               "continuous reference; the observed order p fits error ∝ n^−p.");
  Table t;
  t.label = "slice_study";
  t.caption =
      "Relative error of the iterative method against the continuous reference, and its "
      "run time, per slice count.";
  t.header = {"Scene", "Slices", "Deflection", "Force", "Energy", "Iterations", "Time (s)"};
  std::vector<std::vector<std::string>> rows;
  for (const SliceStudyScene& s : studies) {
    t.caption += caption_of(s);
    for (const SliceStudyPoint& p : s.points) {
      t.rows.push_back({s.scene, std::to_string(p.slices), sci(p.errors.deflection),
                        sci(p.errors.force), sci(p.errors.energy), count(p.iterations),
                        seconds(p.time_s)});
      rows.push_back({s.scene, std::to_string(p.slices), cell(p.time_s), cell(p.errors.deflection),
                      cell(p.errors.force), cell(p.errors.energy)});
    }
    error_figure(page, s);
  }
  page.table(t);
  page.csv(
      "slice_study",
      {"scene", "slices", "iterative_time_s", "deflection_error", "force_error", "energy_error"},
      rows);
}

}  // namespace fibrecheck
