#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "tow_generator.h"

namespace fibrecheck {

/// `fibrecheck generate tow [--fibres N] [--slices N] [--seed S] ... --out SCENE`: writes a
/// generated scene.
struct GenerateArguments {
  TowOptions tow;
  std::string out;
};

/// Registers `generate` and its `tow` sub-command, whose options fill `args`.
CLI::App* add_generate_command(CLI::App& app, GenerateArguments& args);

/// Writes the tow; 0 on success. Impossible options throw InputError naming the option.
int run_generate(const GenerateArguments& args);

}  // namespace fibrecheck
