#include "contact_problem.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.h"
#include "input_error.h"
#include "json_reader.h"

namespace fibrecheck {

using nlohmann::json;

namespace {

constexpr const char* kFormat = "fibrecheck-contact-problem";
constexpr int kVersion = 1;

json numbers(const Eigen::VectorXd& v) {
  return json(std::vector<double>(v.data(), v.data() + v.size()));
}

/// A JSON array of finite numbers of the given length (any length when `size` < 0).
Eigen::VectorXd read_numbers(ObjectReader& reader, const std::string& key, Eigen::Index size) {
  const json& values = reader.array(key);
  if (size >= 0 && static_cast<Eigen::Index>(values.size()) != size)
    reader.fail(reader.field(key), "must hold " + std::to_string(size) + " numbers, got " +
                                       std::to_string(values.size()));
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!values[i].is_number() || !std::isfinite(values[i].get<double>()))
      reader.fail(indexed(reader.field(key), i), "must be a finite number");
    v[static_cast<Eigen::Index>(i)] = values[i].get<double>();
  }
  return v;
}

}  // namespace

void set_offsets(ContactProblem& problem) {
  problem.offset.assign(problem.contacts.size() + 1, 0);
  for (std::size_t k = 0; k < problem.contacts.size(); ++k)
    problem.offset[k + 1] = problem.offset[k] + 1 + problem.contacts[k].tangents;
}

void write_contact_problem(const std::string& path, const ContactProblem& problem) {
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["scene"] = problem.scene;
  j["step"] = problem.step;
  j["mu"] = problem.mu;
  j["convention"] =
      "unknowns r per contact: normal force P (N), then the friction force along each tangent (N); "
      "w = q - W r per contact: the overlap left (mm, <= 0 when solved), then the slip left along "
      "each tangent (mm); Coulomb: P >= 0, P*w_n = 0, |F| <= mu*P, sticking w_t = 0, slipping "
      "|F| = mu*P and w_t = lambda*F with lambda >= 0; excluded contacts have r = 0";
  json contacts = json::array();
  for (const ProblemContact& c : problem.contacts)
    contacts.push_back({{"kind", c.kind},
                        {"fibres", c.fibres},
                        {"tangents", c.tangents},
                        {"excluded", c.excluded}});
  j["contacts"] = std::move(contacts);
  std::vector<long> rows, cols;
  std::vector<double> values;
  rows.reserve(problem.W.nonZeros());
  cols.reserve(problem.W.nonZeros());
  values.reserve(problem.W.nonZeros());
  for (int k = 0; k < problem.W.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(problem.W, k); it; ++it) {
      rows.push_back(static_cast<long>(it.row()));
      cols.push_back(static_cast<long>(it.col()));
      values.push_back(it.value());
    }
  j["W"] = {{"size", problem.W.rows()}, {"rows", rows}, {"cols", cols}, {"values", values}};
  j["q"] = numbers(problem.q);
  if (problem.reaction.size() > 0)
    j["reference"] = {{"reaction", numbers(problem.reaction)}, {"status", problem.status}};
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out.precision(17);
    out << j.dump() << "\n";
    if (!out) throw InputError(path, "", "could not be written");
  });
}

ContactProblem read_contact_problem(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot be opened");
  json j;
  try {
    in >> j;
  } catch (const json::parse_error& e) {
    throw InputError(path, "", std::string("is not JSON: ") + e.what());
  }
  ObjectReader top(j, "", path);
  if (top.string("format") != kFormat)
    top.fail("format", std::string("must be \"") + kFormat + "\"");
  if (top.integer("version", 0) != kVersion)
    top.fail("version", "must be " + std::to_string(kVersion));
  ContactProblem p;
  p.scene = top.string("scene", "");
  p.step = static_cast<int>(top.integer("step", 1));
  p.mu = top.number("mu");
  if (p.mu < 0.0) top.fail("mu", "must be at least 0");
  top.string("convention", "");
  const json& contacts = top.array("contacts");
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    ObjectReader c(contacts[k], indexed("contacts", k), path);
    ProblemContact contact;
    contact.kind = c.string("kind", "");
    if (c.has("fibres"))
      for (const json& name : c.array("fibres"))
        contact.fibres.push_back(name.is_string() ? name.get<std::string>() : name.dump());
    contact.tangents = static_cast<int>(c.integer("tangents", 0));
    if (contact.tangents < 0 || contact.tangents > 2)
      c.fail(c.field("tangents"), "must be 0, 1 or 2");
    if (contact.tangents > 0 && !(p.mu > 0.0))
      c.fail(c.field("tangents"), "must be 0 when mu is 0 (no friction, no tangents)");
    if (c.has("excluded")) {
      const json& e = c.at("excluded");
      if (!e.is_boolean()) c.fail(c.field("excluded"), "must be true or false");
      contact.excluded = e.get<bool>();
    }
    c.finish();
    p.contacts.push_back(std::move(contact));
  }
  set_offsets(p);
  const Eigen::Index n = p.offset.back();
  ObjectReader w(top.at("W"), "W", path);
  if (w.integer("size", -1) != n)
    w.fail("W.size", "must be " + std::to_string(n) + ", the unknowns of the contacts");
  const Eigen::VectorXd rows = read_numbers(w, "rows", -1);
  const Eigen::VectorXd cols = read_numbers(w, "cols", rows.size());
  const Eigen::VectorXd values = read_numbers(w, "values", rows.size());
  w.finish();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(rows.size()));
  for (Eigen::Index i = 0; i < rows.size(); ++i) {
    if (rows[i] < 0 || rows[i] >= n || cols[i] < 0 || cols[i] >= n ||
        rows[i] != std::floor(rows[i]) || cols[i] != std::floor(cols[i]))
      w.fail(indexed("W.rows", static_cast<std::size_t>(i)),
             "row and column must be whole numbers from 0 to " + std::to_string(n - 1));
    entries.emplace_back(static_cast<Eigen::Index>(rows[i]), static_cast<Eigen::Index>(cols[i]),
                         values[i]);
  }
  p.W.resize(n, n);
  p.W.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> transposed = p.W.transpose();
  // Symmetric to the round-off of the finite-element solves it comes from.
  const Eigen::SparseMatrix<double> difference = p.W - transposed;
  double asymmetry = 0.0, scale = 0.0;
  for (int k = 0; k < p.W.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.W, k); it; ++it)
      scale = std::max(scale, std::fabs(it.value()));
  for (int k = 0; k < difference.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(difference, k); it; ++it)
      asymmetry = std::max(asymmetry, std::fabs(it.value()));
  if (asymmetry > 1e-9 * scale) {
    std::ostringstream why;
    why << "must be symmetric (|W - W^T| reaches " << asymmetry / scale << " of its largest entry)";
    w.fail("W", why.str());
  }
  p.q = read_numbers(top, "q", n);
  if (top.has("reference")) {
    ObjectReader ref(top.at("reference"), "reference", path);
    p.reaction = read_numbers(ref, "reaction", n);
    p.status = ref.string("status", "");
    ref.finish();
  }
  top.finish();
  return p;
}

}  // namespace fibrecheck
