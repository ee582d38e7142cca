#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// `fibrecheck compare SCENE... --out DIR`: both solvers on each scene, the errors of the user's
/// run and their split (DESIGN §6), in DIR/<scene>/compare.json beside every result file.
/// `fibrecheck compare --run RESULT --truth RESULT [--out FILE]`: the errors of one stored result
/// against another (no solver runs; works without the finite-element stack).
struct CompareArguments {
  std::vector<std::string> scenes;
  std::string out, run, truth;
  bool quiet = false;
};

CLI::App* add_compare_command(CLI::App& app, CompareArguments& args);

/// 0 when every scene was compared, 3 when one was not comparable or a run did not converge.
int run_compare(const CompareArguments& args);

}  // namespace fibrecheck
