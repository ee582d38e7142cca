#include "expected_outcome.h"

#include <cmath>
#include <sstream>

#include "json_reader.h"

namespace fibrecheck {

using nlohmann::json;

namespace {

const char* const kSolvers[] = {"iterative", "reference"};

std::map<std::string, std::string> per_solver(ObjectReader& parent, const std::string& key,
                                              const std::string& source, bool statuses) {
  std::map<std::string, std::string> values;
  if (!parent.has(key)) return values;
  ObjectReader r(parent.at(key), parent.field(key), source);
  for (const char* solver : kSolvers) {
    if (!r.has(solver)) continue;
    const std::string value = r.string(solver);
    if (statuses) {
      try {
        parse_status(value, source);
      } catch (const InputError&) {
        r.fail(r.field(solver), "\"" + value +
                                    "\" is none of converged, max_iterations, diverged, "
                                    "unresolvable, beyond_reach");
      }
    }
    values[solver] = value;
  }
  r.finish();
  return values;
}

double relative_tolerance(ObjectReader& r) {
  const double t = r.number("relative_tolerance", 1e-6);
  if (!(t > 0.0)) r.fail(r.field("relative_tolerance"), "must be positive");
  return t;
}

std::string sci(double x) {
  std::ostringstream out;
  out.precision(6);
  out << x;
  return out.str();
}

}  // namespace

ExpectedOutcome read_expected_outcome(const json& object, const std::string& source) {
  ExpectedOutcome e;
  ObjectReader top(object, "expected", source);
  e.closed_form = top.string("closed_form", "");
  e.status = per_solver(top, "status", source, true);
  e.message = per_solver(top, "message", source, false);
  e.warning = top.string("warning", "");
  if (top.has("forces")) {
    const json& list = top.array("forces");
    for (std::size_t i = 0; i < list.size(); ++i) {
      ObjectReader r(list[i], indexed(top.field("forces"), i), source);
      ExpectedOutcome::Force f;
      const json& ids = r.array("fibres");
      if (ids.size() != 2 || !ids[0].is_string() || !ids[1].is_string())
        r.fail(r.field("fibres"), "must be two ids");
      f.fibres = {ids[0].get<std::string>(), ids[1].get<std::string>()};
      f.total_force = r.number("total_force");
      if (f.total_force < 0.0) r.fail(r.field("total_force"), "must not be negative");
      f.relative_tolerance = relative_tolerance(r);
      r.finish();
      e.forces.push_back(f);
    }
  }
  if (top.has("deflections")) {
    const json& list = top.array("deflections");
    for (std::size_t i = 0; i < list.size(); ++i) {
      ObjectReader r(list[i], indexed(top.field("deflections"), i), source);
      ExpectedOutcome::Deflection d;
      d.fibre = r.string("fibre");
      d.position = r.number("position");
      if (d.position < 0.0 || d.position > 1.0) r.fail(r.field("position"), "must lie in [0, 1]");
      d.displacement = r.vector3("displacement");
      d.relative_tolerance = relative_tolerance(r);
      r.finish();
      e.deflections.push_back(d);
    }
  }
  top.finish();
  return e;
}

json to_json(const ExpectedOutcome& e) {
  json j = json::object();
  if (!e.closed_form.empty()) j["closed_form"] = e.closed_form;
  if (!e.status.empty()) j["status"] = e.status;
  if (!e.message.empty()) j["message"] = e.message;
  if (!e.warning.empty()) j["warning"] = e.warning;
  for (const ExpectedOutcome::Force& f : e.forces)
    j["forces"].push_back({{"fibres", {f.fibres[0], f.fibres[1]}},
                           {"total_force", f.total_force},
                           {"relative_tolerance", f.relative_tolerance}});
  for (const ExpectedOutcome::Deflection& d : e.deflections)
    j["deflections"].push_back(
        {{"fibre", d.fibre},
         {"position", d.position},
         {"displacement", {d.displacement.x(), d.displacement.y(), d.displacement.z()}},
         {"relative_tolerance", d.relative_tolerance}});
  return j;
}

std::string expected_status(const ExpectedOutcome& expected, const std::string& solver) {
  auto it = expected.status.find(solver);
  return it == expected.status.end() ? "converged" : it->second;
}

OutcomeCheck check_outcome(const ExpectedOutcome& e, const Result& r, const std::string& solver) {
  OutcomeCheck check;
  const std::string status = expected_status(e, solver);
  if (status != to_string(r.status)) {
    check.failures.push_back("status " + std::string(to_string(r.status)) + ", expected " + status +
                             (r.message.empty() ? "" : " (" + r.message + ")"));
    return check;
  }
  if (auto it = e.message.find(solver);
      it != e.message.end() && r.message.find(it->second) == std::string::npos)
    check.failures.push_back("the message does not say \"" + it->second + "\": " + r.message);
  if (!e.warning.empty()) {
    bool found = false;
    for (const std::string& w : r.warnings) found = found || w.find(e.warning) != std::string::npos;
    if (!found) check.failures.push_back("no warning says \"" + e.warning + "\"");
  }
  // The numbers of a run that did not converge mean nothing: only the status and message count.
  if (r.status != Status::converged) return check;
  double worst = e.forces.empty() && e.deflections.empty() ? NAN : 0.0;
  for (const ExpectedOutcome::Force& f : e.forces) {
    double force = 0.0;
    for (const ContactResult& c : r.contacts)
      if ((c.fibres[0] == f.fibres[0] && c.fibres[1] == f.fibres[1]) ||
          (c.fibres[0] == f.fibres[1] && c.fibres[1] == f.fibres[0]))
        force += c.total_force;
    const double error =
        f.total_force > 0.0 ? std::fabs(force - f.total_force) / f.total_force : std::fabs(force);
    worst = std::max(worst, error);
    if (!(error <= f.relative_tolerance))
      check.failures.push_back("force between " + f.fibres[0] + " and " + f.fibres[1] + " " +
                               sci(force) + " N, expected " + sci(f.total_force) + " N (error " +
                               sci(error) + ", tolerance " + sci(f.relative_tolerance) + ")");
  }
  for (const ExpectedOutcome::Deflection& d : e.deflections) {
    const FibreResult* fibre = nullptr;
    for (const FibreResult& f : r.fibres)
      if (f.id == d.fibre) fibre = &f;
    if (!fibre || fibre->displacement.size() < 2) {
      check.failures.push_back("no displacements of fibre " + d.fibre);
      continue;
    }
    const double at = d.position * static_cast<double>(fibre->displacement.size() - 1);
    const std::size_t j = static_cast<std::size_t>(std::lround(at));
    if (std::fabs(at - static_cast<double>(j)) > 1e-9) {
      check.failures.push_back("position " + sci(d.position) + " of fibre " + d.fibre +
                               " is not one of the result's samples");
      continue;
    }
    const double error =
        (fibre->displacement[j] - d.displacement).norm() / std::max(d.displacement.norm(), 1e-300);
    worst = std::max(worst, error);
    if (!(error <= d.relative_tolerance))
      check.failures.push_back("deflection of " + d.fibre + " at " + sci(d.position) + " off by " +
                               sci(error) + " (tolerance " + sci(d.relative_tolerance) + ")");
  }
  check.error = worst;
  return check;
}

}  // namespace fibrecheck
