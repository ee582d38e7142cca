#include "result.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "atomic_file.h"
#include "input_error.h"

namespace fibrecheck {

using nlohmann::json;

namespace {

json vec(const Eigen::Vector3d& v) {
  return json::array({v[0], v[1], v[2]});
}

Eigen::Vector3d to_vec(const json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

}  // namespace

namespace {
constexpr std::pair<Status, const char*> kStatusNames[] = {
    {Status::converged, "converged"},
    {Status::max_iterations, "max_iterations"},
    {Status::diverged, "diverged"},
    {Status::unresolvable, "unresolvable"},
    {Status::beyond_reach, "beyond_reach"}};
constexpr std::pair<Criterion, const char*> kCriterionNames[] = {
    {Criterion::contact, "contact"},
    {Criterion::energy, "energy"},
    {Criterion::force, "force"},
    {Criterion::active_set, "active_set"},
    {Criterion::max_iterations, "max_iterations"},
    {Criterion::growth, "growth"},
    {Criterion::oscillation, "oscillation"},
    {Criterion::non_finite, "non_finite"},
    {Criterion::unresolvable, "unresolvable"},
    {Criterion::memory, "memory"}};

template <typename Enum, std::size_t N>
const char* name_of(Enum value, const std::pair<Enum, const char*> (&names)[N]) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return "?";
}

template <typename Enum, std::size_t N>
Enum parse_name(const std::string& text, const std::pair<Enum, const char*> (&names)[N],
                const std::string& source, const char* field) {
  std::string known;
  for (const auto& [v, name] : names) {
    if (text == name) return v;
    known += std::string(known.empty() ? "" : ", ") + name;
  }
  throw InputError(source, field, "\"" + text + "\" is none of " + known);
}
}  // namespace

const char* to_string(Status status) {
  return name_of(status, kStatusNames);
}

const char* to_string(Criterion criterion) {
  return name_of(criterion, kCriterionNames);
}

Status parse_status(const std::string& text, const std::string& source) {
  return parse_name(text, kStatusNames, source, "status");
}

Criterion parse_criterion(const std::string& text, const std::string& source) {
  return parse_name(text, kCriterionNames, source, "criterion");
}

bool replace_non_finite(Result& r) {
  bool found = false;
  auto scrub = [&found](double& x) {
    if (!std::isfinite(x)) x = 0.0, found = true;
  };
  auto scrub_vector = [&scrub](auto& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i) scrub(v[i]);
  };
  for (double* x :
       {&r.strain_energy, &r.strain_energy_exact, &r.max_overlap, &r.gap_force_residual, &r.c,
        &r.c_stable_limit, &r.axial_load_dropped, &r.max_deflection_over_radius, &r.max_slope,
        &r.wall_time_s, &r.deformed_test.gap_where_pushing, &r.deformed_test.overlap_where_free})
    scrub(*x);
  // An estimate that is not a number is no estimate: it is dropped, not set to zero.
  if (r.error_estimate &&
      !(std::isfinite(r.error_estimate->deflection) && std::isfinite(r.error_estimate->force) &&
        std::isfinite(r.error_estimate->energy)))
    r.error_estimate.reset();
  if (r.finite_elements) {
    scrub(r.finite_elements->complementarity_residual);
    scrub(r.finite_elements->strain_energy_elements);
    scrub(r.finite_elements->line_force_order);
    scrub(r.finite_elements->line_force_error_estimate);
  }
  if (r.friction)
    for (double* x :
         {&r.friction->stick_residual, &r.friction->slip_residual, &r.friction->cone_residual})
      scrub(*x);
  for (FibreResult& f : r.fibres) {
    for (Eigen::Vector3d& u : f.displacement) scrub_vector(u);
    for (Eigen::Vector2d& m : f.moment) scrub_vector(m);
  }
  for (ContactResult& c : r.contacts) {
    scrub(c.total_force);
    scrub(c.normal_force);
    scrub(c.friction_force);
    if (c.extrapolated_force) scrub(*c.extrapolated_force);
    for (ContactPoint& p : c.points) {
      scrub(p.position);
      scrub_vector(p.point);
      scrub_vector(p.force);
      scrub_vector(p.normal_force);
      scrub_vector(p.friction_force);
    }
  }
  for (WallResult& w : r.walls) {
    scrub(w.force);
    scrub(w.pressure);
    scrub(w.area);
  }
  for (HistoryEntry& h : r.history) {
    scrub(h.max_overlap);
    scrub(h.strain_energy);
  }
  if (found) {
    r.warnings.push_back("non-finite numbers in the result were replaced by zero");
    if (r.status == Status::converged) {
      r.status = Status::diverged;
      r.criterion = Criterion::non_finite;
      r.message =
          "the solution holds non-finite numbers (loads or stiffnesses beyond double "
          "precision?)" +
          (r.message.empty() ? std::string() : "; " + r.message);
    }
  }
  return found;
}

