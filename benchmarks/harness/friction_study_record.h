#pragma once

// The friction study's records, as friction_study.json holds them: what the harness writes and
// the report reads. The JSON's field names are read by outside tools too: they do not change.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// One friction model on one generated tow at one compaction and one μ.
struct FrictionPoint {
  int fibres = 0;
  double compaction = 0;  ///< F
  double mu = 0;
  std::string model;  ///< `seed` (Eqs. 4.29–4.33) or `coulomb`
  double fibre_volume_fraction = 0;
  std::string status, criterion, message;
  long iterations = 0;
  long geometric_updates = 0;
  double time_s = 0;
  /// Coulomb's law on the answer (mm): the largest slip where |F| < μN, and the largest slip not
  /// along F where |F| = μN (the result's `friction`).
  double stick_residual = NAN, slip_residual = NAN;
  double pressure = NAN;  ///< MPa, mean over the walls
};

nlohmann::json to_json(const FrictionPoint& point);
void from_json(const nlohmann::json& j, FrictionPoint& point);

}  // namespace fibrecheck
