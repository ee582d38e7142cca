#pragma once

// The scale study's records, as scale_study.json holds them: what the harness writes and the
// report reads. The JSON's field names are read by outside tools too: they do not change.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fibrecheck {

/// One solver (and method) on one tow size, its own process.
struct ScalePoint {
  int fibres = 0, slices = 0;
  std::string solver;  ///< "iterative" | "fem" | "siconos"
  std::string method;  ///< the rule, "active_set", or the peer's solver
  int processes = 1;
  std::string status;
  long candidates = 0, active = 0, iterations = 0, unknowns = 0;
  double time_s = 0.0;                       ///< the solver's own time (without start-up and files)
  double process_time_s = 0.0;               ///< the whole process
  double peak_memory_mb = 0.0;               ///< resident (the largest process's)
  double peak_proportional_memory_mb = 0.0;  ///< shared pages counted as shares; 0: not measured
  double agreement = -1.0;  ///< peer: against the reference (relative), −1 when not compared
  double ms_per_iteration() const { return iterations > 0 ? 1e3 * time_s / iterations : 0.0; }
};

/// Time (and memory) ∝ fibres^exponent for one solver, method and process count, fitted by least
/// squares on log–log over its converged sizes (two at least).
struct ScaleExponent {
  std::string solver, method;
  int processes = 1;
  int sizes = 0;
  double time = 0.0, memory = 0.0;
};

/// The study's object (`"study": "scale"`): the tows' slices and seed, every point, the exponents.
struct ScaleStudy {
  int slices = 0;
  std::uint64_t seed = 0;
  /// The peak resident memory of the program that only starts (`fibrecheck --help`): the
  /// libraries' pages, which every process holds; 0 when not measured.
  double program_floor_memory_mb = 0.0;
  std::vector<ScalePoint> points;
  std::vector<ScaleExponent> exponents;
};

/// With `ms_per_iteration`, which reading computes again from the time and the iterations.
nlohmann::json to_json(const ScalePoint& point);
void from_json(const nlohmann::json& j, ScalePoint& point);
nlohmann::json to_json(const ScaleExponent& exponent);
void from_json(const nlohmann::json& j, ScaleExponent& exponent);
nlohmann::json to_json(const ScaleStudy& study);
/// Whether `j` is a scale study's object (its `study` is "scale").
bool is_scale_study(const nlohmann::json& j);
void from_json(const nlohmann::json& j, ScaleStudy& study);

}  // namespace fibrecheck
