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

#include <cmath>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

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
  bool quiet = false;
};

/// A power law p/E = k(Vfⁿ − Vf0ⁿ) fitted by least squares (n = 3 for van Wyk).
struct PowerLawFit {
  bool valid = false;
  double k = NAN, n = NAN, vf0 = NAN, r2 = NAN;
  int points = 0;
};

/// Fits p/E = k(Vfⁿ − Vf0ⁿ) at the given n: linear least squares in Vfⁿ; R² of the pressures.
/// Needs two points with different Vf.
PowerLawFit fit_power_law(const std::vector<double>& vf, const std::vector<double>& pressure,
                          double modulus, double n);
/// Toll's law: the n in [1, 30] (steps of 0.01) with the best R². Needs three points.
PowerLawFit fit_toll(const std::vector<double>& vf, const std::vector<double>& pressure,
                     double modulus);

struct CompactionPoint {
  int step = 0;  ///< from 1
  double compaction = 1, load_factor = 1, fibre_volume_fraction = 0, pressure = 0;
  double strain_energy = 0, contacts_per_fibre = 0, time_s = 0;
  long iterations = 0;
  std::string status;
};

/// One solver's load path.
struct CompactionRun {
  std::string solver;  ///< "iterative" | "fem" (as in the result files)
  std::string rule;
  double mu = 0;
  std::string friction_model;  ///< "none" (μ = 0), "coulomb" or "seed"
  std::string status, message;
  double time_s = 0;
  std::vector<CompactionPoint> points;
  PowerLawFit van_wyk, toll;
  /// Result files of kept states (relative to the study folder), with their steps.
  std::vector<std::pair<int, std::string>> sections;

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
};

struct CompactionStudyScene {
  std::string scene;
  std::string scene_file;  ///< the stepped scene as solved (relative to the study folder)
  double youngs_modulus = 0;
  std::vector<CompactionRun> runs;
  std::vector<CompactionAgreement> agreement;
};

/// Throws InputError for a scene without walls, or without steps when none are asked for.
std::vector<CompactionStudyScene> run_compaction_study(const std::vector<Scene>& scenes,
                                                       const CompactionStudyOptions& options,
                                                       const Solvers& solvers,
                                                       const std::string& folder);

nlohmann::json to_json(const CompactionStudyScene& scene);

}  // namespace fibrecheck
