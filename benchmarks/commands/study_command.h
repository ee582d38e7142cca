#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "compaction_study.h"
#include "friction_study.h"
#include "scale_study.h"
#include "slice_study.h"
#include "stability_study.h"
#include "tolerance_study.h"

namespace fibrecheck {

/// `fibrecheck study slices|tolerance|stability|compaction SCENE... --out DIR [options]`, or
/// `fibrecheck study scale|friction --out DIR [--fibres N,...] [options]` on generated tows: one
/// study on the scenes, each point written to DIR when done (a study run again computes only what
/// is missing), then its CSV and JSON. Each study has its own options, with its defaults.
struct StudyArguments {
  std::string study;                ///< the sub-command chosen
  std::vector<std::string> scenes;  ///< the scene files (all studies but scale)
  std::string out;
  bool quiet = false;
  /// A line from inside each iterative run this often (s); 0, or quiet: none.
  double progress_every_s = 60.0;
  SliceStudyOptions slices;
  ToleranceStudyOptions tolerance;
  StabilityStudyOptions stability;
  CompactionStudyOptions compaction;
  /// Its programs are found when it runs; "0" alone in a list of sizes means none.
  ScaleStudyOptions scale;
  FrictionStudyOptions friction;
};

/// Registers `study` and its sub-commands.
CLI::App* add_study_command(CLI::App& app, StudyArguments& args);

/// Runs the study chosen; a study it does not know is bad input.
int run_study(const StudyArguments& args);

}  // namespace fibrecheck
