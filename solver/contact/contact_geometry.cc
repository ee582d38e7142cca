#include "contact_geometry.h"

#include "closest_points.h"
#include "parallel_work.h"

namespace fibrecheck {

ContactGeometry::ContactGeometry(const std::vector<Fibre>& fibres,
                                 const std::vector<WallSpec>& walls,
                                 const Eigen::Vector3d& tow_axis, ContactGeometryModel model)
    : fibres_(fibres), walls_(walls), model_(model), axis_(tow_axis.normalized()) {
  g2_ = cross_section_axes(axis_).second;
}

void ContactGeometry::set_tangents(Contact& c) const {
  if (c.kind == ContactKind::point) {
    c.tangents = 2;
    c.tangent = cross_section_axes(c.normal).first;
    return;
  }
  // Slices and wall stations: the cross-section plane's line ⊥ n (none if n is along the axis).
  const Eigen::Vector3d t = axis_.cross(c.normal);
  c.tangents = t.norm() > 1e-9 ? 1 : 0;
  c.tangent = c.tangents ? Eigen::Vector3d(t.normalized()) : Eigen::Vector3d::Zero();
}

void ContactGeometry::place_on_undeformed(Contact& c) const {
  place_normal(c, true);
  set_tangents(c);
}

void ContactGeometry::place(Contact& c, const Eigen::Vector3d& u_a,
                            const Eigen::Vector3d& u_b) const {
  place_on_undeformed(c);
  if (deformed()) follow(c, u_a, u_b);
}

void ContactGeometry::place_at(Contact& c, const Eigen::Vector3d& u_a,
                               const Eigen::Vector3d& u_b) const {
  place_normal(c, false);
  set_tangents(c);
  if (deformed()) follow(c, u_a, u_b);
}

void ContactGeometry::place_normal(Contact& c, bool at_chords) const {
  if (c.kind == ContactKind::wall) return;  // the wall's normal, at its station
  const Fibre& fa = fibres_[c.a];
  const Fibre& fb = fibres_[c.b];
  if (c.kind == ContactKind::point && at_chords) {
    // Eqs. 4.16–4.24 on the straight chords.
    const ClosestPoints cp = segment_closest_points(fa.start, fa.end, fb.start, fb.end);
    c.s_a = cp.mu_a;
    c.s_b = cp.mu_b;
  }
  Eigen::Vector3d difference = fb.point(c.s_b) - fa.point(c.s_a);
  if (c.kind == ContactKind::line) difference -= difference.dot(axis_) * axis_;
  const double distance = difference.norm();
  // Centres closer than half the contact distance give no trustworthy direction (two fibres
  // passing through each other have no preferred side): a fixed one is taken and reported.
  c.normal_held = distance < 0.5 * (fa.radius + fb.radius);
  if (!c.normal_held) {
    c.normal = difference / distance;
    return;
  }
  Eigen::Vector3d n = c.kind == ContactKind::point ? fa.t.cross(fb.t) : Eigen::Vector3d(g2_);
  if (n.norm() < 1e-12) n = g2_;
  c.normal = n.normalized();
}

Eigen::Vector3d ContactGeometry::centre_difference(const Contact& c, const Eigen::Vector3d& u_a,
                                                   const Eigen::Vector3d& u_b) const {
  Eigen::Vector3d difference = fibres_[c.b].point(c.s_b) + u_b - (fibres_[c.a].point(c.s_a) + u_a);
  if (c.kind == ContactKind::line) difference -= difference.dot(axis_) * axis_;
  return difference;
}

double ContactGeometry::overlap_along_normal(const Contact& c, const Eigen::Vector3d& u_a,
                                             const Eigen::Vector3d& u_b) const {
  const Eigen::Vector3d ac = fibres_[c.a].point(c.s_a) + u_a;
  if (c.kind == ContactKind::wall)
    return fibres_[c.a].radius - c.normal.dot(ac - walls_[c.b].point);
  Eigen::Vector3d difference = fibres_[c.b].point(c.s_b) + u_b - ac;
  if (c.kind == ContactKind::line) difference -= difference.dot(axis_) * axis_;
  return fibres_[c.a].radius + fibres_[c.b].radius - c.normal.dot(difference);
}

double ContactGeometry::overlap(const Contact& c, const Eigen::Vector3d& u_a,
                                const Eigen::Vector3d& u_b) const {
  if (!deformed() || c.kind == ContactKind::wall) return overlap_along_normal(c, u_a, u_b);
  const double radii = fibres_[c.a].radius + fibres_[c.b].radius;
  const Eigen::Vector3d difference = centre_difference(c, u_a, u_b);
  return keeps_normal(c, difference) ? radii - c.normal.dot(difference) : radii - difference.norm();
}

bool ContactGeometry::passed_through(const Contact& c, const Eigen::Vector3d& u_a,
                                     const Eigen::Vector3d& u_b) const {
  return c.kind != ContactKind::wall && centre_difference(c, u_a, u_b).dot(c.normal) <= 0.0;
}

// Centres closer than half the contact distance give no trustworthy direction, and centres that
// have passed through each other one that would push them on through.
bool ContactGeometry::keeps_normal(const Contact& c, const Eigen::Vector3d& difference) const {
  return difference.norm() < 0.5 * (fibres_[c.a].radius + fibres_[c.b].radius) ||
         difference.dot(c.normal) <= 0.0;
}

double ContactGeometry::deformed_gap(const Contact& c, const Eigen::Vector3d& u_a,
                                     const Eigen::Vector3d& u_b) const {
  if (c.kind == ContactKind::wall) return -overlap_along_normal(c, u_a, u_b);
  return centre_difference(c, u_a, u_b).norm() - (fibres_[c.a].radius + fibres_[c.b].radius);
}

Eigen::Vector3d ContactGeometry::deformed_normal(const Contact& c, const Eigen::Vector3d& u_a,
                                                 const Eigen::Vector3d& u_b) const {
  if (c.kind == ContactKind::wall) return c.normal;
  const Eigen::Vector3d difference = centre_difference(c, u_a, u_b);
  const double distance = difference.norm();
  return distance > 1e-12 * (fibres_[c.a].radius + fibres_[c.b].radius)
             ? Eigen::Vector3d(difference / distance)
             : c.normal;
}

void ContactGeometry::follow(Contact& c, const Eigen::Vector3d& u_a,
                             const Eigen::Vector3d& u_b) const {
  if (c.kind == ContactKind::wall) return;
  const Eigen::Vector3d difference = centre_difference(c, u_a, u_b);
  if (keeps_normal(c, difference)) return;
  turn(c, difference / difference.norm());
}

void ContactGeometry::turn(Contact& c, const Eigen::Vector3d& normal) const {
  c.normal = normal;
  set_tangents(c);
  const double size = c.friction.norm();
  const Eigen::Vector3d turned = c.tangential(c.friction);
  const double left = turned.norm();
  c.friction = left > 1e-12 * size ? Eigen::Vector3d(size / left * turned) : turned;
}

void ContactGeometry::measure(std::vector<Contact>& contacts,
                              const std::vector<Eigen::Vector3d>& u_a,
                              const std::vector<Eigen::Vector3d>& u_b, bool slip,
                              bool follow_normals) const {
  const int count = static_cast<int>(contacts.size());
  Contact* const contact = contacts.data();
  const Eigen::Vector3d* const side_a = u_a.data();
  const Eigen::Vector3d* const side_b = u_b.data();
  const bool follow_them = deformed() && follow_normals;
  const bool linear = !follow_them;
#pragma omp parallel for schedule(static) if (count > kParallelContacts)
  for (int k = 0; k < count; ++k) {
    Contact& c = contact[k];
    if (follow_them) follow(c, side_a[k], side_b[k]);
    c.overlap =
        linear ? overlap_along_normal(c, side_a[k], side_b[k]) : overlap(c, side_a[k], side_b[k]);
    if (slip) c.slip = c.tangential(c.relative(side_a[k], side_b[k]) - c.origin);
  }
}

}  // namespace fibrecheck
