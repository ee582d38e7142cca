#include "compaction_section.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>

#include "atomic_file.h"
#include "cross_section_figure.h"
#include "input_error.h"
#include "load_path.h"

namespace fibrecheck {

namespace {

/// "iterative, μ = 0.2 (Coulomb)", "reference, frictionless", …
std::string run_title(const CompactionRun& r) {
  const std::string solver = r.solver == "fem" ? "reference" : "iterative";
  std::ostringstream out;
  out << solver << ", ";
  if (r.friction_model == "none")
    out << "frictionless";
  else
    out << "μ = " << r.mu << (r.friction_model == "seed" ? " (seed rule)" : " (Coulomb)");
  if (r.geometry == "linearised") out << ", linearised contact";
  return out.str();
}

/// The first run of `solver` with friction coefficient `mu`, `model` and (unless empty)
/// `geometry`, or none.
const CompactionRun* run_of(const CompactionStudyScene& s, const std::string& solver, double mu,
                            const std::string& model, const std::string& geometry = "") {
  for (const CompactionRun& r : s.runs)
    if (r.solver == solver && r.mu == mu && r.friction_model == model &&
        (geometry.empty() || r.geometry == geometry))
      return &r;
  return nullptr;
}

std::string series_entry(const std::string& plot, int k) {
  return std::string(plot.empty() ? "" : ", ") + "@DATA" + std::to_string(k) + "@ using 1:2 with ";
}

/// Each run's converged steps: the compaction curve (where the walls carry force) and the strain
/// energy per step, as series and their plot commands, one style per run.
struct CompactionCurves {
  std::vector<Gnuplot::Series> pressure, energy;
  std::string plot_pressure, plot_energy;
  bool any_pressure = false;
};

CompactionCurves compaction_curves(const CompactionStudyScene& s) {
  const char* colours[] = {"#2040c0", "#e02020", "#20a040", "#e0a000", "#8040c0", "#404040"};
  CompactionCurves c;
  int style = 0;
  for (const CompactionRun& r : s.runs) {
    std::ostringstream points, energy;
    for (const CompactionPoint& p : r.points) {
      if (p.status != "converged") continue;
      if (p.pressure > 0.0) points << p.fibre_volume_fraction << " " << p.pressure << "\n";
      energy << p.step << " " << p.strain_energy << " " << p.contacts_per_fibre << "\n";
    }
    const std::string colour = colours[style % 6];
    const std::string pt = std::to_string(5 + 2 * style);
    c.plot_pressure += series_entry(c.plot_pressure, static_cast<int>(c.pressure.size())) +
                       "points pt " + pt + " ps 1.6 lc rgb '" + colour + "' title '" +
                       run_title(r) + "'";
    c.pressure.push_back({points.str().empty() ? "nan nan\n" : points.str()});
    c.plot_energy += series_entry(c.plot_energy, static_cast<int>(c.energy.size())) +
                     "linespoints pt " + pt + " lw 2 lc rgb '" + colour + "' title '" +
                     run_title(r) + "'";
    c.energy.push_back({energy.str().empty() ? "nan nan nan\n" : energy.str()});
    c.any_pressure |= !points.str().empty();
    ++style;
  }
  return c;
}

/// The run whose fits are drawn: the reference's if it has them, else the first run with fits.
const CompactionRun* fitted_run(const CompactionStudyScene& s) {
  const CompactionRun* fitted = nullptr;
  for (const CompactionRun& r : s.runs) {
    const bool has_fit = r.van_wyk.k == r.van_wyk.k;
    if (has_fit && (!fitted || (r.solver == "fem" && fitted->solver != "fem"))) fitted = &r;
  }
  return fitted;
}

/// The fitted laws p = kE(Vfⁿ − Vf0ⁿ) of `r` as gnuplot functions of x = Vf, from Vf0 on.
std::string fit_lines(const CompactionRun& r, double E) {
  auto law = [&](const PowerLawFit& f, double n) {
    std::ostringstream out;
    out.precision(10);
    out << E * f.k << "*(x**" << n << " - " << f.vf0 << "**" << n << ")";
    return out.str();
  };
  std::string lines;
  if (std::isfinite(r.van_wyk.vf0))
    lines += ", (x >= " + std::to_string(r.van_wyk.vf0) + " ? " + law(r.van_wyk, 3.0) +
             " : 1/0) with lines lw 2 dt 2 lc rgb '#202020' title 'van Wyk fit (" + run_title(r) +
             ")'";
  if (std::isfinite(r.toll.vf0) && std::isfinite(r.toll.n))
    lines += ", (x >= " + std::to_string(r.toll.vf0) + " ? " + law(r.toll, r.toll.n) +
             " : 1/0) with lines lw 2 dt 3 lc rgb '#a02080' title 'Toll fit'";
  return lines;
}

/// The compaction curves with the fits, and the strain energy per step.
void curve_figures(ReportPage& page, const CompactionStudyScene& s) {
  const CompactionCurves c = compaction_curves(s);
  const CompactionRun* fitted = fitted_run(s);
  const std::string fits = fitted ? fit_lines(*fitted, s.youngs_modulus) : "";
  if (c.any_pressure)
    page.figure("compaction_" + file_name_slug(s.scene),
                "Compaction curve of " + s.scene +
                    ": the mean wall pressure against the fibre volume fraction at every "
                    "converged step that loads the walls, for each solver and friction "
                    "setting, with the van Wyk and Toll fits" +
                    (fitted ? " of the " + run_title(*fitted) + " run" : std::string()) + ".",
                "set xlabel 'fibre volume fraction V_f'\nset ylabel 'pressure (MPa)'\nset "
                "logscale y\nset format y '10^{%L}'\nset key bottom right\nset grid\nset "
                "samples 400\nset offsets graph 0.05, graph 0.05, 0, 0\nplot " +
                    c.plot_pressure + fits,
                c.pressure);
  page.figure("compaction_energy_" + file_name_slug(s.scene),
              "Strain energy per step of " + s.scene +
                  "'s load path for each run (steps that did not converge left out).",
              "set xlabel 'step'\nset ylabel 'strain energy (N mm)'\nset logscale y\nset "
              "format y '10^{%L}'\nset key top left\nset grid\nset offsets 0.2, 0.2, 0, "
              "0\nplot " +
                  c.plot_energy,
              c.energy);
}

/// Rows "Vf |p_it − p_ref| / max p_ref" of the steps both converged on where the reference's
/// walls carry force.
std::string pressure_difference_rows(const CompactionRun& iterative,
                                     const CompactionRun& reference) {
  const double largest = largest_pressure(reference);
  std::ostringstream rows;
  if (!(largest > 0.0)) return rows.str();
  for (const StepDifference& d : step_differences(iterative, reference))
    if (d.reference_pressure > 0.0)
      rows << d.fibre_volume_fraction << " " << std::max(1e-16, d.pressure / largest) << "\n";
  return rows.str();
}

/// Each iterative curve's pressure difference from the reference's with the same μ, per step.
void agreement_figure(ReportPage& page, const CompactionStudyScene& s) {
  std::vector<Gnuplot::Series> errors;
  std::string plot;
  for (const CompactionAgreement& a : s.agreement) {
    const CompactionRun* it = run_of(s, "iterative", a.mu, a.friction_model, a.geometry);
    const CompactionRun* ref = run_of(s, "fem", a.mu, a.against, a.geometry);
    if (!it || !ref) continue;
    const std::string rows = pressure_difference_rows(*it, *ref);
    if (rows.empty()) continue;
    const int k = static_cast<int>(errors.size());
    errors.push_back({rows});
    plot += series_entry(plot, k) + "linespoints pt " + std::to_string(5 + 2 * k) +
            " ps 1.5 lw 2 title '" + run_title(*it) + "'";
  }
  if (plot.empty()) return;
  page.figure(
      "compaction_error_" + file_name_slug(s.scene),
      "The iterative compaction curve of " + s.scene +
          " against the reference's with the same friction coefficient μ: the pressure difference "
          "at "
          "each step, relative to the reference curve's largest pressure.",
      "set xlabel 'fibre volume fraction V_f'\nset ylabel '|p_{it} - p_{ref}| / "
      "max p_{ref}'\nset logscale y\nset format y '10^{%L}'\nset key "
      "outside top center horizontal\nset grid\nset offsets graph 0.05, graph 0.05, 0, 0\nplot " +
          plot,
      errors);
}

/// The kept states of the iterative runs drawn like Figure 4.14: the run with the scene's
/// friction (Coulomb) where the scene has friction, else the frictionless one. The stepped scene
/// and the states are read from the study's folder; what cannot be read is named in the summary.
void cross_section_figures(ReportPage& page, const StoredCompactionStudy& stored) {
  const CompactionStudyScene& s = stored.study;
  const std::filesystem::path folder = stored.folder;
  try {
    const Scene stepped = read_scene((folder / s.scene_file).string());
    for (const CompactionRun& r : s.runs) {
      if (r.solver != "iterative" || r.friction_model == "seed") continue;
      if (r.geometry != s.runs.front().geometry) continue;
      if (r.friction_model == "none" && run_of(s, "iterative", stepped.contact.friction, "coulomb"))
        continue;
      for (const auto& [step, file] : r.sections) {
        const Scene at =
            scene_at_step(stepped, stepped.steps.at(static_cast<std::size_t>(step - 1)));
        const Result result = read_result((folder / file).string());
        // A run that stopped early keeps the state it stopped in: its status says what it is.
        std::string stopped;
        if (result.status != Status::converged)
          stopped = "; the step did not converge (" + std::string(to_string(result.status)) +
                    "): the state it stopped in";
        draw_cross_section(
            page, "compaction_section_" + file_name_slug(s.scene) + "_step" + std::to_string(step),
            "A cross-section of " + s.scene + " at step " + std::to_string(step) +
                " of its load path (" + run_title(r) + stopped + ")",
            at, result);
      }
    }
  } catch (const InputError& e) {
    page.summary().missing.push_back("cross-sections of " + s.scene + ": " + e.what());
  }
}

Table fits_table() {
  Table fits;
  fits.label = "compaction_fits";
  fits.caption =
      "Compaction runs: how each load path ended, the last step's Vf and pressure, and the fits "
      "on the steps with wall force (– where too few steps carry force: van Wyk needs two, Toll "
      "three; Toll's n is fitted up to 30, and ≥ 30 says the curve is steeper than that).";
  fits.header = {"Scene",  "Run",   "Status", "Steps",  "Vf",       "p (MPa)", "vW k",
                 "vW Vf0", "vW R2", "Toll k", "Toll n", "Toll Vf0", "Toll R2", "Time (s)"};
  return fits;
}

/// Toll's n, or "≥ 30" where the fit ended at the largest exponent it tries.
std::string toll_exponent(const PowerLawFit& toll) {
  if (toll.n >= kTollLargestExponent) return "≥ " + seconds(kTollLargestExponent);
  return fixed3(toll.n);
}

void fits_rows(Table& t, const CompactionStudyScene& s) {
  for (const CompactionRun& r : s.runs) {
    int steps = 0;
    const CompactionPoint* last = nullptr;
    for (const CompactionPoint& p : r.points)
      if (p.status == "converged") ++steps, last = &p;
    t.rows.push_back({s.scene, run_title(r), r.status,
                      std::to_string(steps) + "/" + std::to_string(r.points.size()),
                      last ? fixed3(last->fibre_volume_fraction) : "–",
                      last ? sci(last->pressure) : "–", sci(r.van_wyk.k), fixed3(r.van_wyk.vf0),
                      fixed3(r.van_wyk.r2), sci(r.toll.k), toll_exponent(r.toll),
                      fixed3(r.toll.vf0), fixed3(r.toll.r2), seconds(r.time_s)});
  }
}

/// A run as a short table column: "it.", "ref. μ 0.2 Coulomb", "it. lin." (the captions say
/// what the abbreviations stand for).
std::string column_title(const CompactionRun& r) {
  std::string title = r.solver == "fem" ? "ref." : "it.";
  if (r.friction_model != "none")
    title += " μ " + seconds(r.mu) + (r.friction_model == "seed" ? " seed rule" : " Coulomb");
  if (r.geometry == "linearised") title += " lin.";
  return title;
}

const char* const kColumnKey =
    " Columns: it. the iterative solver, ref. the reference, lin. the linearised contact (the "
    "others on the deformed fibres), μ and the friction model where there is friction.";

/// The steps of `s`'s load path, the most any of its runs reached.
std::size_t steps_of(const CompactionStudyScene& s) {
  std::size_t steps = 0;
  for (const CompactionRun& r : s.runs) steps = std::max(steps, r.points.size());
  return steps;
}

/// The runs of `s` that `keep` picks.
template <class Keep>
std::vector<const CompactionRun*> runs_of(const CompactionStudyScene& s, Keep keep) {
  std::vector<const CompactionRun*> runs;
  for (const CompactionRun& r : s.runs)
    if (keep(r)) runs.push_back(&r);
  return runs;
}

/// A table of the steps of `s`'s load path, a column per run of `runs` (a cell `cell(point)`,
/// empty where the run had stopped before the step), on the steps where `shown(point)` holds for
/// some run; every step where `shown` is empty.
template <class Cell>
void fill_step_table(Table& t, const CompactionStudyScene& s,
                     const std::vector<const CompactionRun*>& runs, Cell cell,
                     const std::function<bool(const CompactionPoint&)>& shown) {
  t.header = {"Step", "Vf"};
  for (const CompactionRun* r : runs) t.header.push_back(column_title(*r));
  for (std::size_t k = 0; k < steps_of(s); ++k) {
    std::vector<std::string> row = {std::to_string(k + 1), ""};
    bool any = !shown;
    for (const CompactionRun* r : runs) {
      if (k >= r->points.size()) {
        row.push_back("");
        continue;
      }
      const CompactionPoint& p = r->points[k];
      row[1] = fixed3(p.fibre_volume_fraction);
      row.push_back(cell(p));
      if (shown) any |= shown(p);
    }
    if (any) t.rows.push_back(row);
  }
}

/// The points the curves of `s` are drawn and fitted from: per step Vf and each run's pressure
/// (the status where the step did not converge, empty where the run had stopped before it), on
/// the steps where some run loads the walls or fails. None where no run loads the walls.
std::optional<Table> points_table(const CompactionStudyScene& s) {
  Table t;
  t.label = "compaction_points_" + file_name_slug(s.scene);
  t.caption = "The points of the compaction curves of " + s.scene +
              ": the mean wall pressure (MPa) at each step of the load path where a run loads "
              "the walls, per run; a status where the step did not converge, nothing where the "
              "run had stopped before it." +
              kColumnKey;
  fill_step_table(
      t, s, runs_of(s, [](const CompactionRun&) { return true; }),
      [](const CompactionPoint& p) { return p.status == "converged" ? sci(p.pressure) : p.status; },
      [](const CompactionPoint& p) { return p.status != "converged" || p.pressure > 0.0; });
  if (t.rows.empty()) return std::nullopt;
  return t;
}

/// What each step of `s` cost the iterative solver: iterations and seconds, and the updates of the
/// normals and of the Tresca radii where there were any, per run.
Table cost_table(const CompactionStudyScene& s) {
  Table t;
  t.label = "compaction_cost_" + file_name_slug(s.scene);
  t.caption = "What each step of " + s.scene +
              "'s load path cost the iterative solver, per run: iterations (wall time in "
              "seconds), each step warm-started from the last; after the slash, the updates of "
              "the normals to the displaced fibres and of the Tresca radii (records kept before "
              "these were counted show none)." +
              kColumnKey;
  auto cell = [](const CompactionPoint& p) {
    std::string cost = count(p.iterations) + " (" + seconds(p.time_s) + " s)";
    if (p.geometric_updates > 0 || p.fixed_point_updates > 0)
      cost += " / " + std::to_string(p.geometric_updates) + ", " +
              std::to_string(p.fixed_point_updates);
    return cost;
  };
  fill_step_table(t, s, runs_of(s, [](const CompactionRun& r) { return r.solver == "iterative"; }),
                  cell, [](const CompactionPoint&) { return true; });
  return t;
}

/// Coulomb's law on each step's answer, per run with Coulomb friction: what lets a reader check
/// that a curve's points are answers of the frictional problem and not states a fixed point left
/// unsettled. On the steps where some run has contacts that carry force or did not converge; none
/// where no run has Coulomb friction.
std::optional<Table> coulomb_table(const CompactionStudyScene& s) {
  const std::vector<const CompactionRun*> runs =
      runs_of(s, [](const CompactionRun& r) { return r.friction_model == "coulomb"; });
  if (runs.empty()) return std::nullopt;
  Table t;
  t.label = "compaction_coulomb_" + file_name_slug(s.scene);
  t.caption = "Coulomb's law on the answer of each step of " + s.scene +
              "'s load path where contacts carry force, per run with Coulomb friction: the "
              "largest slip at a contact that sticks (|F| < μN), then the largest slip not along "
              "its friction at one that slips, in mm. A converged step leaves both within the "
              "scene's overlap tolerance; a step that did not converge gives its status before "
              "what its state left (records kept before these were measured show –)." +
              kColumnKey;
  fill_step_table(
      t, s, runs,
      [](const CompactionPoint& p) {
        const std::string residuals = sci(p.stick_residual) + " / " + sci(p.slip_residual);
        return p.status == "converged" ? residuals : p.status + ": " + residuals;
      },
      [](const CompactionPoint& p) {
        return p.status != "converged" || p.contacts_per_fibre > 0.0;
      });
  return t;
}

Table agreement_table() {
  Table agreement;
  agreement.label = "compaction_agreement";
  agreement.caption =
      "The iterative solver's compaction curve against the reference's with the same friction "
      "coefficient μ: the "
      "largest per-step difference in pressure, relative to the reference curve's largest "
      "pressure, and in strain energy, relative to its largest, over the steps both converged. "
      "The seed's friction rule is measured against exact Coulomb friction.";
  agreement.header = {"Scene",   "μ",     "Iterative friction", "Reference friction",
                      "Contact", "Steps", "Pressure error",     "Energy error"};
  return agreement;
}

void agreement_rows(Table& t, const CompactionStudyScene& s) {
  for (const CompactionAgreement& a : s.agreement)
    t.rows.push_back({s.scene, sci(a.mu), a.friction_model, a.against, a.geometry,
                      std::to_string(a.steps), sci(a.pressure_error), sci(a.energy_error)});
}

// The pressure of `other` against `base` at the last step both converged on with wall force: a
// sentence part "<what> x % higher/lower at Vf = …", or empty.
std::string pressure_change(const CompactionRun* base, const CompactionRun* other,
                            const std::string& what) {
  if (!base || !other) return "";
  for (std::size_t k = std::min(base->points.size(), other->points.size()); k-- > 0;) {
    const CompactionPoint &b = base->points[k], &o = other->points[k];
    if (b.status != "converged" || o.status != "converged" || !(b.pressure > 0.0)) continue;
    const double change = 100.0 * (o.pressure / b.pressure - 1.0);
    std::ostringstream out;
    out << what << " a pressure " << seconds(std::fabs(change)) << " % "
        << (change >= 0 ? "higher" : "lower") << " at $V_f = " << fixed3(b.fibre_volume_fraction)
        << "$";
    return out.str();
  }
  return "";
}

// What friction and the contact geometry do to the pressure, on the largest tow studied.
std::optional<std::string> compaction_finding(const std::vector<StoredCompactionStudy>& studies) {
  for (auto it = studies.rbegin(); it != studies.rend(); ++it) {
    const CompactionStudyScene& s = it->study;
    const CompactionRun* frictionless = run_of(s, "iterative", 0.0, "none", "deformed");
    const CompactionRun* linearised = run_of(s, "iterative", 0.0, "none", "linearised");
    const CompactionRun* coulomb = nullptr;
    for (const CompactionRun& r : s.runs)
      if (r.solver == "iterative" && r.friction_model == "coulomb" && r.geometry == "deformed")
        coulomb = &r;
    const std::string geometry =
        pressure_change(frictionless, linearised, "the linearised contact gives");
    const std::string friction =
        coulomb ? pressure_change(frictionless, coulomb,
                                  "Coulomb friction (μ = " + seconds(coulomb->mu) + ") gives")
                : "";
    if (geometry.empty() && friction.empty()) continue;
    std::string out = "Compacting " + s.scene +
                      ", against the frictionless contact on the "
                      "deformed fibres, " +
                      geometry + (geometry.empty() || friction.empty() ? "" : "; ") + friction +
                      " ([#tab:compaction_fits]).";
    return out;
  }
  return std::nullopt;
}

}  // namespace

void write_compaction_section(ReportPage& page, const std::vector<StoredCompactionStudy>& studies) {
  if (studies.empty()) return;
  page.section(
      "Compaction",
      "Each tow is compacted step by step along its load path (every position scaled by F about "
      "the tow's centre, walls included), each step starting from the last. The pressure is the "
      "mean over the walls of the wall force over the wall's area; Vf the fibres' cross-sections "
      "over the area between the walls. Curves are fitted on the steps where the walls carry "
      "force by van Wyk's $p = kE(V_f^3 - V_{f0}^3)$ [@vanwyk1946] and Toll's $p = kE(V_f^n - "
      "V_{f0}^n)$ [@toll1998]. Friction: "
      "Coulomb's law per step (stick while |F| < muN, slip against the relative motion "
      "otherwise), which both solvers solve as a Tresca fixed point (the radii muN updated "
      "outside a convex inner problem, relaxed; the reference solves each inner problem exactly, "
      "by a bounded-variable active set when every contact has one tangent and by a semismooth "
      "Newton method with crossings; an outside solver, Siconos, agrees with it on exported "
      "problems), and the seed's own rule (§4.3.4, Eqs. 4.29-4.33: the previous "
      "resultant split along the deformed centres' normal, capped), run by the iterative "
      "solver only.");
  Table fits = fits_table(), agreement = agreement_table();
  for (const StoredCompactionStudy& stored : studies) {
    fits_rows(fits, stored.study);
    curve_figures(page, stored.study);
    agreement_rows(agreement, stored.study);
    agreement_figure(page, stored.study);
    cross_section_figures(page, stored);
  }
  if (!fits.rows.empty()) {
    page.table(fits);
    if (auto finding = compaction_finding(studies)) page.finding(*finding);
  }
  if (!agreement.rows.empty()) page.table(agreement);
  for (const StoredCompactionStudy& stored : studies)
    if (auto points = points_table(stored.study)) page.table(*points);
  page.table(cost_table(studies.back().study));
  for (const StoredCompactionStudy& stored : studies)
    if (auto coulomb = coulomb_table(stored.study)) page.table(*coulomb);
}

}  // namespace fibrecheck
