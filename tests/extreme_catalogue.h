#pragma once

// The catalogue of extreme scenes (scenes/extreme/): every file, and what every result must be
// whatever its status — finite.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "result.h"

namespace fibrecheck::testing {

inline std::vector<std::string> extreme_catalogue() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(FIBRECHECK_SCENES_DIR "/extreme"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

inline std::string extreme_scene_path(const std::string& name) {
  return FIBRECHECK_SCENES_DIR "/extreme/" + name + ".json";
}

/// A test name for a catalogue scene (gtest allows letters, digits and underscores).
inline std::string catalogue_test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

/// The first non-finite number in a result, or "" when all are finite.
inline std::string first_non_finite(const Result& r) {
  auto bad = [](double x) { return !std::isfinite(x); };
  const std::pair<const char*, double> scalars[] = {
      {"strain_energy", r.strain_energy},
      {"strain_energy_exact", r.strain_energy_exact},
      {"max_overlap", r.max_overlap},
      {"gap_force_residual", r.gap_force_residual},
      {"c", r.c},
      {"c_stable_limit", r.c_stable_limit},
      {"axial_load_dropped", r.axial_load_dropped},
      {"max_deflection_over_radius", r.max_deflection_over_radius},
      {"max_slope", r.max_slope},
      {"wall_time_s", r.wall_time_s}};
  for (const auto& [name, x] : scalars)
    if (bad(x)) return name;
  for (const FibreResult& f : r.fibres) {
    for (const Eigen::Vector3d& u : f.displacement)
      if (!u.allFinite()) return "a displacement of " + f.id;
    for (const Eigen::Vector2d& m : f.moment)
      if (!m.allFinite()) return "a moment of " + f.id;
  }
  for (const ContactResult& c : r.contacts) {
    if (bad(c.total_force)) return "a contact force";
    for (const ContactPoint& p : c.points)
      if (bad(p.position) || !p.force.allFinite()) return "a contact point";
  }
  for (const HistoryEntry& h : r.history)
    if (bad(h.max_overlap) || bad(h.strain_energy)) return "the history";
  return "";
}

}  // namespace fibrecheck::testing
