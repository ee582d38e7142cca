#include "friction_section.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "csv_file.h"
#include "gnuplot.h"

namespace fibrecheck {

namespace {

/// The two runs of one tow, compaction and μ.
struct RunPair {
  const FrictionPoint* seed = nullptr;
  const FrictionPoint* coulomb = nullptr;
};

using PairKey = std::tuple<int, double, double>;  // fibres, F (descending), μ

std::map<PairKey, RunPair> pairs_of(const std::vector<FrictionPoint>& points) {
  std::map<PairKey, RunPair> pairs;
  for (const FrictionPoint& p : points) {
    RunPair& pair = pairs[{p.fibres, -p.compaction, p.mu}];
    (p.model == "seed" ? pair.seed : pair.coulomb) = &p;
  }
  return pairs;
}

std::string outcome(const FrictionPoint* p) {
  if (!p) return "–";
  return p->criterion == p->status || p->status == "converged"
             ? p->status
             : p->status + " (" + p->criterion + ")";
}

/// How far the seed rule's answer is from Coulomb's law, where it converged (a diverged run's
/// best state says nothing about the rule).
std::string seed_slip(const FrictionPoint* p) {
  return p && p->status == "converged" ? sci(p->stick_residual) : "–";
}

std::string iterations(const FrictionPoint* p) {
  return p ? count(p->iterations) : "–";
}

/// Pressure of the seed's rule over Coulomb's, where both converged.
double pressure_ratio(const RunPair& pair) {
  if (!pair.seed || !pair.coulomb || pair.seed->status != "converged" ||
      pair.coulomb->status != "converged" || !(pair.coulomb->pressure > 0.0))
    return NAN;
  return pair.seed->pressure / pair.coulomb->pressure;
}

Table friction_table(const std::map<PairKey, RunPair>& pairs) {
  Table t;
  t.label = "friction";
  t.caption =
      "Generated tows compacted in one step to F, each with friction coefficient μ, solved by "
      "the iterative solver with the seed's friction rule (Eqs. 4.29–4.33) and with Coulomb "
      "friction: how each run ended, its iterations, how far the seed rule's converged answer is "
      "from Coulomb's law (the largest slip at a contact below its cone, mm), and the seed rule's "
      "wall pressure over Coulomb's where both converged.";
  t.header = {"Fibres",
              "F",
              "Vf",
              "μ",
              "Seed rule",
              "Iter.",
              "Coulomb",
              "Iter.",
              "Seed: slip below the cone (mm)",
              "Pressure ratio"};
  for (const auto& [key, pair] : pairs) {
    const FrictionPoint& any = pair.seed ? *pair.seed : *pair.coulomb;
    t.rows.push_back({std::to_string(any.fibres), fixed3(any.compaction),
                      fixed3(any.fibre_volume_fraction), fixed3(any.mu), outcome(pair.seed),
                      iterations(pair.seed), outcome(pair.coulomb), iterations(pair.coulomb),
                      seed_slip(pair.seed), fixed3(pressure_ratio(pair))});
  }
  return t;
}

/// How each run on one tow size ended, by its fibre volume fraction and μ: the seed's rule
/// (circles, drawn a little to the left) and Coulomb friction (triangles, to the right), coloured
/// by status.
void outcome_figure(ReportPage& page, int fibres, const std::vector<FrictionPoint>& points) {
  constexpr double kApart = 0.006;  // of Vf, between the two models' marks
  std::ostringstream series[2][3];  // model (seed, Coulomb) × status (converged, diverged, cap)
  for (const FrictionPoint& p : points) {
    if (p.fibres != fibres) continue;
    const int model = p.model == "seed" ? 0 : 1;
    const int status = p.status == "converged" ? 0 : p.status == "diverged" ? 1 : 2;
    series[model][status] << p.fibre_volume_fraction + (model == 0 ? -kApart : kApart) << " "
                          << p.mu << "\n";
  }
  std::vector<Gnuplot::Series> data;
  for (auto& model : series)
    for (auto& status : model) data.push_back({rows_or_nan(status.str())});
  std::ostringstream plot;
  const char* colour[] = {"#1a9850", "#d73027", "#4575b4"};
  const char* status[] = {"converged", "diverged", "iteration cap"};
  const char* model[] = {"seed rule", "Coulomb"};
  plot << "plot ";
  for (int m = 0; m < 2; ++m)
    for (int k = 0; k < 3; ++k)
      plot << (m + k > 0 ? ", " : "") << "@DATA" << 3 * m + k << "@ using 1:2 with points pt "
           << (m == 0 ? 7 : 9) << " ps 2.2 lc rgb '" << colour[k] << "' title '" << model[m] << ", "
           << status[k] << "'";
  page.figure("friction_seed_rule_" + std::to_string(fibres),
              "How each run on the " + std::to_string(fibres) +
                  "-fibre tow ended, by its fibre volume fraction after compaction and its "
                  "friction coefficient μ: the seed's friction rule (circles, left of each "
                  "fraction) and Coulomb friction (triangles, right); green converged, red "
                  "diverged, blue stopped at the iteration cap.",
              "set xlabel 'fibre volume fraction V_f'\nset ylabel 'friction coefficient "
              "{/Symbol m}'\nset offsets graph 0.1, graph 0.1, graph 0.15, graph 0.15\nset key "
              "above horizontal maxcols 3\nset grid\n" +
                  plot.str(),
              data);
}

// How often each model converged, and the densest tow on which the seed's rule still did.
std::string friction_finding(const std::vector<FrictionPoint>& points) {
  int runs = 0, seed_converged = 0, coulomb_converged = 0;
  double densest = 0.0, loosest_failure = INFINITY;
  for (const FrictionPoint& p : points) {
    const bool converged = p.status == "converged";
    if (p.model == "coulomb") {
      coulomb_converged += converged;
      continue;
    }
    ++runs;
    seed_converged += converged;
    if (converged) densest = std::max(densest, p.fibre_volume_fraction);
    if (!converged) loosest_failure = std::min(loosest_failure, p.fibre_volume_fraction);
  }
  std::ostringstream out;
  out << "The seed's friction rule converged in " << seed_converged << " of " << runs
      << " compactions ([#tab:friction])";
  if (seed_converged > 0) out << ", up to $V_f = " << fixed3(densest) << "$";
  if (std::isfinite(loosest_failure))
    out << "; it failed from $V_f = " << fixed3(loosest_failure) << "$";
  out << ". The iterative solver's Coulomb friction converged in " << coulomb_converged << " of "
      << runs << ".";
  return out.str();
}

}  // namespace

void write_friction_section(ReportPage& page, const std::vector<FrictionPoint>& points) {
  if (points.empty()) return;
  page.section(
      "The seed's friction rule",
      "The seed's rule (§4.3.4, Eqs. 4.29–4.33) takes each contact's last resultant, splits it "
      "along the normal of the displaced centres and caps the tangential part at $\\mu N$. It is "
      "not Coulomb's law: a contact under a side load below $\\mu N$ does not stick, as the normal "
      "turns as soon as a fibre moves. Generated tows of each size are compacted in one step to "
      "each F and solved with it and with Coulomb friction; a run that does not converge is a "
      "result, not a failure of the study.");
  std::set<int> sizes;
  for (const FrictionPoint& p : points) sizes.insert(p.fibres);
  for (int fibres : sizes) outcome_figure(page, fibres, points);
  page.table(friction_table(pairs_of(points)));
  page.finding(friction_finding(points));
  std::vector<std::vector<std::string>> rows;
  for (const FrictionPoint& p : points)
    rows.push_back({count(p.fibres), cell(p.compaction), cell(p.fibre_volume_fraction), cell(p.mu),
                    p.model, p.status, p.criterion, count(p.iterations), cell(p.time_s),
                    cell(p.stick_residual), cell(p.pressure)});
  page.csv("friction",
           {"fibres", "compaction", "fibre_volume_fraction", "mu", "friction_model", "status",
            "criterion", "iterations", "time_s", "stick_residual_mm", "pressure_MPa"},
           rows);
}

}  // namespace fibrecheck
