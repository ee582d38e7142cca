#include "comparison_section.h"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <sstream>

#include "atomic_file.h"
#include "cross_section_figure.h"
#include "csv_file.h"

namespace fibrecheck {

namespace {

/// The table of every comparison, and the comparable ones' rows for data/comparison.csv.
Table comparison_table(const std::vector<StoredComparison>& comparisons,
                       std::vector<std::vector<std::string>>& rows) {
  Table t;
  t.label = "comparison";
  t.caption =
      "Relative error of the iterative method as each scene specifies it against the ground "
      "truth, and its split into iteration (stopping criterion) and slicing (slice approximation) "
      "errors, each the worst of deflection, force and energy; the geometry part, the "
      "linearised contact against the contact on the deformed fibres on the same slices (what "
      "the small-deflection contact costs on the scene: part of the error where the scene asks "
      "for it); run times of the user's run and of the ground truth.";
  t.header = {"Scene",     "Rule",    "Deflection", "Force",         "Energy",
              "Iteration", "Slicing", "Geometry",   "Iterative (s)", "Reference (s)"};
  for (const StoredComparison& c : comparisons) {
    const ComparisonRecord& s = c.summary;
    const double user_time = s.user().wall_time_s;
    const double truth_time = s.truth() ? s.truth()->wall_time_s : NAN;
    if (!s.comparable) {
      t.rows.push_back({s.scene, s.rule, "not comparable", s.reason, "", "", "", "",
                        seconds(user_time), seconds(truth_time)});
      continue;
    }
    t.rows.push_back({s.scene, s.rule, sci(s.total.deflection), sci(s.total.force),
                      sci(s.total.energy), sci(s.iteration.worst()), sci(s.slicing.worst()),
                      sci(s.geometry.worst()), seconds(user_time), seconds(truth_time)});
    rows.push_back({s.scene, s.rule, cell(s.total.deflection), cell(s.total.force),
                    cell(s.total.energy), cell(s.iteration.worst()), cell(s.slicing.worst()),
                    cell(s.geometry.worst()), cell(user_time), cell(truth_time)});
  }
  return t;
}

// The worst force error of the runs as the scenes specify them, and which part of the split
// makes most of it.
std::optional<std::string> accuracy_finding(const std::vector<StoredComparison>& comparisons) {
  const ComparisonRecord* worst = nullptr;
  int compared = 0;
  for (const StoredComparison& c : comparisons) {
    if (!c.summary.comparable || !std::isfinite(c.summary.total.force)) continue;
    ++compared;
    if (!worst || c.summary.total.force > worst->total.force) worst = &c.summary;
  }
  if (!worst) return std::nullopt;
  const double iteration = worst->iteration.force, slicing = worst->slicing.force;
  std::ostringstream out;
  out << "On " << compared << (compared == 1 ? " scene" : " scenes")
      << " run as specified, the iterative method's force "
      << "error against the ground truth is at most " << sci(worst->total.force) << " ("
      << worst->scene << ", [#tab:comparison]), mostly from its "
      << (slicing > iteration ? "slices" : "stopping criterion") << " (slicing " << sci(slicing)
      << ", iteration " << sci(iteration) << ").";
  return out.str();
}

constexpr std::size_t kShortestHistory = 10;

/// The user's run's largest overlap and strain energy at each recorded iteration.
void history_figure(ReportPage& page, const StoredComparison& c) {
  const std::string& scene = c.summary.scene;
  std::ostringstream overlap, energy;
  for (const HistoryEntry& h : c.user.history) {
    if (h.max_overlap > 0.0) overlap << h.iteration << " " << h.max_overlap << "\n";
    if (std::isfinite(h.strain_energy)) energy << h.iteration << " " << h.strain_energy << "\n";
  }
  // A run of a few iterations has no history worth a figure.
  if (c.user.history.size() < kShortestHistory || overlap.str().empty()) return;
  page.figure(
      "history_" + file_name_slug(scene),
      "Convergence of the iterative method on " + scene + " (rule " + c.user.rule +
          "): the largest overlap (left, logarithmic) and the strain energy by the trapezium "
          "rule, Eq. 4.34 (right), at each recorded iteration.",
      "set logscale x\nset logscale y\nset autoscale xfix\nset offsets graph 0.02, graph 0.02, 0, "
      "0\nset xlabel 'iteration'\nset ylabel 'largest overlap "
      "(mm)'\nset y2label 'strain energy (N mm)'\nset y2tics\nset ytics nomirror\nset format y "
      "'10^{%L}'\nset key outside top center horizontal\nset grid\nplot @DATA0@ using 1:2 with "
      "linespoints pt 7 "
      "ps 0.5 lw 2 title 'largest overlap', @DATA1@ using 1:2 axes x1y2 with lines lw 2 dt 2 "
      "title 'strain energy'",
      {{overlap.str()}, {energy.str()}});
}

/// The fibre the ground truth deflects most (its index), or none when nothing moved.
std::optional<std::size_t> most_deflected_fibre(const Result& truth) {
  std::size_t fibre = 0;
  double largest = -1.0;
  for (std::size_t f = 0; f < truth.fibres.size(); ++f)
    for (const Eigen::Vector3d& u : truth.fibres[f].displacement)
      if (u.norm() > largest) largest = u.norm(), fibre = f;
  if (!(largest > 0.0)) return std::nullopt;
  return fibre;
}

/// A fibre's deflection (µm) along `direction` against s = x / L, as rows "s deflection".
std::string deflection_rows(const FibreResult& f, const Eigen::Vector3d& direction) {
  std::ostringstream out;
  const std::size_t n = f.displacement.size();
  for (std::size_t j = 0; j < n; ++j)
    out << (n > 1 ? double(j) / (n - 1) : 0.0) << " " << 1e3 * f.displacement[j].dot(direction)
        << "\n";
  return out.str();
}

/// The most deflected fibre along its largest displacement, from both solvers.
void deflection_figure(ReportPage& page, const StoredComparison& c) {
  const std::optional<std::size_t> fibre = most_deflected_fibre(c.truth);
  if (!fibre || *fibre >= c.user.fibres.size()) return;
  const FibreResult& truth = c.truth.fibres[*fibre];
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& u : truth.displacement)
    if (u.norm() > direction.norm()) direction = u;
  direction.normalize();
  const std::string& scene = c.summary.scene;
  page.figure(
      "deflection_" + file_name_slug(scene),
      "Deflection of fibre " + truth.id + " of " + scene +
          " (the most deflected) along its largest displacement, from the iterative "
          "method (rule " +
          c.user.rule + ") and the reference.",
      "set xlabel 'position along the fibre, s = x / L'\nset ylabel 'deflection "
      "(µm)'\nset key bottom center\nset grid\nplot @DATA0@ using 1:2 with lines lw "
      "4 lc rgb '#888888' title 'reference (ground truth)', @DATA1@ using 1:2 with "
      "lines lw 2 dt 2 lc rgb '#c00000' title 'iterative, rule " +
          c.user.rule + "'",
      {{deflection_rows(truth, direction)}, {deflection_rows(c.user.fibres[*fibre], direction)}});
}

// The error split as bars per scene (log scale): what stopping, slicing and the small-deflection
// contact each contribute, so that a reader sees at once which to spend effort on.
void error_split_figure(ReportPage& page, const std::vector<StoredComparison>& comparisons) {
  std::ostringstream rows;
  int scenes = 0;
  // A part below 1e-16 (or missing) is drawn at the axis's floor: exact to round-off.
  auto bar = [](double e) { return std::isfinite(e) && e > 1e-16 ? e : 1e-16; };
  for (const StoredComparison& c : comparisons) {
    const ComparisonRecord& s = c.summary;
    if (!s.comparable) continue;
    rows << '"' << s.scene << "\" " << bar(s.iteration.worst()) << " " << bar(s.slicing.worst())
         << " " << bar(s.geometry.worst()) << "\n";
    ++scenes;
  }
  if (scenes < 2) return;
  page.figure(
      "error_split",
      "The error of each scene's run split into its causes (the worst of deflection, force and "
      "energy): the stopping criterion (iteration), the slices (slicing) and the linearised "
      "against the deformed contact (geometry, on the same slices); bars at the floor are exact "
      "to round-off or not measured ([#tab:comparison]).",
      "set style data histograms\nset style histogram clustered gap 1\nset style fill solid "
      "0.8 border -1\nset logscale y\nset xrange [-0.6:" +
          std::to_string(scenes) +
          " - 0.4]\nset yrange [1e-16:*]\nset format y '10^{%L}'\nset "
          "ylabel 'relative error'\nset xtics rotate by -30 noenhanced\nset key outside top center "
          "horizontal\nset grid "
          "y\nplot @DATA0@ using 2:xtic(1) title 'iteration' lc rgb '#3060c0', '' using 3 title "
          "'slicing' lc rgb '#e0a000', '' using 4 title 'geometry' lc rgb '#a02080'",
      {{rows.str()}});
}

}  // namespace

