#include "vtk_writer.h"

#include <sstream>

#include "atomic_file.h"

namespace fibrecheck {

namespace {

void write_vectors(std::ostringstream& out, const char* name,
                   const std::vector<Eigen::Vector3d>& values) {
  out << "        <DataArray type=\"Float64\" Name=\"" << name
      << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Eigen::Vector3d& v : values)
    out << "          " << v[0] << " " << v[1] << " " << v[2] << "\n";
  out << "        </DataArray>\n";
}

}  // namespace

void write_vtk(const std::string& path, const Scene& scene, const Result& result) {
  std::vector<Eigen::Vector3d> points, displacement, force;
  std::vector<double> radius;
  std::vector<std::pair<std::size_t, std::size_t>> lines;  // first point, count
  for (const FibreResult& fr : result.fibres) {
    const int f = scene.fibre_index(fr.id);
    if (f < 0) continue;
    const FibreSpec& spec = scene.fibres[f];
    const std::size_t n = fr.displacement.size();
    lines.emplace_back(points.size(), n);
    for (std::size_t j = 0; j < n; ++j) {
      const double s = n > 1 ? static_cast<double>(j) / (n - 1) : 0.0;
      points.push_back(spec.start + s * (spec.end - spec.start) + fr.displacement[j]);
      displacement.push_back(fr.displacement[j]);
      force.push_back(Eigen::Vector3d::Zero());
      radius.push_back(spec.radius);
    }
  }
  const std::size_t first_vertex = points.size();
  for (const ContactResult& c : result.contacts)
    for (const ContactPoint& p : c.points) {
      points.push_back(p.point);
      displacement.push_back(Eigen::Vector3d::Zero());
      force.push_back(p.force);
      radius.push_back(0.0);
    }
  const std::size_t vertices = points.size() - first_vertex;

  std::ostringstream out;
  out.precision(10);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << points.size() << "\" NumberOfVerts=\"" << vertices
      << "\" NumberOfLines=\"" << lines.size() << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "      <PointData Scalars=\"radius\" Vectors=\"displacement\">\n"
      << "        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n";
  for (double r : radius) out << "          " << r << "\n";
  out << "        </DataArray>\n";
  write_vectors(out, "displacement", displacement);
  write_vectors(out, "force", force);
  out << "      </PointData>\n      <Points>\n";
  write_vectors(out, "Points", points);
  out << "      </Points>\n      <Verts>\n"
         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t v = 0; v < vertices; ++v) out << "          " << first_vertex + v << "\n";
  out << "        </DataArray>\n"
         "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t v = 1; v <= vertices; ++v) out << "          " << v << "\n";
  out << "        </DataArray>\n      </Verts>\n      <Lines>\n"
         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& [start, count] : lines)
    for (std::size_t j = 0; j < count; ++j) out << "          " << start + j << "\n";
  out << "        </DataArray>\n"
         "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const auto& line : lines) out << "          " << (offset += line.second) << "\n";
  out << "        </DataArray>\n      </Lines>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomically(path, out.str());
}

}  // namespace fibrecheck
