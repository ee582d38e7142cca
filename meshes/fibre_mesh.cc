#include "fibre_mesh.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "atomic_file.h"
#include "contact_detection.h"
#include "fibre.h"

namespace fibrecheck {

namespace {

/// Sorted, de-duplicated stations; a contact station marks its neighbourhood fine.
void add_station(FibreStations& f, double s, bool fine) {
  f.s.push_back(std::min(1.0, std::max(0.0, s)));
  f.fine.push_back(fine ? 1 : 0);
}

void sort_unique(FibreStations& f) {
  std::vector<std::size_t> order(f.s.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return f.s[a] < f.s[b]; });
  std::vector<double> s;
  std::vector<char> fine;
  for (std::size_t i : order) {
    if (!s.empty() && f.s[i] - s.back() < 1e-9) {
      fine.back() = static_cast<char>(fine.back() | f.fine[i]);
      continue;
    }
    s.push_back(f.s[i]);
    fine.push_back(f.fine[i]);
  }
  f.s = std::move(s);
  f.fine = std::move(fine);
}

/// Characteristic length at each station: the element length, divided near contacts.
std::vector<double> station_sizes(const FibreStations& f, const MeshOptions& options) {
  std::vector<double> size(f.s.size(), f.element_length);
  for (std::size_t i = 0; i < f.s.size(); ++i)
    if (f.fine[i]) size[i] = f.element_length / options.contact_refinement;
  return size;
}

/// Elements on the interval between stations j and j + 1 of a fibre of length L: the smaller of
/// the two stations' sizes, evenly. (The elements are exact at their nodes whatever their size;
/// the grading only serves the output. Fixed counts spare Gmsh integrating a size field, which
/// cost it most of its time on large tows.)
int interval_elements(const FibreStations& f, const std::vector<double>& size, std::size_t j,
                      double L) {
  const double h = std::min(size[j], size[j + 1]);
  return std::max(1, static_cast<int>(std::ceil((f.s[j + 1] - f.s[j]) * L / h - 1e-9)));
}

}  // namespace

std::vector<FibreStations> mesh_stations(const Scene& scene, const MeshOptions& options) {
  const std::vector<Fibre> fibres = make_fibres(scene);
  const int n = scene.contact.slices;
  std::vector<FibreStations> stations(fibres.size());
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  for (std::size_t i = 0; i < fibres.size(); ++i) {
    FibreStations& f = stations[i];
    f.id = fibres[i].id;
    f.element_length = options.size_per_slice * fibres[i].length / n;
    add_station(f, 0.0, false);
    add_station(f, 1.0, false);
    if (!scene.walls.empty())
      for (int j = 0; j < n; ++j) add_station(f, (j + 0.5) / n, false);
    if (detector.slicing() && fibres[i].along_tow_axis) {
      const Eigen::Vector3d axis = scene.contact.axis.normalized();
      const double along = (fibres[i].end - fibres[i].start).dot(axis);
      for (int j = 0; j < detector.line_quadrature().size(); ++j) {
        const double s = (detector.slice_position(j) - fibres[i].start.dot(axis)) / along;
        if (s > 0.0 && s < 1.0) add_station(f, s, false);
      }
    }
  }
  for (const LoadSpec& load : scene.loads)
    if (load.kind == LoadKind::point)
      add_station(stations[scene.fibre_index(load.fibre)], load.position, false);
  std::vector<std::vector<Eigen::Vector3d>> undeformed(
      fibres.size(), std::vector<Eigen::Vector3d>(detector.grid().size(), Eigen::Vector3d::Zero()));
  for (const Contact& c : detector.detect(undeformed)) {
    if (c.kind != ContactKind::point) continue;  // slices and walls already have their stations
    add_station(stations[c.a], c.s_a, true);
    add_station(stations[c.b], c.s_b, true);
  }
  for (std::size_t i = 0; i < options.contact_stations.size() && i < stations.size(); ++i)
    for (double s : options.contact_stations[i]) add_station(stations[i], s, true);
  for (std::size_t i = 0; i < options.sample_stations.size() && i < stations.size(); ++i)
    for (double s : options.sample_stations[i]) add_station(stations[i], s, false);
  for (FibreStations& f : stations) sort_unique(f);
  return stations;
}

long mesh_elements(const Scene& scene, const MeshOptions& options) {
  const std::vector<FibreStations> stations = mesh_stations(scene, options);
  long elements = 0;
  for (std::size_t i = 0; i < scene.fibres.size(); ++i) {
    if (!options.fibres.empty() && !options.fibres[i]) continue;
    const FibreStations& f = stations[i];
    const std::vector<double> size = station_sizes(f, options);
    const double L = (scene.fibres[i].end - scene.fibres[i].start).norm();
    for (std::size_t j = 0; j + 1 < f.s.size(); ++j) elements += interval_elements(f, size, j, L);
  }
  return elements;
}

