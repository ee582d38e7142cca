#pragma once

// The compaction study. Question: what compaction curve — pressure on the walls against the fibre
// volume fraction Vf — does the seed's method give for a tow, how far is it from the exact
// reference's, and what does friction (exact Coulomb, and the seed's own rule of §4.3.4) change?
//
// Each scene's load path (its `steps`, or `--steps K --final-compaction F` for a scene without)
// is run by the iterative solver and the reference, frictionless and with the scene's μ; with
// μ > 0 also by the iterative solver with the seed's friction rule. Per step: Vf, the pressure
// (mean over the walls of wall force / wall area), the strain energy and the contacts per fibre.
// Each curve is fitted by van Wyk's p = kE(Vf³ − Vf0³) and Toll's p = kE(Vfⁿ − Vf0ⁿ) on the steps
// where the walls carry force.
//
// Sample run:
//   fibrecheck generate tow --fibres 19 --seed 2 --volume-fraction 0.35 --steps 6
//     (continued:) --final-compaction 0.7 --friction 0.2 --out tow19.json
//   fibrecheck study compaction tow19.json --out study

#include <string>
#include <vector>

#include "compaction_study_record.h"
#include "comparison.h"
#include "scene.h"

namespace fibrecheck {

struct CompactionStudyOptions {
  /// For scenes without steps: K compaction steps down to `final_compaction` (0: such a scene is
  /// bad input).
  int steps = 0;
  double final_compaction = 0.7;
  /// Steps (1-based) whose state the iterative runs keep for the cross-section pictures, besides
  /// the last (every run keeps its last).
  std::vector<int> sections;
  /// The reference only on scenes of at most this many fibres (0: on every scene), and with
  /// friction only on those of at most `frictional_reference_fibres`: on the deformed fibres its
  /// sequences are the study's costliest part.
  int reference_fibres = 0;
  int frictional_reference_fibres = 0;
  bool quiet = false;
};

/// Throws InputError for a scene without walls, or without steps when none are asked for.
std::vector<CompactionStudyScene> run_compaction_study(const std::vector<Scene>& scenes,
                                                       const CompactionStudyOptions& options,
                                                       const Solvers& solvers,
                                                       const std::string& folder);

}  // namespace fibrecheck
