#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace fibrecheck {

/// How finely the reference model meshes each fibre's chord.
struct MeshOptions {
  /// Element length as a fraction of the slice spacing (1: one element per slice interval).
  double size_per_slice = 1.0;
  /// Elements near a contact point are this many times smaller. The elements are exact at their
  /// nodes whatever their size, so a grading only serves pictures of the fields between them.
  double contact_refinement = 1.0;
  /// Further stations per fibre (fractions of its length), e.g. the contact points a solver found
  /// on the deformed fibres (refined like contacts) and the result's sample positions.
  std::vector<std::vector<double>> contact_stations, sample_stations;
  /// Which fibres to mesh (by index in the scene); empty: all of them.
  std::vector<char> fibres;
};

/// The points of one fibre where the mesh must have nodes (fractions of its length from start):
/// both supports, the slice positions, the wall stations, the point loads and the contact points;
/// `fine` marks the contact points, where the mesh is refined.
struct FibreStations {
  std::string id;
  std::vector<double> s;
  std::vector<char> fine;
  double element_length = 0.0;  ///< mm, away from contacts
};

/// Stations of every fibre of a scene, with the contact points of its undeformed state (found by
/// the iterative solver's detection, so both solvers see the same contacts).
std::vector<FibreStations> mesh_stations(const Scene& scene, const MeshOptions& options);

/// The elements write_mesh makes on the fibres `options.fibres` marks (all when it is empty), so
/// that the memory a mesh will take is known before it is made.
long mesh_elements(const Scene& scene, const MeshOptions& options);

/// Meshes every fibre's chord as a 1-D curve with Gmsh — nodes at every station, refined near
/// contacts — with physical groups named after the fibre ids (curves) and `<id>/start`,
/// `<id>/end` (supports), and writes it as a Gmsh .msh file (format 4.1).
void write_mesh(const Scene& scene, const MeshOptions& options, const std::string& path);

/// The same geometry as a Gmsh script (.geo) a user can open in Gmsh's GUI.
std::string geo_script(const Scene& scene, const MeshOptions& options);

}  // namespace fibrecheck
