#include "scene.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "atomic_file.h"
#include "expected_outcome.h"
#include "input_error.h"
#include "json_reader.h"

namespace fibrecheck {

using nlohmann::json;

namespace {

void require_positive(ObjectReader& reader, const std::string& key, double value) {
  if (!(value > 0.0)) reader.fail(reader.field(key), "must be positive, got " + json(value).dump());
}

FibreSpec read_fibre(const json& node, const std::string& path, const std::string& file) {
  ObjectReader r(node, path, file);
  FibreSpec f;
  f.id = r.string("id");
  if (f.id.empty()) r.fail(r.field("id"), "must not be empty");
  f.start = r.vector3("start");
  f.end = r.vector3("end");
  f.radius = r.number("radius");
  require_positive(r, "radius", f.radius);
  f.youngs_modulus = r.number("youngs_modulus");
  require_positive(r, "youngs_modulus", f.youngs_modulus);
  const double scale = std::max({f.start.norm(), f.end.norm(), f.radius});
  const double length = (f.end - f.start).norm();
  if (length <= 1e-12 * scale) r.fail(r.field("end"), "zero-length fibre: end equals start");
  // The beam formulas divide by E·I and multiply by L³: both must stay ordinary numbers.
  const double EI = f.youngs_modulus * M_PI * std::pow(f.radius, 4) / 4.0;
  const double compliance = std::pow(length, 3) / (48.0 * EI);
  if (!std::isnormal(EI) || !std::isnormal(compliance)) {
    std::ostringstream out;
    out << "with youngs_modulus " << f.youngs_modulus << " and length " << length
        << " the bending stiffness E*pi*r^4/4 = " << EI
        << " N*mm^2 and the compliance L^3/(48EI) = " << compliance
        << " mm/N leave the range of double precision";
    r.fail(r.field("radius"), out.str());
  }
  r.finish();
  return f;
}

LoadSpec read_load(const json& node, const std::string& path, const std::string& file) {
  ObjectReader r(node, path, file);
  LoadSpec load;
  load.fibre = r.string("fibre");
  const std::string kind = r.string("kind", "point");
  if (kind == "point") {
    load.kind = LoadKind::point;
    load.position = r.number("position", 0.5);
    if (load.position < 0.0 || load.position > 1.0)
      r.fail(r.field("position"), "must lie in [0, 1] (fraction of the fibre's length), got " +
                                      json(load.position).dump());
    load.force = r.vector3("force");
  } else if (kind == "distributed") {
    load.kind = LoadKind::distributed;
    load.force = r.vector3("force_per_length");
  } else {
    r.fail(r.field("kind"), "must be \"point\" or \"distributed\", got \"" + kind + "\"");
  }
  r.finish();
  return load;
}

WallSpec read_wall(const json& node, const std::string& path, const std::string& file) {
  ObjectReader r(node, path, file);
  WallSpec wall;
  wall.id = r.string("id");
  if (wall.id.empty()) r.fail(r.field("id"), "must not be empty");
  wall.point = r.vector3("point");
  wall.normal = r.vector3("normal");
  if (!(wall.normal.norm() > 0.0)) r.fail(r.field("normal"), "must not be the zero vector");
  wall.normal.normalize();
  r.finish();
  return wall;
}

}  // namespace

int Scene::fibre_index(const std::string& id) const {
  for (std::size_t i = 0; i < fibres.size(); ++i)
    if (fibres[i].id == id) return static_cast<int>(i);
  return -1;
}

double Scene::overlap_tolerance() const {
  if (solver.overlap_tolerance) return *solver.overlap_tolerance;
  double smallest = std::numeric_limits<double>::infinity();
  for (const FibreSpec& f : fibres) smallest = std::min(smallest, f.radius);
  return std::isfinite(smallest) ? 1e-5 * smallest : 1e-7;
}

const char* to_string(ContactGeometryModel model) {
  return model == ContactGeometryModel::deformed ? "deformed" : "linearised";
}

const char* to_string(FrictionModel model) {
  return model == FrictionModel::seed ? "seed" : "coulomb";
}

const char* to_string(LoadKind kind) {
  return kind == LoadKind::point ? "point" : "distributed";
}

Scene scene_from_json(const json& document, const std::string& source) {
  Scene scene;
  scene.source = source;
  ObjectReader top(document, "", source);
  scene.name = top.string("name", std::filesystem::path(source).stem().string());
  top.string("description", "");
  if (top.has("generator") && !top.at("generator").is_object())
    top.fail("generator", "must be a JSON object");
  if (top.has("expected")) scene.expected = read_expected_outcome(top.at("expected"), source);

  const json& fibres = top.array("fibres");
  if (fibres.empty()) top.fail("fibres", "must list at least one fibre");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < fibres.size(); ++i) {
    scene.fibres.push_back(read_fibre(fibres[i], indexed("fibres", i), source));
    if (!ids.insert(scene.fibres.back().id).second)
      throw InputError(source, indexed("fibres", i) + ".id",
                       "duplicate fibre id \"" + scene.fibres.back().id + "\"");
  }

