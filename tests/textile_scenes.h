#pragma once

// Scenes textile users build that the tow generator does not, built in code: a plain weave, and
// binder fibres pressed across a small tow on a floor. They have no closed forms; the tests hold
// their answers to the seed's own test, to each other and to Siconos.

#include <cmath>
#include <string>

#include "scene.h"

namespace fibrecheck::testing {

/// A plain weave: four fibres along x under a uniform load, pressed onto four along y held up by
/// point loads, every crossing overlapping by 2e-4 mm before the loads act and the fibres slightly
/// skewed, so that the closest points of the bent fibres slide from where the chords cross.
inline Scene plain_weave() {
  Scene s;
  s.name = "plain_weave";
  const double pitch = 0.12, length = 5 * pitch, r = 0.01;
  const double shift[4] = {0.004, -0.007, 0.002, -0.003}, skew[4] = {0.006, -0.004, 0.008, -0.006};
  const double offset[4] = {-0.005, 0.006, -0.002, 0.008};
  for (int i = 0; i < 4; ++i) {
    const double y = pitch * (i + 1) + shift[i];
    s.fibres.push_back(
        {"X" + std::to_string(i), {0, y, 0.0099}, {length, y + skew[i], 0.0099}, r, 80000});
    s.loads.push_back({"X" + std::to_string(i), LoadKind::distributed, 0.5, {0, 0, -2e-4}});
  }
  for (int j = 0; j < 4; ++j) {
    const double x = pitch * (j + 1) + offset[j];
    s.fibres.push_back({"Y" + std::to_string(j),
                        {x, 0, -0.0099},
                        {x - skew[j], length, -0.0099},
                        r,
                        80000 * (1 + 0.5 * j)});
    s.loads.push_back({"Y" + std::to_string(j), LoadKind::point, 0.35 + 0.1 * j, {0, 0, 6e-5}});
  }
  s.contact.slices = 20;
  s.output.samples = 51;
  return s;
}

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
