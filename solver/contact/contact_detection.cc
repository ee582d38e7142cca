#include "contact_detection.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "closest_points.h"
#include "slice_broad_phase.h"

namespace fibrecheck {

double candidate_margin(const std::vector<Fibre>& fibres, double factor) {
  return factor * smallest_radius(fibres);
}

ContactDetector::ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene,
                                 double margin)
    : ContactDetector(fibres, scene, margin, LineQuadrature::slices(scene.contact.slices)) {}

ContactDetector::ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene,
                                 double margin, LineQuadrature line)
    : geometry_(fibres, scene.walls, scene.contact.axis, scene.contact.geometry),
      line_(std::move(line)),
      margin_(margin) {
  const Eigen::Vector3d& axis = geometry_.tow_axis();
  std::tie(g1_, g2_) = cross_section_axes(axis);
  const int m = std::max(scene.contact.slices, 20);
  grid_.resize(m + 1);
  for (int j = 0; j <= m; ++j) grid_[j] = static_cast<double>(j) / m;
  x0_ = INFINITY;
  x1_ = -INFINITY;
  int others = 0;
  for (std::size_t i = 0; i < fibres.size(); ++i) {
    if (fibres[i].along_tow_axis) {
      tow_fibres_.push_back(static_cast<int>(i));
      x0_ = std::min({x0_, fibres[i].start.dot(axis), fibres[i].end.dot(axis)});
      x1_ = std::max({x1_, fibres[i].start.dot(axis), fibres[i].end.dot(axis)});
    } else {
      ++others;
    }
  }
  slicing_ = tow_fibres_.size() >= 2;
  point_pairs_possible_ = fibres.size() >= 2 && others >= 1;
  if (!slicing_) x0_ = 0, x1_ = 1;
}

Eigen::Vector3d ContactDetector::interpolate(
    const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int fibre, double s) const {
  const auto& u = grid_u[fibre];
  const int m = static_cast<int>(grid_.size()) - 1;
  const int j = std::min(std::max(static_cast<int>(std::floor(s * m)), 0), m - 1);
  const double w = s * m - j;
  return (1.0 - w) * u[j] + w * u[j + 1];
}

std::vector<Contact> ContactDetector::detect(
    const std::vector<std::vector<Eigen::Vector3d>>& grid_u) const {
  std::vector<Contact> contacts;
  if (slicing_) detect_lines(grid_u, contacts);
  if (point_pairs_possible_) detect_points(grid_u, contacts);
  if (walls()) detect_walls(grid_u, contacts);
  const bool deformed = geometry_.deformed();
  for (Contact& c : contacts) {
    // Linearised: placed on the undeformed fibres first, so that a crossing is displaced as the
    // fibres are at the chords' closest points, where it acts.
    if (!deformed) geometry_.place_on_undeformed(c);
    const Eigen::Vector3d u_a = interpolate(grid_u, c.a, c.s_a);
    const Eigen::Vector3d u_b = c.kind == ContactKind::wall ? Eigen::Vector3d::Zero().eval()
                                                            : interpolate(grid_u, c.b, c.s_b);
    if (deformed) geometry_.place(c, u_a, u_b);
    c.overlap = geometry_.overlap(c, u_a, u_b);
  }
  if (!deformed) {
    contacts.erase(std::remove_if(contacts.begin(), contacts.end(),
                                  [this](const Contact& c) {
                                    return c.kind != ContactKind::wall && !(c.overlap > -margin_);
                                  }),
                   contacts.end());
    return contacts;
  }
  // Crossings were placed where the chords cross; on the deformed fibres they move towards the
  // closest points of the displaced fibres nearby, and are measured there.
  for (Contact& c : contacts) {
    if (c.kind != ContactKind::point) continue;
    int steps = 0;
    while (steps < kDetectionSteps && follow_crossing(grid_u, c, interpolate(grid_u, c.a, c.s_a),
                                                      interpolate(grid_u, c.b, c.s_b)))
      ++steps;
    if (steps > 0) place_crossing(grid_u, c);
  }
  return contacts;
}

void ContactDetector::place_crossing(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                     Contact& c) const {
  const Eigen::Vector3d u_a = interpolate(grid_u, c.a, c.s_a);
  const Eigen::Vector3d u_b = interpolate(grid_u, c.b, c.s_b);
  geometry_.place_at(c, u_a, u_b);
  c.overlap = geometry_.overlap(c, u_a, u_b);
}

void ContactDetector::keep_crossing_places(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                           std::vector<Contact>& found,
                                           const std::vector<Contact>& before,
                                           const std::vector<long>& origin) const {
  if (!geometry_.deformed()) return;
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (found[i].kind != ContactKind::point || origin[i] < 0) continue;
    const Contact& was = before[static_cast<std::size_t>(origin[i])];
    found[i].s_a = was.s_a;
    found[i].s_b = was.s_b;
    place_crossing(grid_u, found[i]);
  }
}

