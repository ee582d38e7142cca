#pragma once

#include <CLI/CLI.hpp>

namespace fibrecheck {

/// `fibrecheck mesh SCENE --out FILE.msh [--geo FILE.geo] [--slices N]`: writes the Gmsh mesh the
/// reference model uses for a scene.
void add_mesh_command(CLI::App& app, int& exit_code);

}  // namespace fibrecheck
