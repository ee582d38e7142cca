#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// `fibrecheck study slices|tolerance|stability|compaction SCENE... --out DIR [options]`: one study
/// on the scenes, each point written to DIR when done (a study run again computes only what is
/// missing), then its CSV and JSON.
struct StudyArguments {
  std::string study;  ///< the sub-command chosen
  std::vector<std::string> scenes;
  std::string out;
  std::vector<int> slices;
  std::vector<double> tolerances, fractions, ratios;
  std::vector<int> refinements;
  long max_iterations = 0;  ///< 0: the study's own cap
  bool against_slices = false;
  int steps = 0;  ///< compaction: steps for scenes without a load path
  double final_compaction = 0.7;
  std::vector<int> sections;
  bool quiet = false;
};

/// Registers `study` and its sub-commands.
CLI::App* add_study_command(CLI::App& app, StudyArguments& args);

int run_study(const StudyArguments& args);

}  // namespace fibrecheck
