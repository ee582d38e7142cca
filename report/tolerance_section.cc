#include "tolerance_section.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "atomic_file.h"
#include "csv_file.h"

namespace fibrecheck {

namespace {

using TimesAndErrors = std::vector<std::pair<double, double>>;

/// Per method, its converged runs with an error above zero as (time, worst error), and those on
/// its Pareto front.
struct MethodPoints {
  std::map<std::string, TimesAndErrors> all, fronts;
  std::vector<double> failed_times;   ///< runs that did not converge: no error to plot
  double exact_reference_time = NAN;  ///< a reference that is its own truth: error zero
};

MethodPoints method_points(const ToleranceStudyScene& s) {
  MethodPoints m;
  for (const TolerancePoint& p : s.points) {
    const double worst = p.errors.worst();
    if (p.method == "reference" && worst == 0.0 && p.status == "converged")
      m.exact_reference_time = p.time_s;
    if (p.status != "converged" && p.time_s > 0) m.failed_times.push_back(p.time_s);
    if (p.status == "converged" && worst > 0 && p.time_s > 0) {
      m.all[p.method].push_back({p.time_s, worst});
      if (p.pareto) m.fronts[p.method].push_back({p.time_s, worst});
    }
  }
  return m;
}

std::string rows_of(const TimesAndErrors& list) {
  std::ostringstream out;
  for (const auto& [time, error] : list) out << time << " " << error << "\n";
  return out.str();
}

/// Error against time on one scene: each method's runs as points, its front as a line.
void error_against_time_figure(ReportPage& page, const ToleranceStudyScene& s) {
  MethodPoints m = method_points(s);
  std::vector<Gnuplot::Series> series;
  std::ostringstream plot;
  plot << "set logscale xy\nset autoscale xfix\nset offsets graph 0.04, graph 0.04, 0, 0\n"
          "set xlabel 'run time (s)'\nset ylabel 'relative error (worst of "
          "deflection, force, energy)'\nset format y '10^{%L}'\nset xtics (0.001, 0.002, 0.005, "
          "0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, "
          "10000)\nset key "
          "outside top center horizontal maxrows 2\nset grid\n";
  if (std::isfinite(m.exact_reference_time))
    plot << "set arrow from " << m.exact_reference_time << ", graph 0 to " << m.exact_reference_time
         << ", graph 1 nohead dt 2 lw 2 lc rgb '#56b4e9'\nset label 'reference (exact: it is "
            "the truth)' at "
         << m.exact_reference_time << ", graph 0.05 right offset -0.5, 0\n";
  plot << "plot ";
  int k = 0, colour = 1;
  const int types[] = {7, 5, 9, 11, 13, 15};
  for (auto& [method, list] : m.all) {
    TimesAndErrors& front = m.fronts[method];
    std::sort(front.begin(), front.end());
    series.push_back({rows_of(list)});
    series.push_back({front.empty() ? "nan nan\n" : rows_of(front)});
    plot << (k ? ", " : "") << "@DATA" << k << "@ using 1:2 with points pt "
         << types[(colour - 1) % 6] << " ps 1.2 lc " << colour << " title '" << method << "', @DATA"
         << k + 1 << "@ using 1:2 with lines lw 2 lc " << colour << " notitle";
    k += 2;
    ++colour;
  }
  if (k == 0) return;
  // Runs that did not converge, at their run time along a row above every error drawn.
  double top = 0.0;
  for (const auto& [method, list] : m.all)
    for (const auto& [time, error] : list) top = std::max(top, error);
  if (!m.failed_times.empty()) {
    std::ostringstream failed;
    for (double time : m.failed_times) failed << time << " " << 3.0 * top << "\n";
    series.push_back({failed.str()});
    plot << ", @DATA" << k
         << "@ using 1:2 with points pt 2 ps 1.5 lw 2 lc rgb '#000000' title "
            "'did not converge'";
  }
  page.figure("error_vs_time_" + file_name_slug(s.scene),
              "Relative error against run time on " + s.scene +
                  ": every converged run of each update rule of the iterative method (overlap "
                  "tolerances and slice counts) and of the reference (refinements); the lines "
                  "join each method's Pareto front; the runs that did not converge as crosses at "
                  "their run time, in a row above the errors ([#tab:outcomes]).",
              plot.str(), series);
}

Table speedup_table() {
  Table t;
  t.label = "speedup";
  t.caption =
      "Speed-up of the iterative method over the implicit reference at equal error: the "
      "fastest converged run of each that reaches the error level (worst of deflection, "
      "force and energy).";
  t.header = {"Scene",         "Error level",   "Iterative rule",
              "Iterative (s)", "Reference (s)", "Speed-up"};
  return t;
}

// How each method's runs ended, per scene: a method that fails at some tolerances is a finding
// the error-against-time figure cannot show (a failed run has no error to plot).
Table outcome_table(const std::vector<ToleranceStudyScene>& studies) {
  Table t;
  t.label = "outcomes";
  t.caption =
      "How the runs of the tolerance study ended, per scene and method: runs at each tolerance "
      "(refinement for the reference) by status; the range of tolerances of the runs that did "
      "not converge.";
  t.header = {"Scene", "Method", "Runs", "Converged", "Diverged", "Other", "Not converged at"};
  for (const ToleranceStudyScene& s : studies) {
    std::vector<std::string> methods;
    for (const TolerancePoint& p : s.points)
      if (std::find(methods.begin(), methods.end(), p.method) == methods.end())
        methods.push_back(p.method);
    for (const std::string& method : methods) {
      int runs = 0, converged = 0, diverged = 0;
      double lowest = INFINITY, highest = -INFINITY;
      for (const TolerancePoint& p : s.points) {
        if (p.method != method) continue;
        ++runs;
        if (p.status == "converged") {
          ++converged;
          continue;
        }
        if (p.status == "diverged") ++diverged;
        lowest = std::min(lowest, p.parameter);
        highest = std::max(highest, p.parameter);
      }
      const std::string failed = !std::isfinite(lowest) ? "–"
                                 : lowest == highest    ? sci(lowest)
                                                        : sci(lowest) + " to " + sci(highest);
      t.rows.push_back({s.scene, method, std::to_string(runs), std::to_string(converged),
                        std::to_string(diverged), std::to_string(runs - converged - diverged),
                        failed});
    }
  }
  return t;
}

// The speed-up at equal error at the finest error level both kinds of run reached, per scene.
std::optional<std::string> speedup_finding(const std::vector<ToleranceStudyScene>& studies) {
  std::ostringstream out;
  for (const ToleranceStudyScene& s : studies) {
    const SpeedUp* finest = nullptr;
    for (const SpeedUp& u : s.speedups)
      if (std::isfinite(u.speedup()) && (!finest || u.error_level < finest->error_level))
        finest = &u;
    if (!finest) continue;
    out << (out.tellp() > 0 ? "; "
                            : "At equal error the iterative method is faster than the "
                              "reference by ")
        << seconds(finest->speedup()) << "× on " << s.scene << " (error "
        << sci(finest->error_level) << ", rule " << finest->iterative_method << ")";
  }
  if (out.tellp() == 0) return std::nullopt;
  out << " ([#tab:speedup]).";
  return out.str();
}

// The methods whose runs diverged at some tolerance, with how many of how many.
std::optional<std::string> outcome_finding(const Table& outcomes) {
  std::ostringstream out;
  for (const auto& row : outcomes.rows) {
    if (row[4] == "0") continue;
    out << (out.tellp() > 0 ? ", " : "") << row[1] << " in " << row[4] << " of " << row[2] << " on "
        << row[0];
  }
  if (out.tellp() == 0) return std::nullopt;
  return "Over the tolerances studied, runs ended diverged: " + out.str() + " ([#tab:outcomes]).";
}

}  // namespace

void write_tolerance_section(ReportPage& page, const std::vector<ToleranceStudyScene>& studies) {
  if (studies.empty()) return;
  page.section("Accuracy against run time",
               "Each update rule was run at overlap tolerances t_d over several decades, and the "
               "reference's continuous line contact at several refinements; each point is the "
               "worst of its deflection, force and energy errors against the ground truth. The "
               "speed-up at equal error compares the fastest run of each kind that reaches an "
               "error level.");
  Table t = speedup_table();
  std::vector<std::vector<std::string>> rows, points;
  for (const ToleranceStudyScene& s : studies) {
    for (const SpeedUp& u : s.speedups) {
      const double speedup = u.speedup();
      t.rows.push_back({s.scene, sci(u.error_level),
                        u.iterative_method.empty() ? "–" : u.iterative_method,
                        seconds(u.iterative_time_s), seconds(u.reference_time_s),
                        std::isfinite(speedup) ? seconds(speedup) : "not reached"});
      rows.push_back({s.scene, cell(u.error_level), cell(u.iterative_time_s),
                      cell(u.reference_time_s), cell(speedup)});
    }
    for (const TolerancePoint& p : s.points)
      points.push_back({s.scene, p.method, cell(p.parameter), cell(p.time_s), count(p.iterations),
                        p.status, cell(p.errors.worst())});
    error_against_time_figure(page, s);
  }
  page.table(t);
  page.summary().headline += "\n" + markdown(t, page.summary().tables);
  const Table outcomes = outcome_table(studies);
  page.table(outcomes);
  if (auto finding = outcome_finding(outcomes)) page.finding(*finding);
  if (auto finding = speedup_finding(studies)) page.finding(*finding);
  page.csv("speedup", {"scene", "error_level", "iterative_time_s", "reference_time_s", "speedup"},
           rows);
  page.csv("tolerance_study",
           {"scene", "method", "parameter", "time_s", "iterations", "status", "worst_error"},
           points);
}

}  // namespace fibrecheck
