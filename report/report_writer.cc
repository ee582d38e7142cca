#include "report_writer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "atomic_file.h"
#include "csv_file.h"
#include "gnuplot.h"
#include "input_error.h"
#include "load_path.h"
#include "tables.h"

namespace fibrecheck {

namespace {

using nlohmann::json;

double number(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

/// The worst of the three errors of DESIGN §6 stored in `j`.
double worst_error(const json& j) {
  return std::max(
      {number(j, "deflection_error"), number(j, "force_error"), number(j, "energy_error")});
}

std::string csv_cell(double x) {
  if (!std::isfinite(x)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", x);
  return text;
}

/// A scene name for file names.
std::string slug(const std::string& name) {
  return file_name_slug(name);
}

struct FigureEntry {
  std::string name, caption;
};

/// The report being assembled: its Markdown body, the LaTeX body, the numbered items.
class Report {
 public:
  explicit Report(const std::string& folder)
      : folder_(folder), gnuplot_((folder_ / "figures").string()) {
    std::filesystem::create_directories(folder_ / "tables");
    std::filesystem::create_directories(folder_ / "figures");
    std::filesystem::create_directories(folder_ / "data");
  }

  void section(const std::string& title, const std::string& text) {
    md_ << "\n## " << title << "\n\n" << text << "\n";
    tex_ << "\n\\section{" << latex_escape(title) << "}\n" << latex_escape(text) << "\n";
  }

  void table(const Table& t) {
    ++summary_.tables;
    md_ << "\n" << markdown(t, summary_.tables) << "\n";
    write_file_atomically((folder_ / "tables" / (t.label + ".tex")).string(), latex(t));
    tex_ << "\n\\input{tables/" << t.label << ".tex}\n";
  }

  void figure(const std::string& name, const std::string& caption, const std::string& body,
              const std::vector<Gnuplot::Series>& series) {
    std::string why;
    if (!gnuplot_.plot(name, body, series, &why)) {
      summary_.missing.push_back(name + ": " + why);
      return;
    }
    ++summary_.figures;
    md_ << "\n![Figure " << summary_.figures << "](figures/" << name << ".png)\n\n**Figure "
        << summary_.figures << ".** " << caption << "\n";
    tex_ << "\n\\begin{figure}[htbp]\n  \\centering\n  "
            "\\includegraphics[width=0.85\\linewidth]{figures/"
         << name << ".png}\n  \\caption{" << latex_escape(caption) << "}\n  \\label{fig:" << name
         << "}\n\\end{figure}\n";
  }

  void csv(const std::string& name, const std::vector<std::string>& header,
           const std::vector<std::vector<std::string>>& rows) {
    write_csv((folder_ / "data" / (name + ".csv")).string(), header, rows);
  }

  ReportSummary finish(const std::vector<std::string>& sources) {
    std::ostringstream md;
    md << "# fibrecheck: the iterative fibre-contact method, checked\n\n"
       << "Errors are relative and the worst over the scene (DESIGN §6): deflection, max over "
          "fibres and samples of ‖u − u_truth‖ / max‖u_truth‖; force, max over contact pairs of "
          "the relative error of the total force; energy, of ½ΣP·v. The ground truth is the "
          "implicit finite-element reference with continuous line contact (on slices where a "
          "scene has only point contacts).\n"
       << md_.str() << "\n---\nData read: " << sources.size() << " files; "
       << "tables in `tables/`, figures in `figures/` (their gnuplot scripts in `figures/src/`), "
          "the numbers in `data/`.\n";
    if (!summary_.missing.empty()) {
      md << "\nFigures not drawn:\n";
      for (const std::string& m : summary_.missing) md << "- " << m << "\n";
    }
    write_file_atomically((folder_ / "report.md").string(), md.str());
    std::ostringstream tex;
    tex << "\\documentclass[a4paper,11pt]{article}\n\\usepackage[T1]{fontenc}\n"
           "\\usepackage{booktabs}\n\\usepackage{graphicx}\n\\usepackage[margin=2.2cm]{geometry}\n"
           "\\title{fibrecheck: the iterative fibre-contact method, checked}\n\\date{}\n"
           "\\begin{document}\n\\maketitle\n"
        << tex_.str() << "\n\\end{document}\n";
    write_file_atomically((folder_ / "report.tex").string(), tex.str());
    return summary_;
  }

  ReportSummary& summary() { return summary_; }

 private:
  std::filesystem::path folder_;
  Gnuplot gnuplot_;
  std::ostringstream md_, tex_;
  ReportSummary summary_;
};

std::string describe_truth(double estimate) {
  if (!(estimate >= 0.0)) return "exact for its slices (point contacts only, or no line contact)";
  return "its extrapolated line force within an estimated " + sci(estimate) + " (relative)";
}

void cross_section(Report& report, const StoredComparison& c, const Scene& scene);

void comparisons(Report& report, const ReportData& data) {
  if (data.comparisons.empty()) return;
  report.section("Accuracy on each scene",
                 "Each scene was solved by the iterative method as the scene specifies it (rule, "
                 "tolerance, slices), by the same method converged to 1e-4 of the scene's "
                 "tolerance, by the reference on the same slices, and by the reference with "
                 "continuous line contact. The error of the user's run is split into the stopping "
                 "criterion's part (against the reference on the same slices) and the slices' "
                 "part (the reference on slices against the continuous one).");
  Table t;
  t.label = "comparison";
  t.caption =
      "Relative error of the iterative method as each scene specifies it against the ground "
      "truth, and its split into iteration (stopping criterion) and slicing (slice approximation) "
      "errors, each the worst of deflection, force and energy; run times of the user's run and "
      "of the ground truth.";
  t.header = {"Scene",     "Rule",    "Deflection",    "Force",        "Energy",
              "Iteration", "Slicing", "Iterative (s)", "Reference (s)"};
  std::vector<std::vector<std::string>> rows;
  for (const StoredComparison& c : data.comparisons) {
    const json& s = c.summary;
    const std::string scene = s["scene"];
    const std::string rule = s.value("rule", "");
    const json& runs = s["runs"];
    const std::string truth = s.value("ground_truth", "reference_slices");
    const double user_time = number(runs["user"], "wall_time_s");
    const double truth_time = runs.contains(truth) ? number(runs[truth], "wall_time_s") : NAN;
    if (!s.value("comparable", false)) {
      t.rows.push_back({scene, rule, "not comparable", s.value("not_comparable", ""), "", "", "",
                        seconds(user_time), seconds(truth_time)});
      continue;
    }
    auto worst = [&](const char* key) { return worst_error(s[key]); };
    t.rows.push_back({scene, rule, sci(number(s, "deflection_error")),
                      sci(number(s, "force_error")), sci(number(s, "energy_error")),
                      sci(worst("iteration_error")), sci(worst("slicing_error")),
                      seconds(user_time), seconds(truth_time)});
    rows.push_back({scene, rule, csv_cell(number(s, "deflection_error")),
                    csv_cell(number(s, "force_error")), csv_cell(number(s, "energy_error")),
                    csv_cell(worst("iteration_error")), csv_cell(worst("slicing_error")),
                    csv_cell(user_time), csv_cell(truth_time)});
  }
  report.table(t);
  std::ostringstream headline;
  headline << markdown(t, 1);
  report.summary().headline += headline.str();
  report.csv("comparison",
             {"scene", "rule", "deflection_error", "force_error", "energy_error", "iteration_error",
              "slicing_error", "iterative_time_s", "reference_time_s"},
             rows);

  for (const StoredComparison& c : data.comparisons) {
    if (!c.has_results) continue;
    const std::string scene = c.summary["scene"];
    const std::string name = slug(scene);
    if (c.scene) cross_section(report, c, *c.scene);
    // Convergence history of the user's run.
    std::ostringstream overlap, energy;
    for (const HistoryEntry& h : c.user.history) {
      if (h.max_overlap > 0.0) overlap << h.iteration << " " << h.max_overlap << "\n";
      if (std::isfinite(h.strain_energy)) energy << h.iteration << " " << h.strain_energy << "\n";
    }
    if (c.user.history.size() >= 2 && !overlap.str().empty()) {
      report.figure(
          "history_" + name,
          "Convergence of the iterative method on " + scene + " (rule " + c.user.rule +
              "): the largest overlap (left, logarithmic) and the strain energy by the trapezium "
              "rule, Eq. 4.34 (right), at each recorded iteration.",
          "set logscale x\nset logscale y\nset xlabel 'iteration'\nset ylabel 'largest overlap "
          "(mm)'\nset y2label 'strain energy (N mm)'\nset y2tics\nset ytics nomirror\nset format y "
          "'10^{%L}'\nset key center right\nset grid\nplot @DATA0@ using 1:2 with linespoints pt 7 "
          "ps 0.5 lw 2 title 'largest overlap', @DATA1@ using 1:2 axes x1y2 with lines lw 2 dt 2 "
          "title 'strain energy'",
          {{overlap.str()}, {energy.str()}});
    }
    // The most deflected fibre, both solvers.
    std::size_t fibre = 0;
    double largest = -1.0;
    for (std::size_t f = 0; f < c.truth.fibres.size(); ++f)
      for (const Eigen::Vector3d& u : c.truth.fibres[f].displacement)
        if (u.norm() > largest) largest = u.norm(), fibre = f;
    if (largest > 0.0 && fibre < c.user.fibres.size()) {
      const FibreResult& truth = c.truth.fibres[fibre];
      Eigen::Vector3d direction = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& u : truth.displacement)
        if (u.norm() > direction.norm()) direction = u;
      direction.normalize();
      auto series = [&](const FibreResult& f) {
        std::ostringstream out;
        const std::size_t n = f.displacement.size();
        for (std::size_t j = 0; j < n; ++j)
          out << (n > 1 ? double(j) / (n - 1) : 0.0) << " "
              << 1e3 * f.displacement[j].dot(direction) << "\n";
        return out.str();
      };
      report.figure("deflection_" + name,
                    "Deflection of fibre " + truth.id + " of " + scene +
                        " (the most deflected) along its largest displacement, from the iterative "
                        "method (rule " +
                        c.user.rule + ") and the reference.",
                    "set xlabel 'position along the fibre, s = x / L'\nset ylabel 'deflection "
                    "(µm)'\nset key bottom center\nset grid\nplot @DATA0@ using 1:2 with lines lw "
                    "4 lc rgb '#888888' title 'reference (ground truth)', @DATA1@ using 1:2 with "
                    "lines lw 2 dt 2 lc rgb '#c00000' title 'iterative, rule " +
                        c.user.rule + "'",
                    {{series(truth)}, {series(c.user.fibres[fibre])}});
    }
  }
}

/// A cross-section of a tow like the seed's Figure 4.14: the fibres cut by the slice at mid-length
/// as circles of their radius at their deformed centres, the rim coloured by the bending moment
/// there, and the contact forces of that slice as lines from each contact point (normal forces,
/// scaled so that the largest is one radius long).
void draw_cross_section(Report& report, const std::string& name, const std::string& what,
                        const Scene& scene, const Result& result) {
  const Eigen::Vector3d axis = scene.contact.axis.normalized();
  int k = 0;
  axis.cwiseAbs().maxCoeff(&k);
  Eigen::Vector3d g1 = Eigen::Vector3d::Unit((k + 1) % 3);
  g1 = (g1 - g1.dot(axis) * axis).normalized();
  const Eigen::Vector3d g2 = axis.cross(g1);
  const double cos_parallel = std::cos(scene.contact.parallel_angle_deg * M_PI / 180.0);
  std::ostringstream circles, normal_forces, friction_forces;
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < result.fibres.size(); ++i) index[result.fibres[i].id] = i;
  int drawn = 0;
  double largest_force = 0.0, radius = INFINITY, largest_radius = 0.0, largest_friction = 0.0;
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const FibreSpec& f : scene.fibres) {
    const Eigen::Vector3d t = (f.end - f.start).normalized();
    if (std::fabs(t.dot(axis)) < cos_parallel || !index.count(f.id)) continue;
    const FibreResult& r = result.fibres[index[f.id]];
    if (r.displacement.empty()) continue;
    const std::size_t j = (r.displacement.size() - 1) / 2;
    const double s = r.displacement.size() > 1 ? double(j) / (r.displacement.size() - 1) : 0.0;
    const Eigen::Vector3d x = f.start + s * (f.end - f.start) + r.displacement[j];
    const double M = j < r.moment.size() ? r.moment[j].norm() : 0.0;
    circles << x.dot(g1) << " " << x.dot(g2) << " " << f.radius << " " << M << "\n";
    lo = lo.cwiseMin(Eigen::Vector2d(x.dot(g1) - f.radius, x.dot(g2) - f.radius));
    hi = hi.cwiseMax(Eigen::Vector2d(x.dot(g1) + f.radius, x.dot(g2) + f.radius));
    radius = std::min(radius, f.radius);
    largest_radius = std::max(largest_radius, f.radius);
    ++drawn;
  }
  if (drawn < 3) return;
  // The contact points nearest the middle slice, one per pair.
  std::vector<const ContactPoint*> points;
  for (const ContactResult& pair : result.contacts) {
    if (pair.kind == "point" || pair.points.empty()) continue;
    const ContactPoint* nearest = &pair.points.front();
    for (const ContactPoint& p : pair.points)
      if (std::fabs(p.position - 0.5) < std::fabs(nearest->position - 0.5)) nearest = &p;
    if (std::fabs(nearest->position - 0.5) > 0.05) continue;
    points.push_back(nearest);
    largest_force = std::max(largest_force, nearest->force.norm());
    largest_friction = std::max(largest_friction, nearest->friction_force.norm());
  }
  for (const ContactPoint* p : points) {
    // The force on fibres[0] and its reaction, each from the contact point: the normal part, and
    // the friction force in red on its own scale (it is at most mu times the normal force).
    const Eigen::Vector3d n = p->normal_force / largest_force * radius;
    const Eigen::Vector3d f = largest_friction > 0.0
                                  ? Eigen::Vector3d(p->friction_force / largest_friction * radius)
                                  : Eigen::Vector3d::Zero();
    for (double sign : {1.0, -1.0}) {
      normal_forces << p->point.dot(g1) << " " << p->point.dot(g2) << " " << sign * n.dot(g1) << " "
                    << sign * n.dot(g2) << "\n";
      if (f.norm() > 0.0)
        friction_forces << p->point.dot(g1) << " " << p->point.dot(g2) << " " << sign * f.dot(g1)
                        << " " << sign * f.dot(g2) << "\n";
    }
  }
  std::ostringstream walls;
  for (const WallSpec& w : scene.walls) {
    // A wall seen edge-on in the section: a line through its point along its in-plane direction,
    // clipped to the picture.
    const Eigen::Vector2d n(w.normal.dot(g1), w.normal.dot(g2));
    if (n.norm() < 1e-9) continue;
    const Eigen::Vector2d p(w.point.dot(g1), w.point.dot(g2)), d(-n.y(), n.x());
    const double far = 10.0 * (hi - lo).norm();
    walls << (p - far * d).x() << " " << (p - far * d).y() << "\n"
          << (p + far * d).x() << " " << (p + far * d).y() << "\n\n";
  }
  const Eigen::Vector2d pad = Eigen::Vector2d::Constant(0.3 * largest_radius);
  lo -= pad;
  hi += pad;
  const std::string ranges = "set xrange [" + std::to_string(lo.x()) + ":" +
                             std::to_string(hi.x()) + "]\nset yrange [" + std::to_string(lo.y()) +
                             ":" + std::to_string(hi.y()) + "]\n";
  report.figure(
      name,
      what +
          ", drawn like the seed's Figure 4.14: the fibres at their deformed centres at "
          "mid-length, the rim coloured by the bending moment |M| there, the walls in grey, and "
          "the contact forces of that slice as lines from each contact point: normal parts in "
          "orange (the largest, " +
          sci(largest_force) +
          " N, one radius long), friction forces in red on their own scale (the largest, " +
          sci(largest_friction) + " N, one radius long).",
      "set size ratio -1\n" + ranges +
          "set xlabel 'cross-section axis 1 (mm)'\nset ylabel 'cross-section axis 2 (mm)'\nset "
          "cblabel '|M| (N mm)'\nset cbrange [0:*]\nset rmargin 14\nset palette defined (0 '#2040c0', "
          "0.5 '#20b040', 1 '#e02020')\nset key off\nset grid\nset format cb '%.1e'\nset clip "
          "two\nplot @DATA0@ using 1:2:3:4 with circles lc palette lw 3 fs empty, @DATA1@ using "
          "1:2:3:4 with vectors nohead lw 3 lc rgb '#e0a000', @DATA2@ using 1:2:3:4 with vectors "
          "nohead lw 3 lc rgb '#e00000', @DATA3@ using 1:2 with lines lw 2 lc rgb '#606060'",
      {{circles.str()},
       {normal_forces.str().empty() ? "nan nan nan nan\n" : normal_forces.str()},
       {friction_forces.str().empty() ? "nan nan nan nan\n" : friction_forces.str()},
       {walls.str().empty() ? "nan nan\n" : walls.str()}});
}

void cross_section(Report& report, const StoredComparison& c, const Scene& scene) {
  const std::string scene_name = c.summary["scene"];
  draw_cross_section(
      report, "cross_section_" + slug(scene_name),
      "A cross-section of " + scene_name + " after the iterative method (rule " + c.user.rule + ")",
      scene, c.user);
}

void slice_studies(Report& report, const ReportData& data) {
  if (data.slice_studies.empty()) return;
  report.section("Accuracy against the number of slices",
                 "A line contact between nearly parallel fibres is approximated by n cross-section "
                 "slices (Figures 4.11–4.12, Eq. 4.28). Each scene was solved by the iterative "
                 "method with its own rule and tolerance at each n and measured against the "
                 "continuous reference; the observed order p fits error ∝ n^−p.");
  Table t;
  t.label = "slice_study";
  std::vector<std::vector<std::string>> rows;
  std::ostringstream caption;
  caption << "Relative error of the iterative method against the continuous reference, and its "
             "run time, per slice count.";
  t.header = {"Scene", "Slices", "Deflection", "Force", "Energy", "Iterations", "Time (s)"};
  for (const json& s : data.slice_studies) {
    const std::string scene = s["scene"];
    caption << " " << scene << ": rule " << s.value("rule", "")
            << ", t_d = " << sci(number(s, "overlap_tolerance")) << " mm, ground truth "
            << describe_truth(number(s, "truth_error_estimate")) << "; observed order "
            << (s["order"]["deflection_error"].is_number()
                    ? seconds(s["order"]["deflection_error"].get<double>())
                    : "–")
            << " (deflection), "
            << (s["order"]["force_error"].is_number()
                    ? seconds(s["order"]["force_error"].get<double>())
                    : "–")
            << " (force), "
            << (s["order"]["energy_error"].is_number()
                    ? seconds(s["order"]["energy_error"].get<double>())
                    : "–")
            << " (energy).";
    std::ostringstream d, f, e;
    for (const json& p : s["points"]) {
      const double n = number(p, "slices");
      t.rows.push_back({scene, std::to_string(static_cast<int>(n)),
                        sci(number(p, "deflection_error")), sci(number(p, "force_error")),
                        sci(number(p, "energy_error")), std::to_string(p.value("iterations", 0L)),
                        seconds(number(p, "iterative_time_s"))});
      rows.push_back({scene, std::to_string(static_cast<int>(n)),
                      csv_cell(number(p, "iterative_time_s")),
                      csv_cell(number(p, "deflection_error")), csv_cell(number(p, "force_error")),
                      csv_cell(number(p, "energy_error"))});
      if (number(p, "deflection_error") > 0) d << n << " " << number(p, "deflection_error") << "\n";
      if (number(p, "force_error") > 0) f << n << " " << number(p, "force_error") << "\n";
      if (number(p, "energy_error") > 0) e << n << " " << number(p, "energy_error") << "\n";
    }
    auto order = [&](const char* key) {
      return s["order"][key].is_number() ? seconds(s["order"][key].get<double>())
                                         : std::string("–");
    };
    report.figure("slices_" + slug(scene),
                  "Relative error of the iterative method on " + scene +
                      " against the continuous reference, per slice count n (rule " +
                      s.value("rule", "") + "), with the observed orders of convergence.",
                  "set logscale xy\nset xlabel 'slices n'\nset ylabel 'relative error'\nset format "
                  "y '10^{%L}'\nset key top right\nset grid\nplot @DATA0@ using 1:2 with "
                  "linespoints pt 7 lw 2 title 'deflection, order " +
                      order("deflection_error") +
                      "', @DATA1@ using 1:2 with linespoints pt 5 lw 2 title 'force, order " +
                      order("force_error") +
                      "', @DATA2@ using 1:2 with linespoints pt 9 lw 2 "
                      "title 'energy, order " +
                      order("energy_error") + "'",
                  {{d.str()}, {f.str()}, {e.str()}});
  }
  t.caption = caption.str();
  report.table(t);
  report.csv(
      "slice_study",
      {"scene", "slices", "iterative_time_s", "deflection_error", "force_error", "energy_error"},
      rows);
}

void tolerance_studies(Report& report, const ReportData& data) {
  if (data.tolerance_studies.empty()) return;
  report.section("Accuracy against run time",
                 "Each update rule was run at overlap tolerances t_d over several decades, and the "
                 "reference's continuous line contact at several refinements; each point is the "
                 "worst of its deflection, force and energy errors against the ground truth. The "
                 "speed-up at equal error compares the fastest run of each kind that reaches an "
                 "error level.");
  Table t;
  t.label = "speedup";
  t.caption =
      "Speed-up of the iterative method over the implicit reference at equal error: the "
      "fastest converged run of each that reaches the error level (worst of deflection, "
      "force and energy).";
  t.header = {"Scene",         "Error level",   "Iterative rule",
              "Iterative (s)", "Reference (s)", "Speed-up"};
  std::vector<std::vector<std::string>> rows, points;
  for (const json& s : data.tolerance_studies) {
    const std::string scene = s["scene"];
    for (const json& u : s["speedups"]) {
      t.rows.push_back(
          {scene, sci(number(u, "error_level")),
           u.value("iterative_method", "–").empty() ? "–" : u.value("iterative_method", "–"),
           seconds(number(u, "iterative_time_s")), seconds(number(u, "reference_time_s")),
           std::isfinite(number(u, "speedup")) ? seconds(number(u, "speedup")) : "not reached"});
      rows.push_back({scene, csv_cell(number(u, "error_level")),
                      csv_cell(number(u, "iterative_time_s")),
                      csv_cell(number(u, "reference_time_s")), csv_cell(number(u, "speedup"))});
    }
    // Per method, every converged point, and its Pareto front (the runs no faster run beats).
    std::map<std::string, std::vector<std::pair<double, double>>> methods, fronts;
    double exact_reference_time = NAN;  // a reference that is its own truth: error zero
    for (const json& p : s["points"]) {
      const double worst = worst_error(p);
      points.push_back({scene, p.value("method", ""), csv_cell(number(p, "parameter")),
                        csv_cell(number(p, "time_s")), std::to_string(p.value("iterations", 0L)),
                        p.value("status", ""), csv_cell(worst)});
      if (p.value("method", "") == "reference" && worst == 0.0 &&
          p.value("status", "") == "converged")
        exact_reference_time = number(p, "time_s");
      if (p.value("status", "") == "converged" && worst > 0 && number(p, "time_s") > 0) {
        methods[p.value("method", "")].push_back({number(p, "time_s"), worst});
        if (p.value("pareto", false))
          fronts[p.value("method", "")].push_back({number(p, "time_s"), worst});
      }
    }
    std::vector<Gnuplot::Series> series;
    std::ostringstream plot;
    plot << "set logscale xy\nset xlabel 'run time (s)'\nset ylabel 'relative error (worst of "
            "deflection, force, energy)'\nset format y '10^{%L}'\nset format x '10^{%L}'\nset key "
            "outside right top\nset grid\n";
    if (std::isfinite(exact_reference_time))
      plot << "set arrow from " << exact_reference_time << ", graph 0 to " << exact_reference_time
           << ", graph 1 nohead dt 2 lw 2 lc rgb '#56b4e9'\nset label 'reference (exact: it is "
              "the truth)' at "
           << exact_reference_time << ", graph 0.95 right offset -0.5, 0\n";
    plot << "plot ";
    int k = 0, colour = 1;
    const int types[] = {7, 5, 9, 11, 13, 15};
    for (auto& [method, list] : methods) {
      auto& front = fronts[method];
      std::sort(front.begin(), front.end());
      std::ostringstream all, best;
      for (const auto& [time, error] : list) all << time << " " << error << "\n";
      for (const auto& [time, error] : front) best << time << " " << error << "\n";
      series.push_back({all.str()});
      series.push_back({best.str().empty() ? "nan nan\n" : best.str()});
      plot << (k ? ", " : "") << "@DATA" << k << "@ using 1:2 with points pt "
           << types[(colour - 1) % 6] << " ps 1.2 lc " << colour << " title '" << method
           << "', @DATA" << k + 1 << "@ using 1:2 with lines lw 2 lc " << colour << " notitle";
      k += 2;
      ++colour;
    }
    if (k > 0)
      report.figure(
          "error_vs_time_" + slug(scene),
          "Relative error against run time on " + scene +
              ": every converged run of each update rule of the iterative method (overlap "
              "tolerances and slice counts) and of the reference (refinements); the lines "
              "join each method's Pareto front.",
          plot.str(), series);
  }
  report.table(t);
  report.summary().headline += "\n" + markdown(t, report.summary().tables);
  report.csv("speedup", {"scene", "error_level", "iterative_time_s", "reference_time_s", "speedup"},
             rows);
  report.csv("tolerance_study",
             {"scene", "method", "parameter", "time_s", "iterations", "status", "worst_error"},
             points);
}

void stability_studies(Report& report, const ReportData& data) {
  if (data.stability_studies.empty()) return;
  report.section(
      "Stability of the force update",
      "The seed's update P' = P + c·d (§4.3.2) is a projected Richardson iteration on "
      "the contact compliance W; its step is c·D (c/n per slice, Eq. 4.28), stable for c "
      "below c_crit = 2/λmax(D½WD½), which every run estimates.");
  Table t;
  t.label = "stability";
  t.caption =
      "Rule seed with c as a fraction of its stable limit c_crit: how each run ended and "
      "after how many iterations (divergence is detected, not waited out).";
  t.header = {"Scene", "c / c_crit", "c (N/mm)", "Status", "Criterion", "Iterations"};
  Table stiff;
  stiff.label = "stiffness";
  stiff.caption =
      "The Young's modulus of every second fibre multiplied by a ratio: iterations, time "
      "and the worst relative error against the reference at the same ratio, per rule.";
  stiff.header = {"Scene", "Ratio", "Method", "Status", "Iterations", "Time (s)", "Error"};
  Table catalogue;
  catalogue.label = "catalogue";
  catalogue.caption =
      "Stability on the extreme catalogue (scenes/extreme/): each scene run once by each solver "
      "as it stands (the iterative solver with the scene's rule, the default where it names "
      "none; the reference on the scene's slices), its status against the one the scene "
      "expects (refused: beyond the solver's reach, said as bad input), and the worst relative "
      "error against the scene's closed-form forces and deflections.";
  catalogue.header = {"Scene",      "Solver",   "Expected", "Status",
                      "Iterations", "Time (s)", "Error",    "As expected"};
  std::vector<std::vector<std::string>> rows;
  for (const json& s : data.stability_studies) {
    const std::string scene = s["scene"];
    if (s.contains("catalogue")) {
      for (const json& p : s["catalogue"]) {
        const std::string solver = p.value("solver", "");
        const std::string rule = p.value("rule", "");
        const bool ok = p.value("failures", "").empty();
        catalogue.rows.push_back(
            {scene, solver == "iterative" && !rule.empty() ? solver + " (" + rule + ")" : solver,
             p.value("expected_status", ""), p.value("status", ""),
             std::to_string(p.value("iterations", 0L)), seconds(number(p, "time_s")),
             p["error"].is_number() ? sci(p["error"].get<double>()) : "–",
             ok ? "yes" : "no: " + p.value("failures", "")});
      }
      continue;
    }
    std::ostringstream converged, diverged, other;
    for (const json& p : s["steps"]) {
      const std::string status = p.value("status", "");
      t.rows.push_back({scene, seconds(number(p, "c_over_c_crit")), sci(number(p, "c")), status,
                        p.value("criterion", ""), std::to_string(p.value("iterations", 0L))});
      rows.push_back({scene, csv_cell(number(p, "c_over_c_crit")), csv_cell(number(p, "c")),
                      std::to_string(p.value("iterations", 0L)), status, p.value("criterion", "")});
      std::ostringstream& into = status == "converged"  ? converged
                                 : status == "diverged" ? diverged
                                                        : other;
      into << number(p, "c_over_c_crit") << " " << std::max(1L, p.value("iterations", 0L)) << "\n";
    }
    for (const json& p : s["stiffness"]) {
      const double worst = worst_error(p);
      stiff.rows.push_back({scene, sci(number(p, "stiffness_ratio")), p.value("method", ""),
                            p.value("status", ""), std::to_string(p.value("iterations", 0L)),
                            seconds(number(p, "time_s")),
                            p.value("method", "") == "reference" ? "(truth)" : sci(worst)});
    }
    report.figure(
        "stability_" + slug(scene),
        "Iterations of the seed's rule on " + scene +
            " against c / c_crit: converged runs, and the iteration at which divergence "
            "was detected; c_crit = " +
            sci(number(s, "c_crit")) + " N/mm.",
        "set logscale y\nset xlabel 'c / c_{crit}'\nset ylabel 'iterations'\nset format y "
        "'10^{%L}'\nset xrange [0:*]\nset offsets 0, graph 0.05, graph 0.1, 0\nset key "
        "top center\nset grid\nset arrow from 1, graph 0 to 1, graph 1 "
        "nohead dt 2 lc rgb '#666666'\nplot @DATA0@ using 1:2 with linespoints pt 7 ps "
        "1.5 lw 2 title 'converged', @DATA1@ using 1:2 with points pt 2 ps 2 lw 3 title "
        "'diverged (iteration detected)', @DATA2@ using 1:2 with points pt 6 ps 2 title "
        "'iteration cap'",
        {{converged.str().empty() ? "nan nan\n" : converged.str()},
         {diverged.str().empty() ? "nan nan\n" : diverged.str()},
         {other.str().empty() ? "nan nan\n" : other.str()}});
  }
  if (!t.rows.empty()) report.table(t);
  if (!stiff.rows.empty()) report.table(stiff);
  if (!catalogue.rows.empty()) report.table(catalogue);
  report.csv("stability", {"scene", "c_over_c_crit", "c", "iterations", "status", "criterion"},
             rows);
}

std::string fixed3(double x) {
  if (!std::isfinite(x)) return "–";
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << x;
  return out.str();
}

double json_number(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

std::string run_title(const json& r) {
  const std::string solver = r.value("solver", "") == "fem" ? "reference" : "iterative";
  const std::string model = r.value("friction_model", "none");
  std::ostringstream out;
  out << solver << ", ";
  if (model == "none")
    out << "frictionless";
  else
    out << "mu " << json_number(r, "mu") << (model == "seed" ? " (seed rule)" : " (Coulomb)");
  return out.str();
}

void compaction_studies(Report& report, const ReportData& data) {
  if (data.compaction_studies.empty()) return;
  report.section(
      "Compaction",
      "Each tow is compacted step by step along its load path (every position scaled by F about "
      "the tow's centre, walls included), each step starting from the last. The pressure is the "
      "mean over the walls of the wall force over the wall's area; Vf the fibres' cross-sections "
      "over the area between the walls. Curves are fitted on the steps where the walls carry "
      "force by van Wyk's p = kE(Vf^3 - Vf0^3) and Toll's p = kE(Vf^n - Vf0^n). Friction: "
      "Coulomb's law per step (stick while |F| < muN, slip against the relative motion "
      "otherwise), which both solvers solve as a Tresca fixed point (the radii muN updated "
      "outside a convex inner problem, relaxed; the reference solves each inner problem exactly, "
      "by a bounded-variable active set when every contact has one tangent and by a semismooth "
      "Newton method with crossings; an outside solver, Siconos, agrees with it on exported "
      "problems), and the seed's own rule (§4.3.4, Eqs. 4.29-4.33: the previous "
      "resultant split along the deformed centres' normal, capped), run by the iterative "
      "solver only.");
  Table fits;
  fits.label = "compaction_fits";
  fits.caption =
      "Compaction runs: how each load path ended, the last step's Vf and pressure, and the fits "
      "on the steps with wall force (– where too few steps carry force: van Wyk needs two, Toll "
      "three).";
  fits.header = {"Scene",  "Run",   "Status", "Steps",  "Vf",       "p (MPa)", "vW k",
                 "vW Vf0", "vW R2", "Toll k", "Toll n", "Toll Vf0", "Toll R2", "Time (s)"};
  Table agreement;
  agreement.label = "compaction_agreement";
  agreement.caption =
      "The iterative solver's compaction curve against the reference's with the same mu: the "
      "largest per-step difference in pressure, relative to the reference curve's largest "
      "pressure, and in strain energy, relative to its largest, over the steps both converged. "
      "The seed's friction rule is measured against exact Coulomb friction.";
  agreement.header = {
      "Scene",          "mu",          "Iterative friction", "Reference friction", "Steps",
      "Pressure error", "Energy error"};
  for (const json& s : data.compaction_studies) {
    const std::string scene = s.value("scene", "");
    const double E = json_number(s, "youngs_modulus");
    std::vector<Gnuplot::Series> curves, energies;
    std::string plot_curves, plot_energy;
    int style = 0;
    const char* colours[] = {"#2040c0", "#e02020", "#20a040", "#e0a000", "#8040c0", "#404040"};
    const json* fitted = nullptr;
    for (const json& r : s["runs"]) {
      const json& vw = r["van_wyk"];
      const json& toll = r["toll"];
      int steps = 0;
      const json* last = nullptr;
      std::ostringstream points, energy;
      for (const json& p : r["points"]) {
        if (p.value("status", "") != "converged") continue;
        ++steps;
        last = &p;
        if (json_number(p, "pressure_MPa") > 0.0)
          points << json_number(p, "fibre_volume_fraction") << " " << json_number(p, "pressure_MPa")
                 << "\n";
        energy << p.value("step", 0) << " " << json_number(p, "strain_energy") << " "
               << json_number(p, "contacts_per_fibre") << "\n";
      }
      fits.rows.push_back({scene, run_title(r), r.value("status", ""),
                           std::to_string(steps) + "/" + std::to_string(r["points"].size()),
                           last ? fixed3(json_number(*last, "fibre_volume_fraction")) : "–",
                           last ? sci(json_number(*last, "pressure_MPa")) : "–",
                           sci(json_number(vw, "k")), fixed3(json_number(vw, "vf0")),
                           fixed3(json_number(vw, "r2")), sci(json_number(toll, "k")),
                           fixed3(json_number(toll, "n")), fixed3(json_number(toll, "vf0")),
                           fixed3(json_number(toll, "r2")),
                           seconds(json_number(r, "wall_time_s"))});
      const std::string colour = colours[style % 6];
      const int k = static_cast<int>(curves.size());
      curves.push_back({points.str().empty() ? "nan nan\n" : points.str()});
      plot_curves += std::string(plot_curves.empty() ? "" : ", ") + "@DATA" + std::to_string(k) +
                     "@ using 1:2 with points pt " + std::to_string(5 + 2 * style) +
                     " ps 1.6 lc rgb '" + colour + "' title '" + run_title(r) + "'";
      const int e = static_cast<int>(energies.size());
      energies.push_back({energy.str().empty() ? "nan nan nan\n" : energy.str()});
      plot_energy += std::string(plot_energy.empty() ? "" : ", ") + "@DATA" + std::to_string(e) +
                     "@ using 1:2 with linespoints pt " + std::to_string(5 + 2 * style) +
                     " lw 2 lc rgb '" + colour + "' title '" + run_title(r) + "'";
      ++style;
      // The fitted curves drawn: the reference with friction if it has them, else any run.
      const bool has_fit = json_number(vw, "k") == json_number(vw, "k");
      if (has_fit &&
          (!fitted || (r.value("solver", "") == "fem" && (*fitted).value("solver", "") != "fem")))
        fitted = &r;
    }
    bool any_pressure = false;
    for (const Gnuplot::Series& c : curves) any_pressure |= c.rows != "nan nan\n";
    std::string fit_lines;
    if (fitted) {
      const json& vw = (*fitted)["van_wyk"];
      const json& toll = (*fitted)["toll"];
      auto law = [&](const json& f, double n) {
        std::ostringstream out;
        out.precision(10);
        out << E * json_number(f, "k") << "*(x**" << n << " - " << json_number(f, "vf0") << "**"
            << n << ")";
        return out.str();
      };
      if (std::isfinite(json_number(vw, "vf0")))
        fit_lines += ", (x >= " + std::to_string(json_number(vw, "vf0")) + " ? " + law(vw, 3.0) +
                     " : 1/0) with lines lw 2 dt 2 lc rgb '#202020' title 'van Wyk fit (" +
                     run_title(*fitted) + ")'";
      if (std::isfinite(json_number(toll, "vf0")) && std::isfinite(json_number(toll, "n")))
        fit_lines += ", (x >= " + std::to_string(json_number(toll, "vf0")) + " ? " +
                     law(toll, json_number(toll, "n")) +
                     " : 1/0) with lines lw 2 dt 3 lc rgb '#a02080' title 'Toll fit'";
    }
    if (any_pressure)
      report.figure("compaction_" + slug(scene),
                    "Compaction curve of " + scene +
                        ": the mean wall pressure against the fibre volume fraction at every "
                        "converged step that loads the walls, for each solver and friction "
                        "setting, with the van Wyk and Toll fits" +
                        (fitted ? " of the " + run_title(*fitted) + " run" : std::string()) + ".",
                    "set xlabel 'fibre volume fraction V_f'\nset ylabel 'pressure (MPa)'\nset "
                    "logscale y\nset format y '10^{%L}'\nset key bottom right\nset grid\nset "
                    "samples 400\nset offsets graph 0.05, graph 0.05, 0, 0\nplot " +
                        plot_curves + fit_lines,
                    curves);
    report.figure("compaction_energy_" + slug(scene),
                  "Strain energy per step of " + scene +
                      "'s load path for each run (steps that did not converge left out).",
                  "set xlabel 'step'\nset ylabel 'strain energy (N mm)'\nset logscale y\nset "
                  "format y '10^{%L}'\nset key top left\nset grid\nset offsets 0.2, 0.2, 0, "
                  "0\nplot " +
                      plot_energy,
                  energies);
    // Per-step pressure differences against the reference.
    std::vector<Gnuplot::Series> errors;
    std::string plot_errors;
    auto run_of = [&](const std::string& solver, double mu, const std::string& model) {
      for (const json& r : s["runs"])
        if (r.value("solver", "") == solver && json_number(r, "mu") == mu &&
            r.value("friction_model", "") == model)
          return &r;
      return static_cast<const json*>(nullptr);
    };
    for (const json& a : s["agreement"]) {
      agreement.rows.push_back({scene, sci(json_number(a, "mu")), a.value("friction_model", ""),
                                a.value("against", ""), std::to_string(a.value("steps", 0)),
                                sci(json_number(a, "pressure_error")),
                                sci(json_number(a, "energy_error"))});
      const json* it = run_of("iterative", json_number(a, "mu"), a.value("friction_model", ""));
      const json* ref = run_of("fem", json_number(a, "mu"), a.value("against", ""));
      if (!it || !ref) continue;
      double largest = 0.0;
      for (const json& q : (*ref)["points"])
        if (q.value("status", "") == "converged")
          largest = std::max(largest, json_number(q, "pressure_MPa"));
      std::ostringstream rows;
      for (const json& q : (*ref)["points"])
        for (const json& i : (*it)["points"])
          if (i.value("step", 0) == q.value("step", 0) && largest > 0.0 &&
              i.value("status", "") == "converged" && q.value("status", "") == "converged" &&
              json_number(q, "pressure_MPa") > 0.0)
            rows << json_number(q, "fibre_volume_fraction") << " "
                 << std::max(1e-16, std::fabs(json_number(i, "pressure_MPa") -
                                              json_number(q, "pressure_MPa")) /
                                        largest)
                 << "\n";
      if (rows.str().empty()) continue;
      const int k = static_cast<int>(errors.size());
      errors.push_back({rows.str()});
      plot_errors += std::string(plot_errors.empty() ? "" : ", ") + "@DATA" + std::to_string(k) +
                     "@ using 1:2 with linespoints pt " + std::to_string(5 + 2 * k) +
                     " ps 1.5 lw 2 title '" + run_title(*it) + "'";
    }
    if (!plot_errors.empty())
      report.figure("compaction_error_" + slug(scene),
                    "The iterative compaction curve of " + scene +
                        " against the reference's with the same mu: the pressure difference at "
                        "each step, relative to the reference curve's largest pressure.",
                    "set xlabel 'fibre volume fraction V_f'\nset ylabel '|p_{it} - p_{ref}| / "
                    "max p_{ref}'\nset logscale y\nset format y '10^{%L}'\nset key top "
                    "left\nset grid\nset offsets graph 0.05, graph 0.05, 0, 0\nplot " +
                        plot_errors,
                    errors);
    // The last state of the run with friction (Coulomb, iterative), drawn like Figure 4.14.
    const std::filesystem::path folder = s.value("folder", "");
    try {
      const Scene stepped = read_scene((folder / s.value("scene_file", "")).string());
      for (const json& r : s["runs"]) {
        if (r.value("solver", "") != "iterative" || r.value("friction_model", "") == "seed")
          continue;
        if (r.value("friction_model", "") == "none" &&
            run_of("iterative", stepped.contact.friction, "coulomb"))
          continue;  // with friction in the scene, the frictional run is the one drawn
        for (const json& section : r["sections"]) {
          const int step = section.value("step", 0);
          Scene at = scene_at_step(stepped, stepped.steps.at(static_cast<std::size_t>(step - 1)));
          const Result result = read_result((folder / section.value("result", "")).string());
          draw_cross_section(report,
                             "compaction_section_" + slug(scene) + "_step" + std::to_string(step),
                             "A cross-section of " + scene + " at step " + std::to_string(step) +
                                 " of its load path (" + run_title(r) + ")",
                             at, result);
        }
      }
    } catch (const InputError& e) {
      report.summary().missing.push_back("cross-sections of " + scene + ": " + e.what());
    }
  }
  if (!fits.rows.empty()) report.table(fits);
  if (!agreement.rows.empty()) report.table(agreement);
}

std::string scale_series(const json& p) {
  const std::string solver = p.value("solver", "");
  const std::string method = p.value("method", "");
  if (solver == "iterative") return "iterative, " + method;
  if (solver == "fem")
    return "reference, " + std::to_string(p.value("processes", 1)) + " process" +
           (p.value("processes", 1) == 1 ? "" : "es");
  return "Siconos " + method;
}

void scale_studies(Report& report, const ReportData& data) {
  if (data.scale_studies.empty()) return;
  report.section(
      "Scale",
      "Generated tows of growing size (fibrecheck study scale), each run its own process: the "
      "iterative solver's rules, the reference under mpiexec and Siconos on the reference's "
      "exported contact problem (Lemke's pivoting, projected Gauss-Seidel and a Newton method on "
      "the linear complementarity problem). Time is the solver's own (without start-up and "
      "files); peak memory is the process's (the largest process's under mpiexec; the program "
      "links the finite-element libraries, about 150 MB of it). For the reference the iterations "
      "are its outer iterations; its active-set passes are in its result files.");
  for (const json& study : data.scale_studies) {
    Table t;
    t.label = "scale";
    t.caption =
        "Cost against tow size (" + std::to_string(study.value("slices", 0)) + " slices, seed " +
        std::to_string(study.value("seed", 0)) +
        "): candidate and pushing contacts, iterations, time, time per iteration and peak "
        "memory (for the reference, over all its processes per finite-element unknown); for "
        "Siconos, its distance from the reference's answer.";
    t.header = {"Fibres",    "Run",        "Status",           "Candidates",
                "Active",    "Iterations", "Time (s)",         "ms/iteration",
                "Peak (MB)", "kB/unknown", "Against reference"};
    std::vector<std::string> series;
    std::map<std::string, std::ostringstream> rows;
    for (const json& p : study["points"]) {
      const std::string name = scale_series(p);
      const bool iterative = p.value("solver", "") != "fem";
      const double agreement = json_number(p, "agreement");
      const double unknowns = json_number(p, "unknowns");
      t.rows.push_back(
          {std::to_string(p.value("fibres", 0)), name, p.value("status", ""),
           std::to_string(p.value("candidates", 0L)), std::to_string(p.value("active", 0L)),
           std::to_string(p.value("iterations", 0L)), seconds(json_number(p, "time_s")),
           iterative ? sci(json_number(p, "ms_per_iteration")) : "–",
           fixed3(json_number(p, "peak_memory_mb")),
           // The reference's peak over all its processes, per finite-element unknown.
           unknowns > 0.0 ? fixed3(1024.0 * json_number(p, "peak_memory_mb") *
                                   p.value("processes", 1) / unknowns)
                          : "–",
           agreement >= 0.0 ? sci(agreement) : "–"});
      if (p.value("status", "") != "converged" || !(json_number(p, "time_s") > 0.0)) continue;
      if (std::find(series.begin(), series.end(), name) == series.end()) series.push_back(name);
      rows[name] << p.value("fibres", 0) << " " << json_number(p, "time_s") << "\n";
    }
    std::string exponents;
    for (const json& e : study["exponents"]) {
      // Named like its points (the reference's with their process count).
      json named = {{"solver", e.value("solver", "")}, {"method", e.value("method", "")}};
      for (const json& p : study["points"])
        if (p.value("solver", "") == e.value("solver", "") &&
            p.value("method", "") == e.value("method", ""))
          named["processes"] = p.value("processes", 1);
      std::ostringstream line;
      line.precision(2);
      line << std::fixed << scale_series(named) << " " << json_number(e, "time");
      exponents += (exponents.empty() ? "" : "; ") + line.str();
    }
    if (!exponents.empty()) t.caption += " Time grows as fibres^a with a: " + exponents + ".";
    report.table(t);
    std::vector<Gnuplot::Series> data_series;
    std::string plot;
    for (const std::string& name : series) {
      const int k = static_cast<int>(data_series.size());
      data_series.push_back({rows[name].str()});
      plot += std::string(plot.empty() ? "" : ", ") + "@DATA" + std::to_string(k) +
              "@ using 1:2 with linespoints pt " + std::to_string(5 + 2 * k) +
              " ps 1.5 lw 2 title '" + name + "'";
    }
    if (!plot.empty())
      report.figure("scale_time",
                    "Solver time against the number of fibres (log-log), converged runs only"
                    " (exponents in the table's caption).",
                    "set xlabel 'fibres'\nset ylabel 'time (s)'\nset logscale xy\nset format y "
                    "'10^{%L}'\nset key top left\nset grid\nset offsets graph 0.05, graph 0.05, "
                    "0, 0\nplot " +
                        plot,
                    data_series);
  }
}

}  // namespace

ReportSummary write_report(const ReportData& data, const std::string& folder) {
  Report report(folder);
  comparisons(report, data);
  slice_studies(report, data);
  tolerance_studies(report, data);
  stability_studies(report, data);
  compaction_studies(report, data);
  scale_studies(report, data);
  return report.finish(data.sources);
}

}  // namespace fibrecheck