bool ContactDetector::follow_crossings(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                       std::vector<Contact>& contacts,
                                       const std::vector<Eigen::Vector3d>& u_a,
                                       const std::vector<Eigen::Vector3d>& u_b, double gain) const {
  bool moved = false;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (contacts[k].kind == ContactKind::point)
      moved |= follow_crossing(grid_u, contacts[k], u_a[k], u_b[k], gain);
  return moved;
}

Eigen::Vector3d ContactDetector::deformed_tangent(
    const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int fibre, double s,
    const Eigen::Vector3d& u) const {
  const Fibre& f = geometry_.fibres()[fibre];
  const double tie = 1e-12;
  const auto right = std::upper_bound(grid_.begin(), grid_.end(), s + tie);
  const auto left = std::lower_bound(grid_.begin(), grid_.end(), s - tie);
  const std::size_t r = static_cast<std::size_t>(right - grid_.begin());
  Eigen::Vector3d slope;
  if (left == grid_.begin()) {
    slope = (grid_u[fibre][r] - u) / (grid_[r] - s);
  } else {
    const std::size_t l = static_cast<std::size_t>(left - grid_.begin()) - 1;
    const double h1 = s - grid_[l];
    const Eigen::Vector3d m1 = (u - grid_u[fibre][l]) / h1;
    if (right == grid_.end()) {
      slope = m1;
    } else {
      const double h2 = grid_[r] - s;
      const Eigen::Vector3d m2 = (grid_u[fibre][r] - u) / h2;
      slope = (h2 * m1 + h1 * m2) / (h1 + h2);
    }
  }
  return (f.end - f.start) + slope;
}

bool ContactDetector::follow_crossing(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                      Contact& c, const Eigen::Vector3d& u_a,
                                      const Eigen::Vector3d& u_b, double gain) const {
  const Fibre& fa = geometry_.fibres()[c.a];
  const Fibre& fb = geometry_.fibres()[c.b];
  const Eigen::Vector3d d = fb.point(c.s_b) + u_b - (fa.point(c.s_a) + u_a);
  const Eigen::Vector3d ta = deformed_tangent(grid_u, c.a, c.s_a, u_a);
  const Eigen::Vector3d tb = deformed_tangent(grid_u, c.b, c.s_b, u_b);
  // The tangent lines' closest points (Eqs. 4.22–4.23 on the lines): d + tb·δb − ta·δa ⟂ ta, tb.
  const double aa = ta.squaredNorm(), bb = tb.squaredNorm(), ab = ta.dot(tb);
  const double det = aa * bb - ab * ab;
  if (!(det > 1e-12 * aa * bb)) return false;
  const double ad = ta.dot(d), bd = tb.dot(d);
  const double window = 2.0 / static_cast<double>(grid_.size() - 1);
  const auto within = [window](double step, double s) {
    return std::clamp(s + std::clamp(step, -window, window), 0.0, 1.0);
  };
  const double s_a = within((bb * ad - ab * bd) / det, c.s_a);
  const double s_b = within((ab * ad - aa * bd) / det, c.s_b);
  const double closer = d.norm() - (d + tb * (s_b - c.s_b) - ta * (s_a - c.s_a)).norm();
  if (!(closer > std::max(gain, 1e-12 * (fa.radius + fb.radius)))) return false;
  c.s_a = s_a;
  c.s_b = s_b;
  return true;
}

void ContactDetector::detect_lines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                   std::vector<Contact>& out) const {
  // Deformed: the displaced centres within the margin. Linearised: the overlap along the
  // undeformed normal decides, and it can close while the displaced centres slide apart, so the
  // pairs are sought about the undeformed centres, each reaching as far as it has moved in the
  // slice's plane; detect() keeps those within the margin.
  const bool deformed = geometry_.deformed();
  std::vector<Eigen::Vector2d> centres;
  std::vector<double> radii, params, reach;
  std::vector<int> owner;
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < line_.size(); ++i) {
    const double x = slice_position(i);
    centres.clear();
    radii.clear();
    params.clear();
    owner.clear();
    reach.clear();
    for (int f : tow_fibres_) {
      const Fibre& fibre = geometry_.fibres()[f];
      const Eigen::Vector3d& axis = geometry_.tow_axis();
      const double along = (fibre.end - fibre.start).dot(axis);
      const double s = (x - fibre.start.dot(axis)) / along;
      if (!(s > 1e-12 && s < 1.0 - 1e-12)) continue;
      const Eigen::Vector3d u = interpolate(grid_u, f, s);
      const Eigen::Vector3d c = fibre.point(s) + (deformed ? u : Eigen::Vector3d::Zero());
      centres.emplace_back(c.dot(g1_), c.dot(g2_));
      if (!deformed) reach.push_back(Eigen::Vector2d(u.dot(g1_), u.dot(g2_)).norm());
      radii.push_back(fibre.radius);
      params.push_back(s);
      owner.push_back(f);
    }
    if (centres.size() > 2)
      slice_pairs(centres, radii, margin_, pairs, reach);
    else
      slice_pairs_all(centres, radii, margin_, pairs, reach);
    for (const auto& [p, q] : pairs) {
      const int first = owner[p] < owner[q] ? p : q, second = owner[p] < owner[q] ? q : p;
      Contact c;
      c.kind = ContactKind::line;
      c.a = owner[first];
      c.b = owner[second];
      c.slice = i;
      c.s_a = params[first];
      c.s_b = params[second];
      c.weight = line_.weight[i];  // Eq. 4.28: a slice carries 1/n of the line's force
      out.push_back(c);
    }
  }
}

