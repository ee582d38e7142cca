#pragma once

// The stability study. Questions: where does the seed's update P' = P + c·d become unstable
// (§4.3.2: "if the value of c is too large the system will become unstable"), and does a stiff
// contrast between contacting fibres break any rule, or the reference?
//
//  - c sweep: rule `seed` with c from 0.05 to 4 times its stable limit c_crit = 2/λmax(D½WD½):
//    iterations to converge, or the iteration at which divergence was detected;
//  - stiffness sweep: the Young's modulus of every second fibre times 1 … 1e9, for every rule (the
//    seed at half its limit) and the reference: iterations, time, error against the reference;
//  - the extreme catalogue: a scene that says what it must give (`expected`, scenes/extreme/) is
//    not swept but run once by each solver as it stands (the default rule where it names none)
//    and judged: status, iterations, time, error against its exact answer.
//
// Sample run:
//   fibrecheck study stability scenes/two_fibres_crossing.json scenes/extreme/*.json --out study

#include <cmath>
#include <string>
#include <vector>

#include "comparison.h"
#include "scene.h"
#include "stability_study_record.h"

namespace fibrecheck {

struct StabilityStudyOptions {
  std::vector<double> fractions = {0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.95, 1.05, 1.25, 1.5, 2, 4};
  std::vector<double> stiffness_ratios = {1, 1e3, 1e6, 1e9};
  long max_iterations = 200000;
  bool quiet = false;
};

std::vector<StabilityStudyScene> run_stability_study(const std::vector<Scene>& scenes,
                                                     const StabilityStudyOptions& options,
                                                     const Solvers& solvers,
                                                     const std::string& folder);

}  // namespace fibrecheck
