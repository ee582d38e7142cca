// Gmsh meshes of the scenes: nodes at every station (supports, slices, loads, contacts), elements
// no longer than asked and refined at contacts, physical groups named after the fibres, and a .geo
// script that Gmsh meshes to the same nodes.
#include "fibre_mesh.h"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <fstream>

#include "atomic_file.h"

namespace fibrecheck {
namespace {

struct MeshedFibre {
  std::vector<Eigen::Vector3d> nodes;
  double longest = 0.0;
};

/// Reads a mesh back through Gmsh: the nodes and the longest element of each named fibre.
std::map<std::string, MeshedFibre> read_back(const std::string& path, bool from_geo) {
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(path);
  if (from_geo) gmsh::model::mesh::generate(1);
  std::map<std::string, MeshedFibre> fibres;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 1);
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    std::vector<std::size_t> tags;
    std::vector<double> xyz;
    gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, tags, xyz);
    MeshedFibre& f = fibres[name];
    for (std::size_t i = 0; i < tags.size(); ++i)
      f.nodes.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    for (int e : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> elements, element_nodes;
      gmsh::model::mesh::getElements(types, elements, element_nodes, dim, e);
      for (const auto& nodes : element_nodes)
        for (std::size_t k = 0; k + 1 < nodes.size(); k += 2) {
          std::vector<double> a, b, p;
          gmsh::model::mesh::getNode(nodes[k], a, p);
          gmsh::model::mesh::getNode(nodes[k + 1], b, p);
          f.longest = std::max(f.longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
        }
    }
  }
  gmsh::finalize();
  return fibres;
}

class FibreMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(FibreMesh, NodesAtEveryStationAndGroupsNamedAfterFibres) {
  const Scene scene = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/" + GetParam() + ".json");
  const MeshOptions options;
  const std::string msh = ::testing::TempDir() + GetParam() + ".msh";
  const std::string geo = ::testing::TempDir() + GetParam() + ".geo";
  write_mesh(scene, options, msh);
  write_file_atomically(geo, geo_script(scene, options));
  const auto stations = mesh_stations(scene, options);
  for (bool from_geo : {false, true}) {
    const auto meshed = read_back(from_geo ? geo : msh, from_geo);
    ASSERT_EQ(meshed.size(), scene.fibres.size());
    for (std::size_t i = 0; i < scene.fibres.size(); ++i) {
      const FibreSpec& spec = scene.fibres[i];
      const MeshedFibre& m = meshed.at(spec.id);
      EXPECT_LE(m.longest, stations[i].element_length * (1 + 1e-9)) << spec.id;
      for (double s : stations[i].s) {
        const Eigen::Vector3d x = spec.start + s * (spec.end - spec.start);
        double nearest = INFINITY;
        for (const Eigen::Vector3d& node : m.nodes) nearest = std::min(nearest, (node - x).norm());
        EXPECT_LT(nearest, 1e-12) << spec.id << " has no node at s = " << s;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(CommittedScenes, FibreMesh,
                         ::testing::Values("two_fibres_crossing", "parallel_fibres", "small_tow_19",
                                           "compaction_test"));

TEST(FibreMeshStations, SupportsSlicesLoadsAndRefinedContacts) {
  Scene s = read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/two_fibres_crossing.json");
  LoadSpec load;
  load.fibre = "A";
  load.position = 0.3;
  load.force = {0, 0, -1e-5};
  s.loads.push_back(load);
  const auto stations = mesh_stations(s, MeshOptions{});
  // A: supports, the load at 0.3, the crossing at 0.5 (refined). No walls, no slices.
  EXPECT_EQ(stations[0].s, (std::vector<double>{0.0, 0.3, 0.5, 1.0}));
  EXPECT_EQ(stations[0].fine, (std::vector<char>{0, 0, 1, 0}));
  EXPECT_NEAR(stations[0].element_length, 1.0 / s.contact.slices, 1e-15);
  const auto tow = mesh_stations(
      read_scene(std::string(FIBRECHECK_SCENES_DIR) + "/parallel_fibres.json"), MeshOptions{});
  EXPECT_EQ(tow[0].s.size(), 2u + 100u);  // supports and 100 slices
}

}  // namespace
}  // namespace fibrecheck