std::string brief_report(const Result& r) {
  std::ostringstream out;
  out.precision(4);
  out << "status " << to_string(r.status) << " (criterion " << to_string(r.criterion) << "), "
      << r.iterations << " iterations, " << r.wall_time_s << " s\n";
  out << "strain energy " << r.strain_energy << " N*mm (trapezium), " << r.strain_energy_exact
      << " N*mm (exact 1/2 sum P*v); max overlap " << r.max_overlap << " mm, gap-force residual "
      << r.gap_force_residual + 0.0 /* −0 printed as 0 */ << " mm; " << r.contacts.size()
      << " contact pairs";
  if (r.error_estimate)
    out << "\nestimated iteration error: deflection " << r.error_estimate->deflection << ", force "
        << r.error_estimate->force << ", energy " << r.error_estimate->energy << " (relative)";
  if (r.slicing_estimate)
    out << "\nestimated slicing error (" << r.slicing_estimate->slices << " against "
        << r.slicing_estimate->coarse_slices << " slices): deflection "
        << r.slicing_estimate->deflection << ", force " << r.slicing_estimate->force << ", energy "
        << r.slicing_estimate->energy << " (relative)";
  if (!r.message.empty()) out << "\n" << r.message;
  return out.str();
}

json result_to_json(const Result& r) {
  json j;
  j["scene"] = r.scene;
  j["solver"] = r.solver;
  j["rule"] = r.rule;
  j["status"] = to_string(r.status);
  j["criterion"] = to_string(r.criterion);
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["wall_time_s"] = r.wall_time_s;
  j["strain_energy"] = r.strain_energy;
  j["strain_energy_exact"] = r.strain_energy_exact;
  j["max_overlap"] = r.max_overlap;
  j["gap_force_residual"] = r.gap_force_residual;
  j["c"] = r.c;
  j["c_stable_limit"] = r.c_stable_limit;
  j["axial_load_dropped"] = r.axial_load_dropped;
  j["candidates"] = r.candidates;
  j["max_deflection_over_radius"] = r.max_deflection_over_radius;
  j["max_slope"] = r.max_slope;
  j["geometry"] = r.geometry;
  j["deformed_test"] = {{"gap_where_pushing", r.deformed_test.gap_where_pushing},
                        {"overlap_where_free", r.deformed_test.overlap_where_free}};
  j["geometric_updates"] = r.geometric_updates;
  j["exact_answers"] = r.exact_answers;
  if (r.error_estimate)
    j["error_estimate"] = {
        {"deflection", r.error_estimate->deflection}, {"force", r.error_estimate->force},
        {"energy", r.error_estimate->energy},         {"passes", r.error_estimate->passes},
        {"settled", r.error_estimate->settled},       {"wall_time_s", r.error_estimate->time_s}};
  if (r.slicing_estimate) {
    const SlicingEstimate& e = *r.slicing_estimate;
    j["slicing_error_estimate"] = {{"deflection", e.deflection},
                                   {"force", e.force},
                                   {"energy", e.energy},
                                   {"slices", e.slices},
                                   {"coarse_slices", e.coarse_slices},
                                   {"orders",
                                    {{"deflection", e.deflection_order},
                                     {"force", e.force_order},
                                     {"energy", e.energy_order}}},
                                   {"wall_time_s", e.time_s}};
    if (e.coarser_slices > 0) {
      auto number = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
      j["slicing_error_estimate"]["coarser_slices"] = e.coarser_slices;
      j["slicing_error_estimate"]["observed_orders"] = {
          {"deflection", number(e.observed_deflection_order)},
          {"force", number(e.observed_force_order)},
          {"energy", number(e.observed_energy_order)}};
    }
  }
  if (r.finite_elements) {
    j["complementarity_residual"] = r.finite_elements->complementarity_residual;
    j["active_set_iterations"] = r.finite_elements->active_set_iterations;
    j["unknowns"] = r.finite_elements->unknowns;
    j["strain_energy_elements"] = r.finite_elements->strain_energy_elements;
    if (r.finite_elements->line_force_error_estimate >= 0.0) {
      j["refinement"] = r.finite_elements->refinement;
      j["line_force_order"] = r.finite_elements->line_force_order;
      j["line_force_error_estimate"] = r.finite_elements->line_force_error_estimate;
    }
  }
  if (r.friction)
    j["friction"] = {{"model", r.friction->model},
                     {"mu", r.friction->mu},
                     {"stick_residual", r.friction->stick_residual},
                     {"slip_residual", r.friction->slip_residual},
                     {"cone_residual", r.friction->cone_residual},
                     {"sticking", r.friction->sticking},
                     {"slipping", r.friction->slipping},
                     {"fixed_point_updates", r.friction->fixed_point_updates}};
  j["stages"] = r.stages;
  j["warnings"] = r.warnings;
  j["fibres"] = json::array();
  for (const FibreResult& f : r.fibres) {
    json d = json::array();
    for (const Eigen::Vector3d& u : f.displacement) d.push_back(vec(u));
    json fibre = {{"id", f.id}, {"displacement", d}};
    if (!f.moment.empty()) {
      json m = json::array();
      for (const Eigen::Vector2d& M : f.moment) m.push_back(json::array({M[0], M[1]}));
      fibre["moment"] = m;
    }
    j["fibres"].push_back(std::move(fibre));
  }
  j["contacts"] = json::array();
  for (const ContactResult& c : r.contacts) {
    json points = json::array();
    for (const ContactPoint& p : c.points) {
      json point = {{"position", p.position},
                    {"point", vec(p.point)},
                    {"force", vec(p.force)},
                    {"normal_force", vec(p.normal_force)},
                    {"friction_force", vec(p.friction_force)}};
      if (!p.state.empty()) point["state"] = p.state;
      points.push_back(std::move(point));
    }
    json pair = {{"fibres", {c.fibres[0], c.fibres[1]}}, {"kind", c.kind},
                 {"total_force", c.total_force},         {"normal_force", c.normal_force},
                 {"friction_force", c.friction_force},   {"points", points}};
    if (c.extrapolated_force) pair["extrapolated_force"] = *c.extrapolated_force;
    j["contacts"].push_back(std::move(pair));
  }
  j["walls"] = json::array();
  for (const WallResult& w : r.walls)
    j["walls"].push_back(
        {{"id", w.id}, {"force", w.force}, {"pressure", w.pressure}, {"area", w.area}});
  j["history"] = json::array();
  for (const HistoryEntry& h : r.history)
    j["history"].push_back({{"iteration", h.iteration},
                            {"max_overlap", h.max_overlap},
                            {"strain_energy", h.strain_energy}});
  if (!r.steps.empty()) {
    j["steps"] = json::array();
    for (const StepResult& step : r.steps) {
      json pressure = json::object();
      for (const auto& [id, p] : step.wall_pressure) pressure[id] = p;
      j["steps"].push_back({{"compaction", step.compaction},
                            {"load_factor", step.load_factor},
                            {"fibre_volume_fraction", step.fibre_volume_fraction},
                            {"wall_pressure", pressure},
                            {"strain_energy", step.strain_energy},
                            {"contacts_per_fibre", step.contacts_per_fibre},
                            {"iterations", step.iterations},
                            {"geometric_updates", step.geometric_updates},
                            {"fixed_point_updates", step.fixed_point_updates},
                            {"stick_residual", step.stick_residual},
                            {"slip_residual", step.slip_residual},
                            {"wall_time_s", step.wall_time_s},
                            {"status", to_string(step.status)}});
    }
  }
  return j;
}

