#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace fibrecheck {

/// `fibrecheck mesh SCENE --out MESH.msh [--geo SCRIPT.geo] [--slices N] [--line-contact M]
/// [--refine K]`: the Gmsh mesh of the reference's first outer iteration.
struct MeshArguments {
  std::string scene, out, geo, line_contact = "slices";
  int slices = 0, refine = 0;
};

/// Registers the sub-command and its options, which fill `args`.
CLI::App* add_mesh_command(CLI::App& app, MeshArguments& args);

/// Writes the mesh (and the script); 0 on success. Bad input throws InputError.
int run_mesh(const MeshArguments& args);

}  // namespace fibrecheck
