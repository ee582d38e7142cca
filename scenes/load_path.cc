#include "load_path.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "cross_section_axes.h"

namespace fibrecheck {

namespace {

/// The low and high wall along g when two opposite walls (normals +g and −g) bound the section.
std::pair<double, double> walls_along(const Scene& scene, const Eigen::Vector3d& g) {
  double low = -INFINITY, high = INFINITY;
  for (const WallSpec& w : scene.walls) {
    const Eigen::Vector3d n = w.normal.normalized();
    if (n.dot(g) > 1.0 - 1e-9) low = std::max(low, w.point.dot(g));
    if (n.dot(g) < -1.0 + 1e-9) high = std::min(high, w.point.dot(g));
  }
  return {low, high};
}

/// The middle of the walls' box where two pairs of opposite walls bound the section, else the
/// mean of the fibres' supports.
Eigen::Vector3d tow_centre(const Scene& scene) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const FibreSpec& f : scene.fibres) centre += f.start + f.end;
  centre /= 2.0 * static_cast<double>(scene.fibres.size());
  const auto [g1, g2] = cross_section_axes(scene.contact.axis.normalized());
  const auto [low1, high1] = walls_along(scene, g1);
  const auto [low2, high2] = walls_along(scene, g2);
  if (std::isfinite(low1) && std::isfinite(high1) && std::isfinite(low2) && std::isfinite(high2))
    centre +=
        (0.5 * (low1 + high1) - centre.dot(g1)) * g1 + (0.5 * (low2 + high2) - centre.dot(g2)) * g2;
  return centre;
}

}  // namespace

Scene scene_at_step(const Scene& scene, const LoadStep& step) {
  Scene s = scene;
  s.steps.clear();
  const Eigen::Vector3d axis = scene.contact.axis.normalized();
  const Eigen::Vector3d centre = tow_centre(scene);
  auto compact = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - centre;
    const Eigen::Vector3d along = d.dot(axis) * axis;
    return Eigen::Vector3d(centre + along + step.compaction * (d - along));
  };
  for (FibreSpec& f : s.fibres) {
    f.start = compact(f.start);
    f.end = compact(f.end);
  }
  for (WallSpec& w : s.walls) w.point = compact(w.point);
  for (LoadSpec& l : s.loads) l.force *= step.load_factor;
  return s;
}

double fibre_volume_fraction(const Scene& scene) {
  double fibres = 0.0;
  for (const FibreSpec& f : scene.fibres) fibres += M_PI * f.radius * f.radius;
  const Eigen::Vector3d axis = scene.contact.axis.normalized();
  const auto [g1, g2] = cross_section_axes(axis);
  // Opposite walls (normals ±g): the distance between them along g.
  auto span = [&](const Eigen::Vector3d& g) {
    const auto [low, high] = walls_along(scene, g);
    return std::isfinite(low) && std::isfinite(high) ? high - low : NAN;
  };
  double area = span(g1) * span(g2);
  if (!std::isfinite(area)) {
    Eigen::Vector2d low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
    for (const FibreSpec& f : scene.fibres)
      for (const Eigen::Vector3d& p : {f.start, f.end}) {
        const Eigen::Vector2d q(p.dot(g1), p.dot(g2));
        low = low.cwiseMin(q - Eigen::Vector2d::Constant(f.radius));
        high = high.cwiseMax(q + Eigen::Vector2d::Constant(f.radius));
      }
    area = (high - low).prod();
  }
  return area > 0.0 ? fibres / area : 0.0;
}

StepResult step_result(const Scene& stepped, const LoadStep& step, const Result& r) {
  StepResult e;
  e.compaction = step.compaction;
  e.load_factor = step.load_factor;
  e.fibre_volume_fraction = fibre_volume_fraction(stepped);
  for (const WallResult& w : r.walls) e.wall_pressure.emplace_back(w.id, w.pressure);
  e.strain_energy = r.strain_energy;
  std::size_t sides = 0;
  for (const ContactResult& c : r.contacts) sides += c.points.size() * (c.kind == "wall" ? 1 : 2);
  e.contacts_per_fibre =
      stepped.fibres.empty() ? 0.0 : static_cast<double>(sides) / stepped.fibres.size();
  e.iterations = r.iterations;
  e.geometric_updates = r.geometric_updates;
  e.fixed_point_updates = r.friction ? r.friction->fixed_point_updates : 0;
  e.stick_residual = r.friction ? r.friction->stick_residual : 0.0;
  e.slip_residual = r.friction ? r.friction->slip_residual : 0.0;
  e.wall_time_s = r.wall_time_s;
  e.status = r.status;
  return e;
}

}  // namespace fibrecheck
