#include "contact_detection.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "beam.h"
#include "closest_points.h"
#include "slice_broad_phase.h"

namespace fibrecheck {

const char* to_string(ContactKind kind) {
  switch (kind) {
    case ContactKind::point:
      return "point";
    case ContactKind::line:
      return "line";
    case ContactKind::wall:
      return "wall";
  }
  return "?";
}

std::vector<long> carry_over(const std::vector<Contact>& previous, std::vector<Contact>& found) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t k = 0; k < previous.size(); ++k) index[previous[k].key()] = k;
  std::vector<long> origin(found.size(), -1);
  for (std::size_t i = 0; i < found.size(); ++i) {
    auto it = index.find(found[i].key());
    if (it == index.end()) continue;
    const Contact& old = previous[it->second];
    found[i].force = old.force;
    found[i].friction = old.friction;
    origin[i] = static_cast<long>(it->second);
    index.erase(it);
  }
  // In the order of `previous`, so that the result does not depend on the hash table's.
  std::vector<std::size_t> left;
  for (const auto& [key, k] : index)
    if (previous[k].force > 0.0) left.push_back(k);
  std::sort(left.begin(), left.end());
  for (std::size_t k : left) {
    found.push_back(previous[k]);
    origin.push_back(static_cast<long>(k));
  }
  return origin;
}

ContactDetector::ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene,
                                 double margin)
    : fibres_(fibres),
      walls_(scene.walls),
      axis_(scene.contact.axis.normalized()),
      margin_(margin) {
  const int n = scene.contact.slices;
  for (int i = 0; i < n; ++i) station_.push_back((i + 0.5) / n), weight_.push_back(1.0 / n);
  std::tie(g1_, g2_) = cross_section_axes(axis_);
  const int m = std::max(scene.contact.slices, 20);
  grid_.resize(m + 1);
  for (int j = 0; j <= m; ++j) grid_[j] = static_cast<double>(j) / m;
  x0_ = INFINITY;
  x1_ = -INFINITY;
  int others = 0;
  for (std::size_t i = 0; i < fibres_.size(); ++i) {
    if (fibres_[i].along_tow_axis) {
      tow_fibres_.push_back(static_cast<int>(i));
      x0_ = std::min({x0_, fibres_[i].start.dot(axis_), fibres_[i].end.dot(axis_)});
      x1_ = std::max({x1_, fibres_[i].start.dot(axis_), fibres_[i].end.dot(axis_)});
    } else {
      ++others;
    }
  }
  slicing_ = tow_fibres_.size() >= 2;
  point_pairs_possible_ = fibres_.size() >= 2 && others >= 1;
  if (!slicing_) x0_ = 0, x1_ = 1;
}

void ContactDetector::use_gauss_stations(int cells) {
  station_.clear();
  weight_.clear();
  const double offset = 0.5 / std::sqrt(3.0);  // Gauss points ±1/√3 on a cell of length 1
  for (int i = 0; i < cells; ++i)
    for (double g : {-offset, offset}) {
      station_.push_back((i + 0.5 + g) / cells);
      weight_.push_back(0.5 / cells);
    }
}

Eigen::Vector3d ContactDetector::interpolate(
    const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int fibre, double s) const {
  const auto& u = grid_u[fibre];
  const int m = static_cast<int>(grid_.size()) - 1;
  const int j = std::min(std::max(static_cast<int>(std::floor(s * m)), 0), m - 1);
  const double w = s * m - j;
  return (1.0 - w) * u[j] + w * u[j + 1];
}

