#pragma once

// The compaction study's records, as compaction_study.json holds them: what the harness writes and
// the report reads. The JSON's field names are read by outside tools too: they do not change.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "power_law_fit.h"

namespace fibrecheck {

/// One step of a load path.
struct CompactionPoint {
  int step = 0;  ///< from 1
  double compaction = 1, load_factor = 1, fibre_volume_fraction = 0;
  double pressure = 0;  ///< MPa, mean over the walls (`pressure_MPa`)
  double strain_energy = 0, contacts_per_fibre = 0;
  double time_s = 0;  ///< `wall_time_s`
  long iterations = 0;
  long geometric_updates = 0;    ///< the step's updates of the normals
  long fixed_point_updates = 0;  ///< the step's, as its result's `friction` counts them
  std::string status;
  /// Coulomb's law on the step's answer (mm): the largest slip where a contact sticks, and the
  /// largest slip not along its friction where it slips (0 without friction, NaN in records kept
  /// before they were).
  double stick_residual = 0, slip_residual = 0;
};

/// One solver's load path.
struct CompactionRun {
  std::string solver;  ///< "iterative" | "fem" (as in the result files)
  std::string rule;
  double mu = 0;
  std::string friction_model;         ///< "none" (μ = 0), "coulomb" or "seed"
  std::string geometry = "deformed";  ///< the contact geometry, "deformed" or "linearised"
  std::string status, message;
  double time_s = 0;  ///< `wall_time_s`
  std::vector<CompactionPoint> points;
  PowerLawFit van_wyk, toll;
  /// Result files of kept states (relative to the study folder), with their steps.
  std::vector<std::pair<int, std::string>> sections;

  /// The run's name in keys and file names, e.g. "iterative_mu0_2_coulomb" ("…_linearised" for
  /// the linearised contact).
  std::string label() const;
};

/// Iterative against reference on one friction setting: the largest per-step difference of the
/// pressure relative to the reference curve's largest pressure, and of the strain energy relative
/// to its largest, over the steps both converged.
struct CompactionAgreement {
  double mu = 0;
  std::string friction_model, against;  ///< the iterative run's model, the reference's
  double pressure_error = NAN, energy_error = NAN;
  int steps = 0;
  std::string geometry = "deformed";  ///< the contact geometry of both runs
};

struct CompactionStudyScene {
  std::string scene;
  std::string scene_file;     ///< the stepped scene as solved (relative to the study folder)
  double youngs_modulus = 0;  ///< MPa, the mean over the fibres (the fits' E)
  std::vector<CompactionRun> runs;
  std::vector<CompactionAgreement> agreement;
};

/// A step both runs converged on: the reference's step and Vf, and the differences between the
/// two runs' pressures (MPa, absolute) and strain energies (N·mm, absolute).
struct StepDifference {
  int step = 0;
  double fibre_volume_fraction = 0;
  double reference_pressure = 0;  ///< MPa
  double pressure = 0, strain_energy = 0;
};

/// The steps both runs converged on, in the reference's order.
std::vector<StepDifference> step_differences(const CompactionRun& iterative,
                                             const CompactionRun& reference);

/// The largest pressure (MPa) and strain energy (N·mm) over a run's converged steps (0 without).
double largest_pressure(const CompactionRun& run);
double largest_strain_energy(const CompactionRun& run);

/// The agreement of an iterative run with a reference run of the same μ.
CompactionAgreement agreement_of(const CompactionRun& iterative, const CompactionRun& reference);

nlohmann::json to_json(const CompactionPoint& point);
void from_json(const nlohmann::json& j, CompactionPoint& point);
nlohmann::json to_json(const CompactionRun& run);
void from_json(const nlohmann::json& j, CompactionRun& run);
nlohmann::json to_json(const CompactionAgreement& agreement);
void from_json(const nlohmann::json& j, CompactionAgreement& agreement);
nlohmann::json to_json(const CompactionStudyScene& scene);
void from_json(const nlohmann::json& j, CompactionStudyScene& scene);

}  // namespace fibrecheck