namespace {
void write_mesh_with_gmsh(const Scene& scene, const MeshOptions& options, const std::string& path) {
  const std::vector<FibreStations> stations = mesh_stations(scene, options);
  // Gmsh is started for this mesh and shut down however it ends.
  struct Session {
    Session() { gmsh::initialize(); }
    ~Session() { gmsh::finalize(); }
  } session;
  gmsh::option::setNumber("General.Terminal", 0);
  // Chords never share points: skip the search for duplicates, which grows with the model.
  gmsh::option::setNumber("Geometry.AutoCoherence", 0);
  // Straight lines with sizes at their ends: a coarse integration of the size field is exact
  // enough and far faster than the default.
  gmsh::option::setNumber("Mesh.LcIntegrationPrecision", 1e-3);
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::model::add(scene.name);
  // All curves first, one synchronisation, then the physical groups (synchronising per fibre
  // costs time quadratic in the number of fibres).
  std::vector<std::size_t> meshed;
  std::vector<std::vector<int>> points(scene.fibres.size()), lines(scene.fibres.size());
  for (std::size_t i = 0; i < scene.fibres.size(); ++i) {
    if (!options.fibres.empty() && !options.fibres[i]) continue;
    meshed.push_back(i);
    const FibreSpec& spec = scene.fibres[i];
    const FibreStations& f = stations[i];
    const std::vector<double> size = station_sizes(f, options);
    for (std::size_t j = 0; j < f.s.size(); ++j) {
      const Eigen::Vector3d x = spec.start + f.s[j] * (spec.end - spec.start);
      points[i].push_back(gmsh::model::geo::addPoint(x[0], x[1], x[2], size[j]));
    }
    const double L = (spec.end - spec.start).norm();
    for (std::size_t j = 0; j + 1 < points[i].size(); ++j) {
      lines[i].push_back(gmsh::model::geo::addLine(points[i][j], points[i][j + 1]));
      gmsh::model::geo::mesh::setTransfiniteCurve(lines[i].back(),
                                                  interval_elements(f, size, j, L) + 1);
    }
  }
  gmsh::model::geo::synchronize();
  // Explicit tags (fibre i: curve i + 1, supports 2i + 1 and 2i + 2): without one Gmsh looks for
  // the largest tag in use over every entity, for each group, which made the groups of a
  // 3 000-fibre tow take more than 15 minutes.
  for (std::size_t i : meshed) {
    const std::string& id = scene.fibres[i].id;
    const int tag = static_cast<int>(i);
    const int curve = gmsh::model::addPhysicalGroup(1, lines[i], tag + 1);
    gmsh::model::setPhysicalName(1, curve, id);
    const int start = gmsh::model::addPhysicalGroup(0, {points[i].front()}, 2 * tag + 1);
    gmsh::model::setPhysicalName(0, start, id + "/start");
    const int end = gmsh::model::addPhysicalGroup(0, {points[i].back()}, 2 * tag + 2);
    gmsh::model::setPhysicalName(0, end, id + "/end");
  }
  gmsh::model::mesh::generate(1);
  // An interrupted run never leaves half a mesh.
  write_atomically(path, [](const std::string& temporary) { gmsh::write(temporary); });
}
}  // namespace

void write_mesh(const Scene& scene, const MeshOptions& options, const std::string& path) {
  // Gmsh reports errors by throwing strings: turned into exceptions.
  try {
    write_mesh_with_gmsh(scene, options, path);
  } catch (const std::string& message) {
    throw std::runtime_error("Gmsh: " + message);
  }
}

std::string geo_script(const Scene& scene, const MeshOptions& options) {
  const std::vector<FibreStations> stations = mesh_stations(scene, options);
  std::ostringstream out;
  out.precision(17);
  out << "// " << scene.name << ": each fibre's chord with nodes at its supports, slices, loads\n"
      << "// and contact points" << (options.contact_refinement > 1.0 ? " (refined there)" : "")
      << ". Mesh with: gmsh -1 " << scene.name << ".geo\n";
  int point = 0, line = 0, group = 0;
  for (std::size_t i = 0; i < scene.fibres.size(); ++i) {
    const FibreSpec& spec = scene.fibres[i];
    const FibreStations& f = stations[i];
    const std::vector<double> size = station_sizes(f, options);
    const int first_point = point + 1, first_line = line + 1;
    out << "// fibre " << spec.id << "\n";
    for (std::size_t j = 0; j < f.s.size(); ++j) {
      const Eigen::Vector3d x = spec.start + f.s[j] * (spec.end - spec.start);
      out << "Point(" << ++point << ") = {" << x[0] << ", " << x[1] << ", " << x[2] << ", "
          << size[j] << "};\n";
    }
    const double L = (spec.end - spec.start).norm();
    for (int p = first_point; p < point; ++p) {
      out << "Line(" << ++line << ") = {" << p << ", " << p + 1 << "};\n";
      out << "Transfinite Curve {" << line
          << "} = " << interval_elements(f, size, static_cast<std::size_t>(p - first_point), L) + 1
          << ";\n";
    }
    out << "Physical Curve(\"" << spec.id << "\", " << ++group << ") = {";
    for (int l = first_line; l <= line; ++l) out << l << (l < line ? ", " : "");
    out << "};\n";
    out << "Physical Point(\"" << spec.id << "/start\", " << ++group << ") = {" << first_point
        << "};\n";
    out << "Physical Point(\"" << spec.id << "/end\", " << ++group << ") = {" << point << "};\n";
  }
  return out.str();
}

}  // namespace fibrecheck
