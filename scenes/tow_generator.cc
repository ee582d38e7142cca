#include "tow_generator.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

#include "input_error.h"

namespace fibrecheck {

namespace {

/// Uniform in [0, 1) from the raw 64-bit stream: the same numbers on every platform.
double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

struct Placed {
  Eigen::Vector2d y0, y1;  ///< (y, z) at x = 0 and x = L
};

}  // namespace

double min_slice_distance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                          const Eigen::Vector2d& b0, const Eigen::Vector2d& b1) {
  // Δ(ξ) = Δ0 + ξ(Δ1 − Δ0), ξ ∈ [0, 1]; |Δ|² is a parabola in ξ.
  const Eigen::Vector2d d0 = b0 - a0;
  const Eigen::Vector2d dd = (b1 - a1) - d0;
  const double denominator = dd.squaredNorm();
  double xi = denominator > 0.0 ? -d0.dot(dd) / denominator : 0.0;
  xi = std::min(1.0, std::max(0.0, xi));
  return (d0 + xi * dd).norm();
}

Scene generate_tow(const TowOptions& o) {
  const std::string source = "tow options";
  if (o.fibres < 1) throw InputError(source, "fibres", "must be at least 1");
  if (o.slices < 1) throw InputError(source, "slices", "must be at least 1");
  if (!(o.misalignment_deg >= 0.0 && o.misalignment_deg < 30.0))
    throw InputError(source, "misalignment_deg", "must lie in [0, 30) degrees");
  if (!(o.length > 0.0 && std::isfinite(o.length)))
    throw InputError(source, "length", "must be positive");
  if (!(o.radius > 0.0 && std::isfinite(o.radius)))
    throw InputError(source, "radius", "must be positive");
  if (!(o.youngs_modulus > 0.0 && std::isfinite(o.youngs_modulus)))
    throw InputError(source, "youngs_modulus", "must be positive");
  if (o.steps < 0 || o.steps > 1000)
    throw InputError(source, "steps", "must be a whole number from 0 to 1000");
  if (!(o.compaction > 0.0 && o.compaction <= 1.0))
    throw InputError(source, "compaction", "must lie in (0, 1]");
  if (o.first_compaction != 0.0 &&
      !(o.first_compaction >= o.compaction && o.first_compaction <= 1.0))
    throw InputError(source, "first-compaction", "must lie in [F, 1] (F the final compaction)");
  if (!(o.friction >= 0.0 && std::isfinite(o.friction)))
    throw InputError(source, "friction", "must be a finite number, not negative");

  const double r = o.radius;
  const double contact = 2.0 * r * (1.0 + o.clearance);
  // Both supports of every fibre sit on sites of one hexagonal lattice, so after compaction by F
  // no two supports overlap and none touches a wall: an overlap at a pinned support could only be
  // relieved by slopes far beyond small-deflection beam theory. Misalignment moves a fibre's far
  // support to another vacant site; such a fibre passes between its neighbours, and that is where
  // the compacted tow overlaps: along the length, shallow, never at a pinned end. The spacing
  // makes a fibre moving to an adjacent site pass the two sites beside its path at a distance
  // halfway between `contact` (clear before compaction) and 2r/F (overlapping after it).
  const double passing = 0.5 * (contact + 2.0 * r / o.compaction);
  const double spacing = std::max(contact / o.compaction, passing / (0.5 * std::sqrt(3.0)));
  const double wall_gap = r * (1.0 + o.clearance) / o.compaction;
  const double densest = M_PI * r * r / (0.5 * std::sqrt(3.0) * spacing * spacing);
  if (!(o.volume_fraction > 0.0 && o.volume_fraction < densest))
    throw InputError(source, "volume_fraction",
                     "must lie in (0, " + std::to_string(densest) +
                         "): the supports sit on a hexagonal lattice of spacing " +
                         std::to_string(spacing) + " mm");

  // A square cross-section whose lattice has about N·densest/Vf sites; N of them, at random,
  // hold the near supports.
  const double side = std::sqrt(o.fibres * M_PI * r * r / o.volume_fraction) + 2.0 * wall_gap;
  const double row = 0.5 * std::sqrt(3.0) * spacing;
  std::vector<Eigen::Vector2d> sites;
  for (int j = 0; wall_gap + j * row <= side - wall_gap + 1e-12; ++j)
    for (int i = 0; wall_gap + (i + 0.5 * (j % 2)) * spacing <= side - wall_gap + 1e-12; ++i)
      sites.emplace_back(wall_gap + (i + 0.5 * (j % 2)) * spacing, wall_gap + j * row);
  if (static_cast<int>(sites.size()) <= o.fibres)
    throw InputError(source, "volume_fraction",
                     "too high for " + std::to_string(o.fibres) + " fibres in a square section");
  std::mt19937_64 rng(o.seed);
  auto pick = [&rng](std::size_t n) {
    return std::min(n - 1, static_cast<std::size_t>(uniform(rng) * static_cast<double>(n)));
  };
  std::vector<int> order(sites.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  for (std::size_t i = order.size() - 1; i > 0; --i)  // Fisher–Yates, platform independent
    std::swap(order[i], order[pick(i + 1)]);
  order.resize(o.fibres);

  // Lattice neighbourhoods within the misalignment's reach L·tan(θ), by a uniform grid of sites.
  const double reach = o.length * std::tan(o.misalignment_deg * M_PI / 180.0);
  const double cell = std::max(reach, spacing);
  const long columns = static_cast<long>(std::ceil(side / cell)) + 1;
  std::unordered_map<long, std::vector<int>> site_grid;
  auto key_of = [&](const Eigen::Vector2d& p) {
    return static_cast<long>(std::floor(p[1] / cell)) * columns +
           static_cast<long>(std::floor(p[0] / cell));
  };
  for (std::size_t i = 0; i < sites.size(); ++i)
    site_grid[key_of(sites[i])].push_back(static_cast<int>(i));
  auto sites_near = [&](const Eigen::Vector2d& p, double distance, std::vector<int>& out) {
    out.clear();
    const long cx = static_cast<long>(std::floor(p[0] / cell));
    const long cy = static_cast<long>(std::floor(p[1] / cell));
    for (long dy = -1; dy <= 1; ++dy)
      for (long dx = -1; dx <= 1; ++dx) {
        auto it = site_grid.find((cy + dy) * columns + cx + dx);
        if (it == site_grid.end()) continue;
        for (int k : it->second)
          if ((sites[k] - p).norm() <= distance + 1e-12) out.push_back(k);
      }
    std::sort(out.begin(), out.end());
  };

  // Fibres start aligned (far support on the near site); then, in random order, each tries to move
  // its far support to a random vacant site within reach, kept only if the fibre then clears every
  // other fibre along its whole length.
  std::vector<int> near_site(order), far_site(order);
  std::vector<int> far_owner(sites.size(), -1), near_owner(sites.size(), -1);
  for (int f = 0; f < o.fibres; ++f) far_owner[far_site[f]] = near_owner[near_site[f]] = f;
  std::vector<int> candidates, neighbours;
  for (int f = 0; f < o.fibres; ++f) {
    const Eigen::Vector2d start = sites[near_site[f]];
    sites_near(start, reach, candidates);
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](int k) { return far_owner[k] >= 0; }),
                     candidates.end());
    if (candidates.empty()) continue;
    const int target = candidates[pick(candidates.size())];
    const Eigen::Vector2d end = sites[target];
    // Fibres that can come within `contact` of this one start within reach + contact of it.
    sites_near(start, 2.0 * reach + contact, neighbours);
    bool ok = true;
    for (int k : neighbours) {
      const int g = near_owner[k];
      if (g < 0 || g == f) continue;
      if (min_slice_distance(start, end, sites[near_site[g]], sites[far_site[g]]) < contact) {
        ok = false;
        break;
      }
    }
    if (!ok) continue;
    far_owner[far_site[f]] = -1;
    far_site[f] = target;
    far_owner[target] = f;
  }
  std::vector<Placed> placed;
  for (int f = 0; f < o.fibres; ++f) placed.push_back({sites[near_site[f]], sites[far_site[f]]});

  // Compaction: the cross-section scales by F about its centre, supports with it.
  const Eigen::Vector2d centre(0.5 * side, 0.5 * side);
  Scene scene;
  scene.name = "tow_" + std::to_string(o.fibres) + "_seed_" + std::to_string(o.seed);
  scene.source = scene.name;
  // With a load path the scene is written before compaction and its steps compact it.
  const double written = o.steps > 0 ? 1.0 : o.compaction;
  if (o.first_compaction > 0.0 && o.steps > 1)
    for (int k = 0; k < o.steps; ++k)
      scene.steps.push_back(
          {o.first_compaction + (o.compaction - o.first_compaction) * k / (o.steps - 1), 1.0});
  else
    for (int k = 1; k <= o.steps; ++k)
      scene.steps.push_back({1.0 - (1.0 - o.compaction) * k / o.steps, 1.0});
  scene.contact.friction = o.friction;
  // With friction every step is a Tresca fixed point of inner problems, each iterated to the
  // tolerance: a compacted 19-fibre step at μ = 0.2 took 148 000 iterations in all. A compaction
  // sequence on the deformed fibres (the default) takes as many in its last steps, a sequence of
  // linearised problems each: 273 000 for 100 fibres and 100 slices at Vf 0.62.
  if (o.friction > 0.0 || o.steps > 0) scene.solver.max_iterations = 400000;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const Eigen::Vector2d y0 = centre + written * (placed[i].y0 - centre);
    const Eigen::Vector2d y1 = centre + written * (placed[i].y1 - centre);
    FibreSpec f;
    f.id = "F" + std::to_string(i);
    f.start = Eigen::Vector3d(0.0, y0[0], y0[1]);
    f.end = Eigen::Vector3d(o.length, y1[0], y1[1]);
    f.radius = r;
    f.youngs_modulus = o.youngs_modulus;
    scene.fibres.push_back(f);
  }
  const double half = 0.5 * written * side;
  scene.walls = {
      {"y_min", Eigen::Vector3d(0, centre[0] - half, 0), Eigen::Vector3d::UnitY()},
      {"y_max", Eigen::Vector3d(0, centre[0] + half, 0), -Eigen::Vector3d::UnitY()},
      {"z_min", Eigen::Vector3d(0, 0, centre[1] - half), Eigen::Vector3d::UnitZ()},
      {"z_max", Eigen::Vector3d(0, 0, centre[1] + half), -Eigen::Vector3d::UnitZ()},
  };
  scene.contact.slices = o.slices;
  scene.contact.axis = Eigen::Vector3d::UnitX();
  scene.contact.parallel_angle_deg = std::max(10.0, 2.0 * o.misalignment_deg);
  validate_scene(scene);
  return scene;
}

}  // namespace fibrecheck
