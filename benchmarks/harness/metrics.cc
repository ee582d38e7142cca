#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "input_error.h"
#include "json_number.h"

namespace fibrecheck {

namespace {

using PairKey = std::tuple<std::string, std::string, std::string>;

/// A pair's identity whichever way round its fibres are listed.
PairKey key_of(const ContactResult& c) {
  const bool flipped = c.kind != "wall" && c.fibres[1] < c.fibres[0];
  return flipped ? PairKey{c.kind, c.fibres[1], c.fibres[0]}
                 : PairKey{c.kind, c.fibres[0], c.fibres[1]};
}

/// The cumulative force magnitude along a line or wall pair: (position, sum so far). Positions are
/// fractions of the first fibre listed; the two fibres of a line contact are nearly parallel
/// members of one tow, whose fractions at one slice agree to the tow's misalignment.
std::vector<std::pair<double, double>> cumulative(const ContactResult& c) {
  std::vector<std::pair<double, double>> points;
  for (const ContactPoint& p : c.points) points.emplace_back(p.position, p.force.norm());
  std::sort(points.begin(), points.end());
  double sum = 0.0;
  for (auto& [s, f] : points) f = sum += f;
  return points;
}

double value_at(const std::vector<std::pair<double, double>>& curve, double s) {
  double value = 0.0;
  for (const auto& [position, sum] : curve) {
    if (position > s) break;
    value = sum;
  }
  return value;
}

double distribution_error(const ContactResult& run, const ContactResult& truth) {
  const auto a = cumulative(run), b = cumulative(truth);
  const double total = b.empty() ? 0.0 : b.back().second;
  if (!(total > 0.0)) return a.empty() ? 0.0 : 1.0;
  double worst = 0.0;
  for (const auto* curve : {&a, &b})
    for (const auto& [s, ignored] : *curve)
      worst = std::max(worst, std::fabs(value_at(a, s) - value_at(b, s)) / total);
  return worst;
}

}  // namespace

double Errors::worst() const {
  return std::max({deflection, force, energy});
}

double truth_force(const ContactResult& pair) {
  return pair.extrapolated_force ? *pair.extrapolated_force : pair.total_force;
}

ErrorReport measure_errors(const Result& run, const Result& truth, const std::string& what) {
  ErrorReport report;
  // Deflections, fibre by fibre.
  std::map<std::string, const FibreResult*> truth_fibres;
  double largest = 0.0;
  for (const FibreResult& f : truth.fibres) {
    truth_fibres[f.id] = &f;
    for (const Eigen::Vector3d& u : f.displacement) largest = std::max(largest, u.norm());
  }
  if (run.fibres.size() != truth.fibres.size())
    throw InputError(what, "fibres", "the two results hold different fibres");
  double deflection = 0.0;
  for (const FibreResult& f : run.fibres) {
    auto it = truth_fibres.find(f.id);
    if (it == truth_fibres.end())
      throw InputError(what, "fibres", "fibre " + f.id + " is in one result only");
    if (it->second->displacement.size() != f.displacement.size())
      throw InputError(what, "fibres", "fibre " + f.id + " has different sample counts");
    for (std::size_t j = 0; j < f.displacement.size(); ++j)
      deflection = std::max(deflection, (f.displacement[j] - it->second->displacement[j]).norm());
  }
  report.errors.deflection = largest > 0.0 ? deflection / largest : deflection > 0.0 ? 1.0 : 0.0;

  // Contact pairs: every pair of either side.
  struct Sides {
    const ContactResult* run = nullptr;
    const ContactResult* truth = nullptr;
  };
  std::map<PairKey, Sides> pairs;
  std::vector<PairKey> order;
  auto add = [&](const ContactResult& c, bool is_run) {
    const PairKey key = key_of(c);
    auto [it, inserted] = pairs.try_emplace(key);
    if (inserted) order.push_back(key);
    (is_run ? it->second.run : it->second.truth) = &c;
  };
  for (const ContactResult& c : truth.contacts) add(c, false);
  for (const ContactResult& c : run.contacts) add(c, true);
  double strongest = 0.0;
  for (const ContactResult& c : truth.contacts) strongest = std::max(strongest, truth_force(c));
  for (const PairKey& key : order) {
    const Sides& sides = pairs[key];
    PairError row;
    row.kind = std::get<0>(key);
    row.fibres = {std::get<1>(key), std::get<2>(key)};
    row.force_run = sides.run ? sides.run->total_force : 0.0;
    row.force_truth = sides.truth ? truth_force(*sides.truth) : 0.0;
    const double scale =
        row.force_truth > 1e-9 * strongest ? row.force_truth : std::max(strongest, 1e-300);
    row.error = std::fabs(row.force_run - row.force_truth) / scale;
    if (row.kind != "point") {
      static const ContactResult none;
      row.distribution_error =
          distribution_error(sides.run ? *sides.run : none, sides.truth ? *sides.truth : none);
    }
    report.errors.force = std::max(report.errors.force, row.error);
    report.pairs.push_back(row);
  }
  const double U = truth.strain_energy_exact;
  report.errors.energy = U != 0.0 ? std::fabs(run.strain_energy_exact - U) / std::fabs(U)
                         : std::fabs(run.strain_energy_exact) > 0.0 ? 1.0
                                                                    : 0.0;
  return report;
}

Errors estimated_errors(const Result& run) {
  if (!run.error_estimate) return {NAN, NAN, NAN};
  return {run.error_estimate->deflection, run.error_estimate->force, run.error_estimate->energy};
}

Errors effectivity(const Errors& estimate, const Errors& truth, const Errors& floor) {
  auto index = [](double e, double t, double f) { return t > f ? e / t : NAN; };
  return {index(estimate.deflection, truth.deflection, floor.deflection),
          index(estimate.force, truth.force, floor.force),
          index(estimate.energy, truth.energy, floor.energy)};
}

Errors measurable_above(const Errors& agreement) {
  auto floor = [](double a) { return std::max(1e-10, 3.0 * a); };
  return {floor(agreement.deflection), floor(agreement.force), floor(agreement.energy)};
}

Errors effectivity(const Errors& estimate, const Errors& truth, double floor) {
  auto index = [floor](double e, double t) { return t > floor ? e / t : NAN; };
  return {index(estimate.deflection, truth.deflection), index(estimate.force, truth.force),
          index(estimate.energy, truth.energy)};
}

double observed_order(const std::vector<double>& n, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (std::size_t i = 0; i < n.size() && i < error.size(); ++i) {
    if (!(error[i] > 0.0) || !(n[i] > 0.0) || !std::isfinite(error[i])) continue;
    const double x = std::log(n[i]), y = std::log(error[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
  }
  if (m < 2) return NAN;
  const double denominator = m * sxx - sx * sx;
  if (!(std::fabs(denominator) > 0.0)) return NAN;
  return -(m * sxy - sx * sy) / denominator;
}

nlohmann::json to_json(const Errors& e) {
  return {{"deflection_error", number_or_null(e.deflection)},
          {"force_error", number_or_null(e.force)},
          {"energy_error", number_or_null(e.energy)}};
}

void from_json(const nlohmann::json& j, Errors& e) {
  e.deflection = number_at(j, "deflection_error");
  e.force = number_at(j, "force_error");
  e.energy = number_at(j, "energy_error");
}

nlohmann::json to_json(const PairError& p) {
  nlohmann::json j = {{"kind", p.kind},
                      {"fibres", {p.fibres[0], p.fibres[1]}},
                      {"force_run", p.force_run},
                      {"force_truth", p.force_truth},
                      {"error", p.error}};
  if (p.distribution_error >= 0.0) j["distribution_error"] = p.distribution_error;
  return j;
}

void from_json(const nlohmann::json& j, PairError& p) {
  p.kind = j.at("kind");
  p.fibres = {j.at("fibres").at(0).get<std::string>(), j.at("fibres").at(1).get<std::string>()};
  p.force_run = j.at("force_run");
  p.force_truth = j.at("force_truth");
  p.error = j.at("error");
  p.distribution_error = j.value("distribution_error", -1.0);
}

}  // namespace fibrecheck
