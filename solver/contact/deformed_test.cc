#include "deformed_test.h"

#include <algorithm>
#include <cmath>

namespace fibrecheck {

DeformedTest deformed_test(const ContactDetector& detector, const std::vector<Contact>& contacts,
                           const std::vector<Eigen::Vector3d>& u_a,
                           const std::vector<Eigen::Vector3d>& u_b,
                           const FibreDisplacements& displacements) {
  const ContactGeometry& geometry = detector.geometry();
  std::vector<std::vector<Eigen::Vector3d>> grid_u(geometry.fibres().size());
  for (const Contact& c : contacts)
    if (c.kind == ContactKind::point)
      for (int f : {c.a, c.b})
        if (grid_u[f].empty()) displacements(f, detector.grid(), grid_u[f]);
  DeformedTest test;
  std::vector<Eigen::Vector3d> at(1);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    Contact c = contacts[k];
    Eigen::Vector3d ua = u_a[k], ub = u_b[k];
    if (c.kind == ContactKind::point && detector.follow_crossing(grid_u, c, ua, ub)) {
      displacements(c.a, {c.s_a}, at);
      ua = at[0];
      displacements(c.b, {c.s_b}, at);
      ub = at[0];
    }
    const double gap = geometry.deformed_gap(c, ua, ub);
    if (c.force > 0.0)
      test.gap_where_pushing = std::max(test.gap_where_pushing, std::fabs(gap));
    else
      test.overlap_where_free = std::max(test.overlap_where_free, -gap);
  }
  return test;
}

}  // namespace fibrecheck
