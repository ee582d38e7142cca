#include "unresolvable_overlap.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact_description.h"

namespace fibrecheck {

double immovable_compliance(const std::vector<Fibre>& fibres) {
  double scale = 0.0;
  for (const Fibre& f : fibres) scale = std::max(scale, std::pow(f.length, 3) / (48.0 * f.EI));
  return 1e-12 * scale;
}

std::optional<std::string> find_overlapping_supports(const std::vector<Fibre>& fibres,
                                                     double tolerance) {
  // The supports, swept in order of x: two closer than the sum of their radii overlap.
  struct Support {
    double x;
    int fibre;
    Eigen::Vector3d point;
    int s;  ///< 0 at the start, 1 at the end
  };
  std::vector<Support> supports;
  double widest = 0.0;
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    supports.push_back({fibres[f].start.x(), static_cast<int>(f), fibres[f].start, 0});
    supports.push_back({fibres[f].end.x(), static_cast<int>(f), fibres[f].end, 1});
    widest = std::max(widest, fibres[f].radius);
  }
  std::sort(supports.begin(), supports.end(),
            [](const Support& a, const Support& b) { return a.x < b.x; });
  for (std::size_t i = 0; i < supports.size(); ++i)
    for (std::size_t j = i + 1; j < supports.size() && supports[j].x - supports[i].x < 2 * widest;
         ++j) {
      const Support& a = supports[i];
      const Support& b = supports[j];
      if (a.fibre == b.fibre) continue;
      const Fibre& A = fibres[std::min(a.fibre, b.fibre)];
      const Fibre& B = fibres[std::max(a.fibre, b.fibre)];
      const double overlap = A.radius + B.radius - (a.point - b.point).norm();
      if (overlap > tolerance) {
        const Support& sa = a.fibre < b.fibre ? a : b;
        const Support& sb = a.fibre < b.fibre ? b : a;
        std::ostringstream out;
        out.precision(3);
        out << "overlap " << overlap << " mm between fibres " << A.id << " and " << B.id
            << " at s = " << sa.s << " of " << A.id << " (s = " << sb.s << " of " << B.id
            << "), their pinned supports at [" << sa.point.x() << ", " << sa.point.y() << ", "
            << sa.point.z() << "], where neither can move: it cannot be resolved";
        return out.str();
      }
    }
  return std::nullopt;
}

std::optional<std::string> find_unresolvable_overlap(const std::vector<Contact>& contacts,
                                                     const std::vector<double>& overlap,
                                                     const std::vector<double>& self_compliance,
                                                     double tolerance,
                                                     const std::vector<Fibre>& fibres,
                                                     const std::vector<WallSpec>& walls) {
  if (auto why = find_overlapping_supports(fibres, tolerance)) return why;
  // A pinned support behind a wall: the wall cannot push it out.
  for (const WallSpec& wall : walls)
    for (const Fibre& f : fibres)
      for (int end = 0; end < 2; ++end) {
        const Eigen::Vector3d& p = end == 0 ? f.start : f.end;
        const double overlap = f.radius - wall.normal.normalized().dot(p - wall.point);
        if (overlap > tolerance) {
          std::ostringstream out;
          out.precision(3);
          out << "overlap " << overlap << " mm between fibre " << f.id << " and wall " << wall.id
              << " at s = " << end << " of " << f.id << ", its pinned support at [" << p.x() << ", "
              << p.y() << ", " << p.z() << "], where it cannot move: it cannot be resolved";
          return out.str();
        }
      }
  const double immovable = immovable_compliance(fibres);
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (overlap[k] > tolerance && self_compliance[k] <= immovable) {
      std::ostringstream out;
      out.precision(3);
      out << "overlap " << overlap[k] << " mm between " << describe(contacts[k], fibres, walls)
          << " where neither can move (pinned supports): it cannot be resolved";
      return out.str();
    }
  return std::nullopt;
}

}  // namespace fibrecheck
