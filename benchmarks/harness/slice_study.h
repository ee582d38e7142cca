#pragma once

// The slice study. Question: how fast does the iterative method's error fall as the slices that
// approximate a line contact grow (Figures 4.11–4.12, Eq. 4.28), and what does each slice count
// cost?
//
// Sample run:
//   fibrecheck study slices scenes/parallel_fibres.json --slices 2,4,8,16,32,64,128 --out study

#include <string>
#include <vector>

#include "comparison.h"
#include "scene.h"
#include "slice_study_record.h"

namespace fibrecheck {

struct SliceStudyOptions {
  std::vector<int> slices = {2, 4, 8, 16, 32, 64, 128};
  bool quiet = false;
};

/// Runs the study on each scene, writing every point to `folder` when done (and skipping the
/// points already there), then `slice_study.json` and `slice_study.csv`.
std::vector<SliceStudyScene> run_slice_study(const std::vector<Scene>& scenes,
                                             const SliceStudyOptions& options,
                                             const Solvers& solvers, const std::string& folder);

}  // namespace fibrecheck
