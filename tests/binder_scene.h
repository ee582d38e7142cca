#pragma once

// A frictional scene users build that the tow generator does not, built in code: binder fibres
// pressed across a small tow on a floor. It has no closed form; the tests hold its answers to the
// seed's own test and to Siconos.

#include <cmath>
#include <string>

#include "scene.h"

namespace fibrecheck::testing {

/// Six tow fibres along x in two rows on a floor, slightly skewed, pressed down by three binder
/// fibres across them (1.5 times as thick, 2.5 times as stiff, at 50°, 80° and 65° to the tow),
/// μ = 0.2: frictional wedges of crossings, slices and the wall.
inline Scene binder_fibres_pressing_a_tow() {
  Scene s;
  s.name = "binder_fibres_pressing_a_tow";
  const double r = 0.01;
  const double y[3] = {0.2, 0.2205, 0.241}, skew[3] = {0.00015, -0.0001, 0.00005};
  for (int row = 0; row < 2; ++row)
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d start(0.0, y[a] + (row ? r : 0.0) + 1e-4 * a, row * 1.9 * r);
      const Eigen::Vector3d end =
          start + Eigen::Vector3d(1.0, (row ? 1.0 : -1.0) * skew[a], 8e-5 * (a - 1));
      s.fibres.push_back({"T" + std::to_string(3 * row + a), start, end, r, 80000});
    }
  const double angle[3] = {50, 80, 65}, load[3] = {-4e-4, -6e-4, -5e-4};
  for (int j = 0; j < 3; ++j) {
    const double theta = angle[j] * M_PI / 180.0;
    const Eigen::Vector3d centre(0.25 + 0.25 * j, 0.2 + 3 * r, 3.9 * r);
    const Eigen::Vector3d half(0.3 * std::cos(theta), 0.3 * std::sin(theta), 0.0);
    s.fibres.push_back({"B" + std::to_string(j), centre - half, centre + half, 1.5 * r, 200000});
    s.loads.push_back({"B" + std::to_string(j), LoadKind::point, 0.5, {0, 0, load[j]}});
  }
  s.walls.push_back({"floor", {0, 0, -1.02 * r}, {0, 0, 1}});
  s.contact.slices = 20;
  s.contact.friction = 0.2;
  s.output.samples = 51;
  return s;
}

}  // namespace fibrecheck::testing
