#pragma once

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "expected_outcome.h"
#include "update_rules.h"

namespace fibrecheck {

/// A fibre: a straight, initially unstressed centreline pinned at `start` and `end` (seed §4.3.1).
struct FibreSpec {
  std::string id;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  ///< pinned support, mm
  Eigen::Vector3d end = Eigen::Vector3d::Zero();    ///< pinned support, mm
  double radius = 0.0;                              ///< mm
  double youngs_modulus = 0.0;                      ///< MPa (N/mm²)
};

enum class LoadKind { point, distributed };

/// An external load on one fibre. Point loads in N at `position` (fraction of the length from
/// start); distributed loads uniform over the whole length, in N/mm.
struct LoadSpec {
  std::string fibre;
  LoadKind kind = LoadKind::point;
  double position = 0.5;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

/// A rigid plane; fibres live on the side the unit normal points to.
struct WallSpec {
  std::string id;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< mm
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

/// How friction acts when μ > 0 (DESIGN §2): `coulomb` — per step a contact sticks while
/// |F_t| < μN and slips against its relative tangential motion with |F_t| = μN otherwise; `seed` —
/// the rule of §4.3.4 as written: the previous iteration's resultant split along the normal of the
/// deformed centres, its tangential part capped by μN (Eqs. 4.29–4.33).
enum class FrictionModel { coulomb, seed };

/// How a contact is measured (DESIGN §2): `deformed` — the seed's: at every iteration the gap and
/// the force direction come from the displaced centres (Eqs. 4.14–4.15; a slice in its
/// cross-section plane, a crossing at the closest points of the deformed fibres); `linearised` —
/// the small-deflection contact: place and normal of the undeformed fibres, the overlap linear in
/// the deflections.
enum class ContactGeometryModel { deformed, linearised };

/// Contact detection (seed §4.3.3). All defaults of the scene format live in these initialisers.
struct ContactSettings {
  int slices = 50;                                  ///< cross-sections n along the tow axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  ///< tow axis (unit after reading)
  double friction = 0.0;                            ///< Coulomb coefficient μ (Eq. 4.31)
  FrictionModel friction_model = FrictionModel::coulomb;
  ContactGeometryModel geometry = ContactGeometryModel::deformed;
  /// Fibres within this angle of the tow axis are tow fibres: pairs of them touch along lines and
  /// are sliced; every other pair is a point contact (Eqs. 4.16–4.24).
  double parallel_angle_deg = 10.0;
};

/// Force update and stopping (seed §4.3.2, §4.3.6).
struct SolverSettings {
  UpdateRule rule = UpdateRule::accelerated;  ///< one of update_rules()
  std::optional<double> c;                    ///< step c of P' = P + c·d, N/mm (rule `seed` only)
  /// t_d, mm; default 1e-5 of the smallest fibre radius.
  std::optional<double> overlap_tolerance;
  double energy_tolerance = 0.0;  ///< t_U, N·mm; 0 switches the energy criterion off
  /// Relative: the run stops when its estimated force error is below this (criterion `force`);
  /// 0 leaves the seed's criteria alone.
  double force_tolerance = 1e-4;
  int energy_window = 10;         ///< n_i
  long max_iterations = 100000;
};

/// One step of a load path: the cross-section compaction factor F (positions ⊥ the tow axis scale
/// by F about the tow's centre, supports and walls included) and the factor on the scene's loads.
struct LoadStep {
  double compaction = 1.0;
  double load_factor = 1.0;
};

struct OutputSettings {
  int samples = 101;  ///< displacement samples per fibre in the result
};

struct Scene {
  std::string name;
  std::vector<FibreSpec> fibres;
  std::vector<LoadSpec> loads;
  std::vector<WallSpec> walls;
  ContactSettings contact;
  SolverSettings solver;
  OutputSettings output;
  /// The load path; empty: one step from the unloaded state, the scene as written.
  std::vector<LoadStep> steps;
  /// What the scene must give, where it is known (catalogue scenes); never read by the solvers.
  std::optional<ExpectedOutcome> expected;
  std::string source;  ///< file it was read from (for messages)

  /// Index of the fibre with this id, or -1.
  int fibre_index(const std::string& id) const;
  /// t_d: the scene's overlap tolerance or its default.
  double overlap_tolerance() const;
};

const char* to_string(LoadKind kind);
const char* to_string(FrictionModel model);
const char* to_string(ContactGeometryModel model);

/// Reads and validates a scene file. Throws InputError (file, field, reason) on any bad input.
Scene read_scene(const std::string& path);
/// Reads every scene file and checks its physics (`validate_scene`) before anything runs.
std::vector<Scene> read_scenes(const std::vector<std::string>& paths);
/// Validates a parsed JSON document as a scene; `source` names it in messages.
Scene scene_from_json(const nlohmann::json& document, const std::string& source);
/// Checks the physics of a scene (also after command-line overrides). Throws InputError.
void validate_scene(const Scene& scene);
/// The scene as JSON, every field written (defaults included).
nlohmann::json scene_to_json(const Scene& scene);
/// Human-readable list of every scene field, its default and its unit.
std::string scene_format_help();
/// Writes a scene file atomically.
void write_scene(const std::string& path, const Scene& scene);

}  // namespace fibrecheck