void ContactDetector::place_on_undeformed(Contact& c) const {
  if (c.kind == ContactKind::wall) return;  // the wall's normal, at its station
  const Fibre& fa = fibres_[c.a];
  const Fibre& fb = fibres_[c.b];
  if (c.kind == ContactKind::point) {
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

std::vector<Contact> ContactDetector::detect(
    const std::vector<std::vector<Eigen::Vector3d>>& grid_u) const {
  std::vector<Contact> contacts;
  if (slicing_) detect_lines(grid_u, contacts);
  if (point_pairs_possible_) detect_points(grid_u, contacts);
  if (!walls_.empty()) detect_walls(grid_u, contacts);
  for (Contact& c : contacts) {
    place_on_undeformed(c);
    c.overlap = overlap_along_normal(c, interpolate(grid_u, c.a, c.s_a),
                                     c.kind == ContactKind::wall
                                         ? Eigen::Vector3d::Zero().eval()
                                         : interpolate(grid_u, c.b, c.s_b));
    c.compliance = self_compliance(c);
  }
  return contacts;
}

void ContactDetector::detect_lines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                   std::vector<Contact>& out) const {
  std::vector<Eigen::Vector2d> centres;
  std::vector<double> radii, params;
  std::vector<int> owner;
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < slice_count(); ++i) {
    const double x = slice_position(i);
    centres.clear();
    radii.clear();
    params.clear();
    owner.clear();
    for (int f : tow_fibres_) {
      const Fibre& fibre = fibres_[f];
      const double along = (fibre.end - fibre.start).dot(axis_);
      const double s = (x - fibre.start.dot(axis_)) / along;
      if (!(s > 1e-12 && s < 1.0 - 1e-12)) continue;
      const Eigen::Vector3d c = fibre.point(s) + interpolate(grid_u, f, s);
      centres.emplace_back(c.dot(g1_), c.dot(g2_));
      radii.push_back(fibre.radius);
      params.push_back(s);
      owner.push_back(f);
    }
    if (centres.size() > 2)
      slice_pairs(centres, radii, margin_, pairs);
    else
      slice_pairs_all(centres, radii, margin_, pairs);
    for (const auto& [p, q] : pairs) {
      const int first = owner[p] < owner[q] ? p : q, second = owner[p] < owner[q] ? q : p;
      Contact c;
      c.kind = ContactKind::line;
      c.a = owner[first];
      c.b = owner[second];
      c.slice = i;
      c.s_a = params[first];
      c.s_b = params[second];
      c.step_scale = weight_[i];  // Eq. 4.28: a slice carries 1/n of the line's force
      out.push_back(c);
    }
  }
}

void ContactDetector::closest_on_polylines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                           int a, int b, int ia0, int ia1, int ib0, int ib1,
                                           Contact& c, double& distance) const {
  distance = INFINITY;
  const Fibre& fa = fibres_[a];
  const Fibre& fb = fibres_[b];
  for (int i = ia0; i < ia1; ++i) {
    const Eigen::Vector3d a1 = fa.point(grid_[i]) + grid_u[a][i];
    const Eigen::Vector3d a2 = fa.point(grid_[i + 1]) + grid_u[a][i + 1];
    for (int j = ib0; j < ib1; ++j) {
      const Eigen::Vector3d b1 = fb.point(grid_[j]) + grid_u[b][j];
      const Eigen::Vector3d b2 = fb.point(grid_[j + 1]) + grid_u[b][j + 1];
      const ClosestPoints cp = segment_closest_points(a1, a2, b1, b2);
      if (cp.distance < distance) {
        distance = cp.distance;
        c.s_a = grid_[i] + cp.mu_a * (grid_[i + 1] - grid_[i]);
        c.s_b = grid_[j] + cp.mu_b * (grid_[j + 1] - grid_[j]);
      }
    }
  }
}

void ContactDetector::detect_points(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                    std::vector<Contact>& out) const {
  const int n = static_cast<int>(fibres_.size());
  const int m = static_cast<int>(grid_.size()) - 1;
  // Broad phase: boxes around each deformed polyline, swept along x.
  std::vector<Eigen::Vector3d> lo(n), hi(n);
  for (int f = 0; f < n; ++f) {
    lo[f] = hi[f] = fibres_[f].start + grid_u[f][0];
    for (int j = 1; j <= m; ++j) {
      const Eigen::Vector3d p = fibres_[f].point(grid_[j]) + grid_u[f][j];
      lo[f] = lo[f].cwiseMin(p);
      hi[f] = hi[f].cwiseMax(p);
    }
    const double reach = fibres_[f].radius + 0.5 * margin_;
    lo[f].array() -= reach;
    hi[f].array() += reach;
  }
  std::vector<int> order(n);
  for (int f = 0; f < n; ++f) order[f] = f;
  std::sort(order.begin(), order.end(), [&](int x, int y) { return lo[x][0] < lo[y][0]; });
  for (int p = 0; p < n; ++p) {
    for (int q = p + 1; q < n && lo[order[q]][0] <= hi[order[p]][0]; ++q) {
      const int a = std::min(order[p], order[q]), b = std::max(order[p], order[q]);
      if (fibres_[a].along_tow_axis && fibres_[b].along_tow_axis && slicing_) continue;
      if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
      Contact c;
      c.kind = ContactKind::point;
      c.a = a;
      c.b = b;
      double distance;
      closest_on_polylines(grid_u, a, b, 0, m, 0, m, c, distance);
      const double radii = fibres_[a].radius + fibres_[b].radius;
      if (distance - radii >= margin_) continue;
      out.push_back(c);
    }
  }
}

