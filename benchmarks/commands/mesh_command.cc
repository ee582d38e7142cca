#include "mesh_command.h"

#include <iostream>

#include "atomic_file.h"
#include "exit_codes.h"
#include "fibre_mesh.h"
#include "mpi_session.h"
#include "reference_solver.h"
#include "scene.h"

namespace fibrecheck {

int run_mesh(const MeshArguments& args) {
  Scene scene = read_scene(args.scene);
  if (args.slices > 0) scene.contact.slices = args.slices;
  validate_scene(scene);
  // The mesh of the reference's first outer iteration, with the same options (its set-up speaks
  // MPI, as the reference does).
  const MpiSession mpi;
  ReferenceOptions reference;
  reference.line_contact =
      args.line_contact == "continuous" ? LineContact::continuous : LineContact::slices;
  reference.refine = args.refine;
  const MeshOptions options = reference_mesh_options(scene, reference);
  write_mesh(scene, options, args.out);
  if (!args.geo.empty()) write_file_atomically(args.geo, geo_script(scene, options));
  std::size_t nodes = 0;
  for (const FibreStations& f : mesh_stations(scene, options)) nodes += f.s.size();
  std::cout << "wrote " << args.out << ": " << scene.fibres.size() << " fibres, " << nodes
            << " stations (supports, slices, loads, contacts)\n";
  return kExitConverged;
}

CLI::App* add_mesh_command(CLI::App& app, MeshArguments& args) {
  CLI::App* mesh =
      app.add_subcommand("mesh", "Write the Gmsh mesh of a scene for the reference model");
  mesh->add_option("scene", args.scene, "Scene file (JSON)")->required();
  mesh->add_option("--out", args.out, "Mesh file (.msh)")->required();
  mesh->add_option("--geo", args.geo, "Also write the geometry as a Gmsh script (.geo)");
  mesh->add_option("--slices", args.slices, "Cross-sections n (overrides contact.slices)")
      ->check(CLI::Range(1, 1000000));
  mesh->add_option("--line-contact", args.line_contact,
                   "Line contacts at the n slices or continuous (as fibrecheck fem)")
      ->check(CLI::IsMember({"slices", "continuous"}));
  mesh->add_option("--refine", args.refine, "Refinements K (as fibrecheck fem)")
      ->check(CLI::Range(0, 12));
  return mesh;
}

}  // namespace fibrecheck
