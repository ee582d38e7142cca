#pragma once

// The friction study. Question: where does the seed's friction rule (§4.3.4, Eqs. 4.29–4.33:
// the last resultant split along the normal of the displaced centres, its tangential part capped
// at μN) converge, where does it stall, and how far is its answer from Coulomb's law and from the
// pressure Coulomb friction gives? On generated tows of each size, compacted in one step to each
// F, with each μ, the iterative solver runs twice: friction model `seed` and `coulomb`. A run that
// does not converge is a result, recorded with its status and message.
//
// Sample run:
//   fibrecheck study friction --fibres 19,100 --mu 0.1,0.2,0.4 --compactions 0.9,0.8,0.7 --out
//   study

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "friction_study_record.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

struct FrictionStudyOptions {
  std::vector<int> fibres = {19, 100};
  std::vector<double> mu = {0.1, 0.2, 0.4};
  std::vector<double> compactions = {0.9, 0.8, 0.7};
  int slices = 100;
  std::uint64_t seed = 2;
  double volume_fraction = 0.35;  ///< before compaction
  long max_iterations = 100000;   ///< of each run
  bool quiet = false;
};

/// Runs the study (points already in `folder` are read, not run again) and writes
/// friction_study.json and friction_study.csv there. Throws InputError for options no tow can be
/// generated with.
std::vector<FrictionPoint> run_friction_study(const FrictionStudyOptions& options,
                                              const std::function<Result(const Scene&)>& iterative,
                                              const std::string& folder);

}  // namespace fibrecheck