void ContactDetector::detect_walls(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                   std::vector<Contact>& out) const {
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    for (int j = 0; j < slice_count(); ++j) {
      const double s = station_[j];
      const Eigen::Vector3d centre = fibres_[f].point(s) + interpolate(grid_u, f, s);
      for (std::size_t w = 0; w < walls_.size(); ++w) {
        const double overlap = fibres_[f].radius - walls_[w].normal.dot(centre - walls_[w].point);
        if (overlap <= -margin_) continue;
        Contact c;
        c.kind = ContactKind::wall;
        c.a = static_cast<int>(f);
        c.b = static_cast<int>(w);
        c.slice = j;
        c.s_a = s;
        c.normal = walls_[w].normal;
        c.overlap = overlap;
        c.step_scale = weight_[j];
        out.push_back(c);
      }
    }
  }
}

void ContactDetector::measure(std::vector<Contact>& contacts,
                              const std::vector<Eigen::Vector3d>& u_a,
                              const std::vector<Eigen::Vector3d>& u_b) const {
  const int count = static_cast<int>(contacts.size());
  Contact* const contact = contacts.data();
  const Eigen::Vector3d* const side_a = u_a.data();
  const Eigen::Vector3d* const side_b = u_b.data();
#pragma omp parallel for schedule(static) if (count > 4096)
  for (int k = 0; k < count; ++k)
    contact[k].overlap = overlap_along_normal(contact[k], side_a[k], side_b[k]);
}

double ContactDetector::overlap_along_normal(const Contact& c, const Eigen::Vector3d& u_a,
                                             const Eigen::Vector3d& u_b) const {
  const Eigen::Vector3d ac = fibres_[c.a].point(c.s_a) + u_a;
  if (c.kind == ContactKind::wall)
    return fibres_[c.a].radius - c.normal.dot(ac - walls_[c.b].point);
  Eigen::Vector3d difference = fibres_[c.b].point(c.s_b) + u_b - ac;
  if (c.kind == ContactKind::line) difference -= difference.dot(axis_) * axis_;
  return fibres_[c.a].radius + fibres_[c.b].radius - c.normal.dot(difference);
}

double ContactDetector::self_compliance(const Contact& c) const {
  auto along = [&](int f, double s) {
    const Fibre& fibre = fibres_[f];
    const double axial = c.normal.dot(fibre.t);
    return point_compliance(s * fibre.length, fibre.length, fibre.EI) * (1.0 - axial * axial);
  };
  double w = along(c.a, c.s_a);
  if (c.kind != ContactKind::wall) w += along(c.b, c.s_b);
  return w;
}

std::string ContactDetector::describe(const Contact& c) const {
  std::ostringstream out;
  out.precision(4);
  if (c.kind == ContactKind::wall)
    out << "fibre " << fibres_[c.a].id << " and wall " << walls_[c.b].id << " at s = " << c.s_a
        << " of " << fibres_[c.a].id;
  else
    out << "fibres " << fibres_[c.a].id << " and " << fibres_[c.b].id << " at s = " << c.s_a
        << " of " << fibres_[c.a].id << " (s = " << c.s_b << " of " << fibres_[c.b].id << ")";
  if (c.kind == ContactKind::line) out << ", slice " << c.slice;
  return out.str();
}

}  // namespace fibrecheck
