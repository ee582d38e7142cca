#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// `fibrecheck study slices|tolerance|stability|compaction SCENE... --out DIR [options]`, or
/// `fibrecheck study scale --out DIR [--fibres N,...] [options]` on generated tows: one study
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
  /// scale: the generated tows and what runs on them (scale_study.h).
  std::vector<int> fibres{100, 1000}, reference_fibres{100}, peer_fibres{100};
  int tow_slices = 100;
  unsigned long tow_seed = 3;
  std::vector<std::string> rules{"auto", "accelerated"}, peer_solvers{"lemke"};
  double seed_c = 0.0;
  int processes = 2;
  bool quiet = false;
};

/// Registers `study` and its sub-commands.
CLI::App* add_study_command(CLI::App& app, StudyArguments& args);

int run_study(const StudyArguments& args);

}  // namespace fibrecheck