  if (top.has("loads")) {
    const json& loads = top.array("loads");
    for (std::size_t i = 0; i < loads.size(); ++i) {
      scene.loads.push_back(read_load(loads[i], indexed("loads", i), source));
      if (!ids.count(scene.loads.back().fibre))
        throw InputError(source, indexed("loads", i) + ".fibre",
                         "no fibre with id \"" + scene.loads.back().fibre + "\"");
    }
  }

  if (top.has("walls")) {
    const json& walls = top.array("walls");
    std::set<std::string> wall_ids;
    for (std::size_t i = 0; i < walls.size(); ++i) {
      scene.walls.push_back(read_wall(walls[i], indexed("walls", i), source));
      const std::string& id = scene.walls.back().id;
      if (ids.count(id) || !wall_ids.insert(id).second)
        throw InputError(source, indexed("walls", i) + ".id",
                         "duplicate id \"" + id + "\" (wall and fibre ids must all differ)");
    }
  }

  if (top.has("contact")) {
    ObjectReader r(top.at("contact"), "contact", source);
    ContactSettings& c = scene.contact;
    const long slices = r.integer("slices", c.slices);
    if (slices < 1 || slices > 1000000)
      r.fail(r.field("slices"),
             "must be a whole number from 1 to 1000000, got " + std::to_string(slices));
    c.slices = static_cast<int>(slices);
    c.axis = r.vector3("axis", c.axis);
    if (!(c.axis.norm() > 0.0)) r.fail(r.field("axis"), "must not be the zero vector");
    c.axis.normalize();
    c.friction = r.number("friction", c.friction);
    if (c.friction < 0.0) r.fail(r.field("friction"), "must not be negative");
    if (r.has("friction_model")) {
      const std::string model = r.string("friction_model");
      if (model == "coulomb")
        c.friction_model = FrictionModel::coulomb;
      else if (model == "seed")
        c.friction_model = FrictionModel::seed;
      else
        r.fail(r.field("friction_model"), "must be \"coulomb\" or \"seed\", got \"" + model + "\"");
    }
    if (r.has("geometry")) {
      const std::string model = r.string("geometry");
      if (model == "deformed")
        c.geometry = ContactGeometryModel::deformed;
      else if (model == "linearised")
        c.geometry = ContactGeometryModel::linearised;
      else
        r.fail(r.field("geometry"),
               "must be \"deformed\" or \"linearised\", got \"" + model + "\"");
    }
    c.parallel_angle_deg = r.number("parallel_angle_deg", c.parallel_angle_deg);
    if (!(c.parallel_angle_deg > 0.0 && c.parallel_angle_deg < 90.0))
      r.fail(r.field("parallel_angle_deg"), "must lie in (0, 90) degrees");
    r.finish();
  }

