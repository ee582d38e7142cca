#pragma once

#include <CLI/CLI.hpp>

namespace fibrecheck {

/// `fibrecheck generate tow --fibres N --slices n --seed S --out FILE [...]`: writes a random,
/// compacted tow scene.
void add_generate_command(CLI::App& app, int& exit_code);

}  // namespace fibrecheck