Result result_from_json(const json& j, const std::string& source) {
  try {
    Result r;
    r.scene = j.at("scene").get<std::string>();
    r.solver = j.value("solver", "");
    r.rule = j.value("rule", "");
    r.status = parse_status(j.at("status").get<std::string>(), source);
    r.criterion = parse_criterion(j.at("criterion").get<std::string>(), source);
    r.message = j.value("message", "");
    r.iterations = j.at("iterations").get<long>();
    r.wall_time_s = j.at("wall_time_s").get<double>();
    r.strain_energy = j.at("strain_energy").get<double>();
    r.strain_energy_exact = j.at("strain_energy_exact").get<double>();
    r.max_overlap = j.at("max_overlap").get<double>();
    r.gap_force_residual = j.value("gap_force_residual", 0.0);
    r.c = j.value("c", 0.0);
    r.c_stable_limit = j.value("c_stable_limit", 0.0);
    r.axial_load_dropped = j.value("axial_load_dropped", 0.0);
    r.candidates = j.value("candidates", 0L);
    r.max_deflection_over_radius = j.value("max_deflection_over_radius", 0.0);
    r.max_slope = j.value("max_slope", 0.0);
    r.geometry = j.value("geometry", std::string("linearised"));
    r.geometric_updates = j.value("geometric_updates", 0L);
    r.exact_answers = j.value("exact_answers", 0L);
    if (j.contains("deformed_test")) {
      r.deformed_test.gap_where_pushing = j["deformed_test"].value("gap_where_pushing", 0.0);
      r.deformed_test.overlap_where_free = j["deformed_test"].value("overlap_where_free", 0.0);
    }
    if (j.contains("error_estimate")) {
      const json& e = j["error_estimate"];
      ErrorEstimate& estimate = r.error_estimate.emplace();
      estimate.deflection = e.at("deflection").get<double>();
      estimate.force = e.at("force").get<double>();
      estimate.energy = e.at("energy").get<double>();
      estimate.passes = e.value("passes", 0);
      estimate.settled = e.value("settled", true);
      estimate.time_s = e.value("wall_time_s", 0.0);
    }
    if (j.contains("slicing_error_estimate")) {
      const json& e = j["slicing_error_estimate"];
      SlicingEstimate& estimate = r.slicing_estimate.emplace();
      estimate.deflection = e.at("deflection").get<double>();
      estimate.force = e.at("force").get<double>();
      estimate.energy = e.at("energy").get<double>();
      estimate.slices = e.value("slices", 0);
      estimate.coarse_slices = e.value("coarse_slices", 0);
      if (e.contains("orders")) {
        estimate.deflection_order = e["orders"].value("deflection", 0.0);
        estimate.force_order = e["orders"].value("force", 0.0);
        estimate.energy_order = e["orders"].value("energy", 0.0);
      }
      estimate.coarser_slices = e.value("coarser_slices", 0);
      if (e.contains("observed_orders")) {
        auto number = [](const json& x) { return x.is_number() ? x.get<double>() : NAN; };
        const json& o = e["observed_orders"];
        estimate.observed_deflection_order = number(o.value("deflection", json()));
        estimate.observed_force_order = number(o.value("force", json()));
        estimate.observed_energy_order = number(o.value("energy", json()));
      }
      estimate.time_s = e.value("wall_time_s", 0.0);
    }
    if (j.contains("unknowns")) {
      FiniteElementFigures& figures = r.finite_elements.emplace();
      figures.complementarity_residual = j.value("complementarity_residual", 0.0);
      figures.active_set_iterations = j.value("active_set_iterations", 0L);
      figures.unknowns = j.at("unknowns").get<long>();
      figures.strain_energy_elements = j.value("strain_energy_elements", 0.0);
      figures.refinement = j.value("refinement", 0);
      figures.line_force_order = j.value("line_force_order", 0.0);
      figures.line_force_error_estimate = j.value("line_force_error_estimate", -1.0);
    }
    if (j.contains("friction")) {
      const json& f = j.at("friction");
      FrictionFigures& figures = r.friction.emplace();
      figures.model = f.at("model").get<std::string>();
      figures.mu = f.at("mu").get<double>();
      figures.stick_residual = f.at("stick_residual").get<double>();
      figures.slip_residual = f.at("slip_residual").get<double>();
      figures.cone_residual = f.at("cone_residual").get<double>();
      figures.sticking = f.value("sticking", 0L);
      figures.slipping = f.value("slipping", 0L);
      figures.fixed_point_updates = f.value("fixed_point_updates", 0L);
    }
    r.stages = j.at("stages").get<std::vector<std::string>>();
    r.warnings = j.value("warnings", std::vector<std::string>{});
    for (const json& f : j.at("fibres")) {
      FibreResult fr;
      fr.id = f.at("id").get<std::string>();
      for (const json& u : f.at("displacement")) fr.displacement.push_back(to_vec(u));
      if (f.contains("moment"))
        for (const json& M : f.at("moment"))
          fr.moment.emplace_back(M.at(0).get<double>(), M.at(1).get<double>());
      r.fibres.push_back(std::move(fr));
    }
    for (const json& c : j.at("contacts")) {
      ContactResult cr;
      cr.fibres = {c.at("fibres").at(0).get<std::string>(),
                   c.at("fibres").at(1).get<std::string>()};
      cr.kind = c.at("kind").get<std::string>();
      cr.total_force = c.at("total_force").get<double>();
      cr.normal_force = c.value("normal_force", cr.total_force);
      cr.friction_force = c.value("friction_force", 0.0);
      if (c.contains("extrapolated_force"))
        cr.extrapolated_force = c.at("extrapolated_force").get<double>();
      for (const json& p : c.at("points")) {
        ContactPoint cp;
        cp.position = p.at("position").get<double>();
        if (p.contains("point")) cp.point = to_vec(p.at("point"));
        cp.force = to_vec(p.at("force"));
        cp.normal_force = p.contains("normal_force") ? to_vec(p.at("normal_force")) : cp.force;
        if (p.contains("friction_force")) cp.friction_force = to_vec(p.at("friction_force"));
        cp.state = p.value("state", std::string());
        cr.points.push_back(cp);
      }
      r.contacts.push_back(std::move(cr));
    }
    for (const json& w : j.at("walls"))
      r.walls.push_back({w.at("id").get<std::string>(), w.at("force").get<double>(),
                         w.value("pressure", 0.0), w.value("area", 0.0)});
    for (const json& h : j.at("history"))
      r.history.push_back({h.at("iteration").get<long>(), h.at("max_overlap").get<double>(),
                           h.at("strain_energy").get<double>()});
    if (j.contains("steps"))
      for (const json& e : j.at("steps")) {
        StepResult step;
        step.compaction = e.at("compaction").get<double>();
        step.load_factor = e.at("load_factor").get<double>();
        step.fibre_volume_fraction = e.at("fibre_volume_fraction").get<double>();
        for (auto it = e.at("wall_pressure").begin(); it != e.at("wall_pressure").end(); ++it)
          step.wall_pressure.emplace_back(it.key(), it.value().get<double>());
        step.strain_energy = e.at("strain_energy").get<double>();
        step.contacts_per_fibre = e.at("contacts_per_fibre").get<double>();
        step.iterations = e.at("iterations").get<long>();
        step.geometric_updates = e.value("geometric_updates", 0L);
        step.fixed_point_updates = e.value("fixed_point_updates", 0L);
        step.stick_residual = e.value("stick_residual", 0.0);
        step.slip_residual = e.value("slip_residual", 0.0);
        step.wall_time_s = e.at("wall_time_s").get<double>();
        step.status = parse_status(e.at("status").get<std::string>(), source);
        r.steps.push_back(std::move(step));
      }
    return r;
  } catch (const json::exception& e) {
    throw InputError(source, "", std::string("not a fibrecheck result: ") + e.what());
  }
}

Result read_result(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "no such file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  json document;
  try {
    document = json::parse(buffer.str());
  } catch (const json::parse_error& e) {
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
  return result_from_json(document, path);
}

void write_result(const std::string& path, const Result& result) {
  write_file_atomically(path, result_to_json(result).dump(1) + "\n");
}

}  // namespace fibrecheck
