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
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "comparison.h"
#include "metrics.h"
#include "scene.h"

namespace fibrecheck {

struct StabilityStudyOptions {
  std::vector<double> fractions = {0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.95, 1.05, 1.25, 1.5, 2, 4};
  std::vector<double> stiffness_ratios = {1, 1e3, 1e6, 1e9};
  long max_iterations = 200000;
  bool quiet = false;
};

struct StepPoint {
  double fraction = 0, c = 0;  ///< c/c_crit and c (N/mm)
  long iterations = 0;
  std::string status, criterion;
  double time_s = 0;
};

struct StiffnessPoint {
  double ratio = 0;
  std::string method;  ///< "seed 0.5", "auto", "accelerated", "reference"
  long iterations = 0;
  std::string status;
  double time_s = 0;
  Errors errors;  ///< against the reference at the same ratio
};

/// One solver on one catalogue scene.
struct CataloguePoint {
  std::string solver;  ///< "iterative" | "reference"
  std::string rule;
  std::string status, expected_status;  ///< a status, or `refused`
  long iterations = 0;
  double time_s = 0;
  double error = NAN;    ///< worst relative error against the scene's closed forms
  std::string failures;  ///< empty: as expected
};

struct StabilityStudyScene {
  std::string scene;
  double c_crit = 0;
  std::vector<StepPoint> steps;
  std::vector<StiffnessPoint> stiffness;
  std::vector<CataloguePoint> catalogue;
};

std::vector<StabilityStudyScene> run_stability_study(const std::vector<Scene>& scenes,
                                                     const StabilityStudyOptions& options,
                                                     const Solvers& solvers,
                                                     const std::string& folder);

nlohmann::json to_json(const StabilityStudyScene& scene);
nlohmann::json to_json(const CataloguePoint& point);
CataloguePoint catalogue_point(const nlohmann::json& point);

}  // namespace fibrecheck