void write_comparison_section(ReportPage& page, const std::vector<StoredComparison>& comparisons) {
  if (comparisons.empty()) return;
  page.section("Accuracy on each scene",
               "Each scene was solved by the iterative method as the scene specifies it (rule, "
               "tolerance, slices), by the same method converged to 1e-4 of the scene's "
               "tolerance, by the reference on the same slices, and by the reference with "
               "continuous line contact. The error of the user's run is split into the stopping "
               "criterion's part (against the reference on the same slices) and the slices' "
               "part (the reference on slices against the continuous one); beside them the "
               "geometry part (the reference linearised against the reference on the deformed "
               "fibres, same slices).");
  std::vector<std::vector<std::string>> rows;
  const Table t = comparison_table(comparisons, rows);
  page.table(t);
  if (auto finding = accuracy_finding(comparisons)) page.finding(*finding);
  error_split_figure(page, comparisons);
  page.summary().headline += markdown(t, 1);
  page.csv("comparison",
           {"scene", "rule", "deflection_error", "force_error", "energy_error", "iteration_error",
            "slicing_error", "geometry_error", "iterative_time_s", "reference_time_s"},
           rows);
  for (const StoredComparison& c : comparisons) {
    if (!c.has_results) continue;
    if (c.scene)
      draw_cross_section(page, "cross_section_" + file_name_slug(c.summary.scene),
                         "A cross-section of " + c.summary.scene +
                             " after the iterative method (rule " + c.user.rule + ")",
                         *c.scene, c.user);
    history_figure(page, c);
    deflection_figure(page, c);
  }
}

}  // namespace fibrecheck
