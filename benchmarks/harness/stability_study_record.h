#pragma once

// The stability study's records, as stability_study.json holds them: what the harness writes and
// the report reads. The JSON's field names are read by outside tools too: they do not change.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "metrics.h"

namespace fibrecheck {

/// One step c of the seed's rule.
struct StepPoint {
  double fraction = 0, c = 0;  ///< c/c_crit (`c_over_c_crit`) and c (N/mm)
  long iterations = 0;
  std::string status, criterion;
  double time_s = 0;
};

/// One rule, or the reference, at one stiffness ratio.
struct StiffnessPoint {
  double ratio = 0;    ///< `stiffness_ratio`
  std::string method;  ///< "seed 0.5", "auto", "accelerated", "reference"
  long iterations = 0;
  std::string status;
  double time_s = 0;
  Errors errors;  ///< against the reference at the same ratio (NaN: the reference did not converge)
};

/// One solver on one catalogue scene.
struct CataloguePoint {
  std::string solver;  ///< "iterative" | "reference"
  std::string rule;
  std::string status, expected_status;  ///< a status, or `refused` (bad input)
  long iterations = 0;
  double time_s = 0;
  double error = NAN;    ///< worst relative error against the scene's closed forms
  std::string failures;  ///< empty: as expected
};

/// A swept scene (`steps`, `stiffness`), or a catalogue scene (`catalogue` only).
struct StabilityStudyScene {
  std::string scene;
  double c_crit = 0;
  std::vector<StepPoint> steps;
  std::vector<StiffnessPoint> stiffness;
  std::vector<CataloguePoint> catalogue;
};

nlohmann::json to_json(const StepPoint& point);
void from_json(const nlohmann::json& j, StepPoint& point);
nlohmann::json to_json(const StiffnessPoint& point);
void from_json(const nlohmann::json& j, StiffnessPoint& point);
nlohmann::json to_json(const CataloguePoint& point);
void from_json(const nlohmann::json& j, CataloguePoint& point);
nlohmann::json to_json(const StabilityStudyScene& scene);
void from_json(const nlohmann::json& j, StabilityStudyScene& scene);

}  // namespace fibrecheck
