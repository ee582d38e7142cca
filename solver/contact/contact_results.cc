#include "contact_results.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace fibrecheck {

std::vector<ContactResult> contact_results(const std::vector<Contact>& contacts,
                                           const std::vector<Fibre>& fibres,
                                           const std::vector<WallSpec>& walls,
                                           const std::vector<Eigen::Vector3d>& force_on_a,
                                           const std::vector<Eigen::Vector3d>& u_a,
                                           const std::vector<Eigen::Vector3d>& u_b, double mu) {
  std::vector<ContactResult> results;
  std::map<std::tuple<int, int, int>, std::size_t> group;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (!(c.force > 0.0)) continue;
    const auto key = std::make_tuple(static_cast<int>(c.kind), c.a, c.b);
    auto it = group.find(key);
    if (it == group.end()) {
      ContactResult cr;
      cr.fibres = {fibres[c.a].id, c.kind == ContactKind::wall ? walls[c.b].id : fibres[c.b].id};
      cr.kind = to_string(c.kind);
      it = group.emplace(key, results.size()).first;
      results.push_back(cr);
    }
    ContactPoint p;
    p.position = c.s_a;
    const Eigen::Vector3d ac = fibres[c.a].point(c.s_a) + u_a[k];
    p.point = c.kind == ContactKind::wall
                  ? Eigen::Vector3d(ac - fibres[c.a].radius * c.normal)
                  : Eigen::Vector3d(0.5 * (ac + fibres[c.b].point(c.s_b) + u_b[k]));
    p.force = force_on_a[k];
    p.friction_force = c.friction;
    p.normal_force = p.force - c.friction;
    if (mu > 0.0) p.state = slips(c, mu) ? "slip" : "stick";
    results[it->second].points.push_back(p);
  }
  for (ContactResult& cr : results) {
    Eigen::Vector3d total = Eigen::Vector3d::Zero(), normal = total, friction = total;
    for (const ContactPoint& p : cr.points) {
      total += p.force;
      normal += p.normal_force;
      friction += p.friction_force;
    }
    cr.total_force = total.norm();
    cr.normal_force = normal.norm();
    cr.friction_force = friction.norm();
  }
  return results;
}

bool slips(const Contact& c, double mu) {
  return c.force > 0.0 && c.friction.norm() >= (1.0 - 1e-9) * mu * c.force;
}

namespace {

/// Coulomb's (or Tresca's) conditions with the disk radius `radius(k)` at each contact `active(k)`.
template <class Radius, class Active>
FrictionFigures disk_figures(const std::vector<Contact>& contacts, Radius radius, Active active) {
  FrictionFigures f;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const double size = c.friction.norm(), g = std::max(radius(k), 0.0);
    f.cone_residual = std::max(f.cone_residual, size - g);
    if (!active(k)) continue;
    if (!(g > 0.0)) {  // no friction can act: free to slip any way
      ++f.slipping;
      continue;
    }
    if (size < (1.0 - 1e-9) * g) {
      ++f.sticking;
      f.stick_residual = std::max(f.stick_residual, c.slip.norm());
      continue;
    }
    ++f.slipping;
    const Eigen::Vector3d direction = c.friction / size;
    const double along = c.slip.dot(direction);
    f.slip_residual =
        std::max(f.slip_residual, (c.slip - along * direction).norm() + std::max(0.0, -along));
  }
  return f;
}

}  // namespace

FrictionFigures friction_figures(const std::vector<Contact>& contacts, double mu,
                                 FrictionModel model) {
  FrictionFigures f = disk_figures(
      contacts, [&](std::size_t k) { return mu * contacts[k].force; },
      [&](std::size_t k) { return contacts[k].force > 0.0; });
  f.model = to_string(model);
  f.mu = mu;
  return f;
}

FrictionFigures tresca_figures(const std::vector<Contact>& contacts,
                               const Eigen::VectorXd& bounds) {
  return disk_figures(
      contacts, [&](std::size_t k) { return bounds[static_cast<Eigen::Index>(k)]; },
      [&](std::size_t k) {
        return contacts[k].force > 0.0 || bounds[static_cast<Eigen::Index>(k)] > 0.0;
      });
}

std::vector<WallResult> wall_results(const std::vector<Contact>& contacts,
                                     const std::vector<Fibre>& fibres,
                                     const std::vector<WallSpec>& walls) {
  std::vector<WallResult> results;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    WallResult wr;
    wr.id = walls[w].id;
    for (const Contact& c : contacts)
      if (c.kind == ContactKind::wall && c.b == static_cast<int>(w)) wr.force += c.force;
    const auto [p1, p2] = cross_section_axes(walls[w].normal);
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const Fibre& f : fibres)
      for (const Eigen::Vector3d& x : {f.start, f.end}) {
        const Eigen::Vector2d q(x.dot(p1), x.dot(p2));
        lo = lo.cwiseMin((q.array() - f.radius).matrix());
        hi = hi.cwiseMax((q.array() + f.radius).matrix());
      }
    wr.area = (hi - lo).prod();
    wr.pressure = wr.area > 0.0 ? wr.force / wr.area : 0.0;
    results.push_back(wr);
  }
  return results;
}

}  // namespace fibrecheck
