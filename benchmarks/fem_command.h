#pragma once

#include <CLI/CLI.hpp>

namespace fibrecheck {

/// `fibrecheck fem SCENE --out RESULT`: solves a scene with the implicit reference model.
void add_fem_command(CLI::App& app, int& exit_code);

}  // namespace fibrecheck
