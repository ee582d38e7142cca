#include "deformed_test.h"

#include <algorithm>
#include <cmath>
#include <sstream>

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
  // From where the contact is measured to where it moved: a difference of two displacements on
  // the same fibre, so that an interpolation's own error (of the grid's spacing squared) cancels
  // for the short moves near the answer.
  std::vector<Eigen::Vector3d> at;
  const auto change = [&](int fibre, double from, double to) {
    displacements(fibre, {std::min(from, to), std::max(from, to)}, at);
    return Eigen::Vector3d(from <= to ? at[1] - at[0] : at[0] - at[1]);
  };
  DeformedTest test;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    Contact c = contacts[k];
    Eigen::Vector3d ua = u_a[k], ub = u_b[k];
    if (c.kind == ContactKind::point && detector.follow_crossing(grid_u, c, ua, ub)) {
      ua += change(c.a, contacts[k].s_a, c.s_a);
      ub += change(c.b, contacts[k].s_b, c.s_b);
    }
    const double gap = geometry.deformed_gap(c, ua, ub);
    if (c.force > 0.0)
      test.gap_where_pushing = std::max(test.gap_where_pushing, std::fabs(gap));
    else
      test.overlap_where_free = std::max(test.overlap_where_free, -gap);
  }
  return test;
}

void warn_where_the_seeds_test_fails(double overlap_tolerance, Result& r) {
  if (r.geometry != "deformed" || r.status != Status::converged) return;
  const DeformedTest& t = r.deformed_test;
  if (!(t.gap_where_pushing > overlap_tolerance || t.overlap_where_free > overlap_tolerance))
    return;
  std::ostringstream out;
  out.precision(3);
  out << "the seed's test on the deformed fibres is not met: a contact pushes across a gap of "
      << t.gap_where_pushing << " mm and one that does not push overlaps by "
      << t.overlap_where_free << " mm, above t_d = " << overlap_tolerance
      << " mm (a crossing may lie off the closest points of the deformed fibres)";
  r.warnings.push_back(out.str());
}

}  // namespace fibrecheck