  if (top.has("solver")) {
    ObjectReader r(top.at("solver"), "solver", source);
    SolverSettings& s = scene.solver;
    if (r.has("rule")) s.rule = parse_update_rule(r.string("rule"), source, r.field("rule"));
    if (r.has("c")) {
      s.c = r.number("c");
      require_positive(r, "c", *s.c);
    }
    if (r.has("overlap_tolerance")) {
      s.overlap_tolerance = r.number("overlap_tolerance");
      require_positive(r, "overlap_tolerance", *s.overlap_tolerance);
    }
    s.energy_tolerance = r.number("energy_tolerance", s.energy_tolerance);
    if (s.energy_tolerance < 0.0) r.fail(r.field("energy_tolerance"), "must not be negative");
    s.force_tolerance = r.number("force_tolerance", s.force_tolerance);
    if (!(s.force_tolerance >= 0.0 && s.force_tolerance < 1.0))
      r.fail(r.field("force_tolerance"), "must lie in [0, 1) (a relative force error)");
    const long window = r.integer("energy_window", s.energy_window);
    if (window < 1 || window > 1000000)
      r.fail(r.field("energy_window"), "must be a whole number from 1 to 1000000");
    s.energy_window = static_cast<int>(window);
    s.max_iterations = r.integer("max_iterations", s.max_iterations);
    if (s.max_iterations < 1) r.fail(r.field("max_iterations"), "must be at least 1");
    r.finish();
  }

  if (top.has("steps")) {
    const json& steps = top.array("steps");
    for (std::size_t i = 0; i < steps.size(); ++i) {
      ObjectReader r(steps[i], indexed("steps", i), source);
      LoadStep step;
      step.compaction = r.number("compaction", step.compaction);
      if (!(step.compaction > 0.0 && step.compaction <= 1.0))
        r.fail(r.field("compaction"), "must lie in (0, 1] (the cross-section scale factor F)");
      step.load_factor = r.number("load_factor", step.load_factor);
      r.finish();
      scene.steps.push_back(step);
    }
  }

  if (top.has("output")) {
    ObjectReader r(top.at("output"), "output", source);
    const long samples = r.integer("samples", scene.output.samples);
    if (samples < 2 || samples > 1000000)
      r.fail(r.field("samples"), "must be a whole number from 2 to 1000000");
    scene.output.samples = static_cast<int>(samples);
    r.finish();
  }
  top.finish();
  validate_scene(scene);
  return scene;
}

void validate_scene(const Scene& scene) {
  const std::string& file = scene.source;
  if (scene.solver.rule == UpdateRule::seed && !scene.solver.c)
    throw InputError(file, "solver.c", "is required by rule \"seed\" (the step c of P' = P + c·d)");
  if (scene.solver.rule == UpdateRule::conjugate_gradient && scene.contact.friction > 0.0)
    throw InputError(file, "solver.rule",
                     "rule \"cg\" solves frictionless contact only; with contact.friction use "
                     "\"accelerated\"");
  if (scene.contact.slices < 1) throw InputError(file, "contact.slices", "must be at least 1");
  if (scene.solver.c && !(*scene.solver.c > 0.0 && std::isfinite(*scene.solver.c)))
    throw InputError(file, "solver.c", "must be a positive finite number");
  if (scene.solver.max_iterations < 1)
    throw InputError(file, "solver.max_iterations", "must be at least 1");
}

namespace {

/// Follows where the parser is (`fibres[1].radius`) so that a syntax error or an overflowing
/// number can be reported with its field.
class ParsePath {
 public:
  struct DuplicateKey {};
  bool on_event(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        count_element();
        frames_.push_back({event == json::parse_event_t::array_start, -1, "", {}});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
      case json::parse_event_t::key:
        if (!frames_.empty()) {
          frames_.back().key = parsed.get<std::string>();
          // JSON leaves duplicates to the reader; one of two values would silently win here.
          if (!frames_.back().keys.insert(frames_.back().key).second) throw DuplicateKey{};
        }
        break;
      case json::parse_event_t::value:
        count_element();
        break;
    }
    return true;
  }

  std::string str() const {
    std::string path;
    for (const Frame& f : frames_) {
      if (f.array) {
        if (f.index >= 0) path += "[" + std::to_string(f.index) + "]";
      } else if (!f.key.empty()) {
        path += (path.empty() ? "" : ".") + f.key;
      }
    }
    return path;
  }

