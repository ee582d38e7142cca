#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "cross_section_axes.h"
#include "scene.h"

namespace fibrecheck {

/// A fibre as the beam model sees it (seed §4.3.1): a straight chord of length L between two pinned
/// supports, bending stiffness EI = E·πr⁴/4, and the local frame (t, e1, e2). Every force is
/// resolved into the two planes (t, e1) and (t, e2); each is a 2-D simply supported beam.
struct Fibre {
  std::string id;
  Eigen::Vector3d start, end;
  Eigen::Vector3d t, e1, e2;  ///< unit axis and the two bending directions
  double radius;              ///< mm
  double length;              ///< L, mm
  double EI;                  ///< N·mm²
  bool along_tow_axis;        ///< within the scene's parallel angle of the tow axis

  /// Undeformed centreline point at fraction s of the length.
  Eigen::Vector3d point(double s) const { return start + s * (end - start); }
};

/// Second moment of area of a circular cross-section, I = πr⁴/4 (mm⁴).
double second_moment_of_area(double radius);

/// Builds the frame: e1/e2 follow the global cross-section axes of the tow axis `axis` (for axis x:
/// e1 ≈ y, e2 ≈ z), projected orthogonal to the fibre.
Fibre make_fibre(const FibreSpec& spec, const Eigen::Vector3d& axis, double parallel_angle_deg);

/// Every fibre of a scene, in its order, with the scene's tow axis and parallel angle.
std::vector<Fibre> make_fibres(const Scene& scene);

/// The smallest radius of the fibres (mm); infinite when there are none.
double smallest_radius(const std::vector<Fibre>& fibres);

}  // namespace fibrecheck
