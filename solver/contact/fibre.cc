#include "fibre.h"

#include <algorithm>
#include <cmath>

namespace fibrecheck {

double second_moment_of_area(double radius) {
  return M_PI * std::pow(radius, 4) / 4.0;
}

Fibre make_fibre(const FibreSpec& spec, const Eigen::Vector3d& axis, double parallel_angle_deg) {
  Fibre f;
  f.id = spec.id;
  f.start = spec.start;
  f.end = spec.end;
  f.radius = spec.radius;
  f.length = (spec.end - spec.start).norm();
  f.EI = spec.youngs_modulus * second_moment_of_area(spec.radius);
  f.t = (spec.end - spec.start) / f.length;
  f.along_tow_axis =
      std::fabs(f.t.dot(axis.normalized())) >= std::cos(parallel_angle_deg * M_PI / 180.0);
  const auto [g1, g2] = cross_section_axes(axis);
  // e1 follows g1 projected off the fibre; if the fibre runs along g1, g2 takes its place.
  Eigen::Vector3d e1 = g1 - g1.dot(f.t) * f.t;
  if (e1.norm() < 0.5) e1 = g2 - g2.dot(f.t) * f.t;
  f.e1 = e1.normalized();
  f.e2 = f.t.cross(f.e1);
  return f;
}

}  // namespace fibrecheck

namespace fibrecheck {

std::vector<Fibre> make_fibres(const Scene& scene) {
  std::vector<Fibre> fibres;
  fibres.reserve(scene.fibres.size());
  for (const FibreSpec& spec : scene.fibres)
    fibres.push_back(make_fibre(spec, scene.contact.axis, scene.contact.parallel_angle_deg));
  return fibres;
}

double smallest_radius(const std::vector<Fibre>& fibres) {
  double r = INFINITY;
  for (const Fibre& f : fibres) r = std::min(r, f.radius);
  return r;
}

}  // namespace fibrecheck