 private:
  struct Frame {
    bool array;
    int index;
    std::string key;
    std::set<std::string> keys;  ///< of an object, seen so far
  };
  void count_element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::vector<Frame> frames_;
};

}  // namespace

std::vector<Scene> read_scenes(const std::vector<std::string>& paths) {
  std::vector<Scene> scenes;
  for (const std::string& path : paths) {
    scenes.push_back(read_scene(path));
    validate_scene(scenes.back());
  }
  return scenes;
}

Scene read_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path)) {
    const bool exists = std::filesystem::exists(path);
    throw InputError(path, "", exists ? "cannot be read" : "no such file");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  json document;
  ParsePath where;
  try {
    document =
        json::parse(buffer.str(), [&where](int depth, json::parse_event_t event, json& parsed) {
          return where.on_event(depth, event, parsed);
        });
  } catch (const ParsePath::DuplicateKey&) {
    throw InputError(path, where.str(), "duplicate key (JSON would keep only one of the two)");
  } catch (const json::exception& e) {
    std::string reason = e.what();
    const auto bracket = reason.find("] ");
    if (bracket != std::string::npos) reason = reason.substr(bracket + 2);
    throw InputError(path, where.str(), "malformed JSON (" + reason + ")");
  }
  return scene_from_json(document, path);
}

namespace {
json vec(const Eigen::Vector3d& v) {
  return json::array({v[0], v[1], v[2]});
}
}  // namespace

json scene_to_json(const Scene& scene) {
  json j;
  j["name"] = scene.name;
  j["fibres"] = json::array();
  for (const FibreSpec& f : scene.fibres)
    j["fibres"].push_back({{"id", f.id},
                           {"start", vec(f.start)},
                           {"end", vec(f.end)},
                           {"radius", f.radius},
                           {"youngs_modulus", f.youngs_modulus}});
  j["loads"] = json::array();
  for (const LoadSpec& l : scene.loads) {
    json load = {{"fibre", l.fibre}, {"kind", to_string(l.kind)}};
    if (l.kind == LoadKind::point) {
      load["position"] = l.position;
      load["force"] = vec(l.force);
    } else {
      load["force_per_length"] = vec(l.force);
    }
    j["loads"].push_back(load);
  }
  j["walls"] = json::array();
  for (const WallSpec& w : scene.walls)
    j["walls"].push_back({{"id", w.id}, {"point", vec(w.point)}, {"normal", vec(w.normal)}});
  j["contact"] = {{"slices", scene.contact.slices},
                  {"axis", vec(scene.contact.axis)},
                  {"friction", scene.contact.friction},
                  {"friction_model", to_string(scene.contact.friction_model)},
                  {"geometry", to_string(scene.contact.geometry)},
                  {"parallel_angle_deg", scene.contact.parallel_angle_deg}};
  j["solver"] = {
      {"rule", to_string(scene.solver.rule)},
      {"c", scene.solver.c ? json(*scene.solver.c) : json(nullptr)},
      {"overlap_tolerance",
       scene.solver.overlap_tolerance ? json(*scene.solver.overlap_tolerance) : json(nullptr)},
      {"energy_tolerance", scene.solver.energy_tolerance},
      {"energy_window", scene.solver.energy_window},
      {"force_tolerance", scene.solver.force_tolerance},
      {"max_iterations", scene.solver.max_iterations}};
  j["output"] = {{"samples", scene.output.samples}};
  if (!scene.steps.empty()) {
    j["steps"] = json::array();
    for (const LoadStep& step : scene.steps)
      j["steps"].push_back({{"compaction", step.compaction}, {"load_factor", step.load_factor}});
  }
  if (scene.expected) j["expected"] = to_json(*scene.expected);
  return j;
}

void write_scene(const std::string& path, const Scene& scene) {
  write_file_atomically(path, scene_to_json(scene).dump(2) + "\n");
}