void ContactDetector::closest_on_polylines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                           int a, int b, Contact& c, double& distance) const {
  distance = INFINITY;
  const Fibre& fa = geometry_.fibres()[a];
  const Fibre& fb = geometry_.fibres()[b];
  const int m = static_cast<int>(grid_.size()) - 1;
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector3d a1 = fa.point(grid_[i]) + grid_u[a][i];
    const Eigen::Vector3d a2 = fa.point(grid_[i + 1]) + grid_u[a][i + 1];
    for (int j = 0; j < m; ++j) {
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
  const std::vector<Fibre>& fibres = geometry_.fibres();
  const int n = static_cast<int>(fibres.size());
  const int m = static_cast<int>(grid_.size()) - 1;
  // Broad phase: boxes around each deformed polyline, swept along x. Linearised: boxes around
  // the chords, each reaching as far as its fibre has moved (the overlap at the chords' closest
  // points decides, in detect()).
  const bool deformed = geometry_.deformed();
  std::vector<Eigen::Vector3d> lo(n), hi(n);
  for (int f = 0; f < n; ++f) {
    const auto shift = [&](int j) { return deformed ? grid_u[f][j] : Eigen::Vector3d::Zero(); };
    lo[f] = hi[f] = fibres[f].start + shift(0);
    double moved = grid_u[f][0].norm();
    for (int j = 1; j <= m; ++j) {
      const Eigen::Vector3d p = fibres[f].point(grid_[j]) + shift(j);
      lo[f] = lo[f].cwiseMin(p);
      hi[f] = hi[f].cwiseMax(p);
      moved = std::max(moved, grid_u[f][j].norm());
    }
    const double reach = fibres[f].radius + 0.5 * margin_ + (deformed ? 0.0 : moved);
    lo[f].array() -= reach;
    hi[f].array() += reach;
  }
  std::vector<int> order(n);
  for (int f = 0; f < n; ++f) order[f] = f;
  std::sort(order.begin(), order.end(), [&](int x, int y) { return lo[x][0] < lo[y][0]; });
  for (int p = 0; p < n; ++p) {
    for (int q = p + 1; q < n && lo[order[q]][0] <= hi[order[p]][0]; ++q) {
      const int a = std::min(order[p], order[q]), b = std::max(order[p], order[q]);
      if (fibres[a].along_tow_axis && fibres[b].along_tow_axis && slicing_) continue;
      if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
      Contact c;
      c.kind = ContactKind::point;
      c.a = a;
      c.b = b;
      if (deformed) {
        double distance;
        closest_on_polylines(grid_u, a, b, c, distance);
        if (distance - (fibres[a].radius + fibres[b].radius) >= margin_) continue;
      }
      out.push_back(c);
    }
  }
}

void ContactDetector::detect_walls(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                   std::vector<Contact>& out) const {
  const std::vector<Fibre>& fibres = geometry_.fibres();
  const std::vector<WallSpec>& walls = geometry_.walls();
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    for (int j = 0; j < line_.size(); ++j) {
      const double s = line_.position[j];
      const Eigen::Vector3d centre = fibres[f].point(s) + interpolate(grid_u, f, s);
      for (std::size_t w = 0; w < walls.size(); ++w) {
        const double overlap = fibres[f].radius - walls[w].normal.dot(centre - walls[w].point);
        if (overlap <= -margin_) continue;
        Contact c;
        c.kind = ContactKind::wall;
        c.a = static_cast<int>(f);
        c.b = static_cast<int>(w);
        c.slice = j;
        c.s_a = s;
        c.normal = walls[w].normal;
        c.overlap = overlap;
        c.weight = line_.weight[j];
        out.push_back(c);
      }
    }
  }
}

}  // namespace fibrecheck