std::string scene_format_help() {
  // The defaults are read from a default-constructed Scene, so they cannot drift from the parser.
  const Scene d;
  std::ostringstream out;
  auto vec3 = [](const Eigen::Vector3d& v) {
    std::ostringstream s;
    s << "[" << v[0] << "," << v[1] << "," << v[2] << "]";
    return s.str();
  };
  out << "Scene file (JSON). Units are consistent; the defaults assume mm, N, MPa.\n"
         "Unknown keys are errors. Every field but `fibres` has a default.\n\n"
         "  name                          string   default: the file name\n"
         "  description                   string   free text, ignored by the solvers\n"
         "  fibres[]                      required, at least one\n"
         "    id                          string, unique\n"
         "    start, end                  [x,y,z] mm, the two pinned supports\n"
         "    radius                      mm, > 0\n"
         "    youngs_modulus              MPa, > 0\n"
         "  loads[]                       default: none\n"
         "    fibre                       id of a fibre\n"
         "    kind                        \"point\" | \"distributed\"   default: \"point\"\n"
         "    position                    fraction of length from start, [0,1]   default: 0.5\n"
         "    force                       [Fx,Fy,Fz] N (point loads)\n"
         "    force_per_length            [qx,qy,qz] N/mm (distributed, uniform)\n"
         "  walls[]                       rigid planes, default: none\n"
         "    id                          string, unique\n"
         "    point, normal               [x,y,z]; fibres stay on the side the normal points to\n"
         "  contact\n"
         "    slices                      cross-sections n   default: "
      << d.contact.slices
      << "\n"
         "    axis                        tow axis   default: "
      << vec3(d.contact.axis)
      << "\n"
         "    friction                    Coulomb coefficient mu   default: "
      << d.contact.friction
      << "\n"
         "    friction_model              \"coulomb\" (stick/slip per load step) | \"seed\"\n"
         "                                (Eqs. 4.29-4.33 on the deformed centres)   default: \""
      << to_string(d.contact.friction_model)
      << "\"\n"
         "    geometry                    \"deformed\" (gap and normal from the displaced "
         "centres,\n"
         "                                Eqs. 4.14-4.15) | \"linearised\" (undeformed place and\n"
         "                                normal, small deflections)   default: \""
      << to_string(d.contact.geometry)
      << "\"\n"
         "    parallel_angle_deg          fibres within this angle of the axis are sliced as\n"
         "                                line contacts   default: "
      << d.contact.parallel_angle_deg
      << "\n"
         "  solver\n"
         "    rule                        the force update, default: \""
      << to_string(d.solver.rule) << "\"\n";
  for (const UpdateRuleName& r : update_rules())
    out << "                                  \"" << r.name << "\": " << r.summary << "\n";
  out << ""
         "    c                           N/mm, step of P' = P + c*d (rule seed; per slice it is\n"
         "                                c/n, Eq. 4.28)   default: null\n"
         "    overlap_tolerance           t_d, mm   default: null = 1e-5 x smallest radius\n"
         "    energy_tolerance            t_U, N*mm, 0 = energy criterion off   default: "
      << d.solver.energy_tolerance
      << "\n"
         "    energy_window               n_i iterations   default: "
      << d.solver.energy_window
      << "\n"
         "    force_tolerance             relative force error the run must reach by its own\n"
         "                                estimate (criterion force), 0 = the seed's criteria\n"
         "                                alone   default: "
      << d.solver.force_tolerance
      << "\n"
         "    max_iterations              default: "
      << d.solver.max_iterations
      << "\n"
         "  output\n"
         "    samples                     displacement samples per fibre   default: "
      << d.output.samples
      << "\n"
         "  steps[]                       a load path, default: none (one step)\n"
         "    compaction                  factor F in (0, 1] on the cross-section about the\n"
         "                                tow's centre (supports and walls too)   default: 1\n"
         "    load_factor                 factor on every load   default: 1\n"
         "  expected                      optional, never read by the solvers: what the scene\n"
         "                                must give (status per solver, closed-form forces and\n"
         "                                deflections with tolerances), judged by the tests and\n"
         "                                the stability study; see scenes/extreme/\n";
  return out.str();
}

}  // namespace fibrecheck
