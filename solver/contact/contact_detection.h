#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "contact_geometry.h"
#include "fibre.h"
#include "line_quadrature.h"
#include "scene.h"

namespace fibrecheck {

/// Candidates are found this fraction of the smallest radius before they touch.
constexpr double kCandidateMarginFactor = 0.1;

/// The candidate margin (mm): `factor` times the smallest fibre radius.
double candidate_margin(const std::vector<Fibre>& fibres, double factor = kCandidateMarginFactor);

/// Finds the candidate contacts of a deformed state (seed §4.3.3):
///  - point contacts between fibres that cross, by the closest points of their deformed
///    centrelines, each approximated by straight segments (Eqs. 4.16–4.24);
///  - line contacts between tow fibres, by cross-sections ("slices") perpendicular to the tow
///    axis, each a point contact at its slice (Figures 4.11–4.12), pairs found by a broad phase;
///  - fibre–wall contacts at the same quadrature along each fibre.
/// A candidate is any pair closer than the margin. Its place, normal and overlap are then those of
/// ContactGeometry (the undeformed fibres).
class ContactDetector {
 public:
  /// Line contacts at `line` (default: the scene's n slices).
  ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene, double margin);
  ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene, double margin,
                  LineQuadrature line);

  /// Fractions of the length at which each fibre's deformed centreline is sampled for detection:
  /// m + 1 equal steps, m = max(n, 20) for n slices.
  const std::vector<double>& grid() const { return grid_; }

  /// All candidate contacts of the deformed state given by each fibre's displacements (mm) at
  /// `grid()` (`grid_u[fibre][j]`). Forces are zero; places, normals and overlaps set.
  std::vector<Contact> detect(const std::vector<std::vector<Eigen::Vector3d>>& grid_u) const;

  const ContactGeometry& geometry() const { return geometry_; }
  const LineQuadrature& line_quadrature() const { return line_; }

  /// The stages the scene needs: slices (two or more tow fibres), point contacts (a fibre off the
  /// tow axis beside another), a broad phase (more than two fibres), walls.
  bool slicing() const { return slicing_; }
  bool point_search() const { return point_pairs_possible_; }
  bool broad_phase() const { return geometry_.fibres().size() > 2; }
  bool walls() const { return !geometry_.walls().empty(); }

  /// Axial position (mm along the tow axis) of the line quadrature's point i.
  double slice_position(int i) const { return x0_ + line_.position[i] * (x1_ - x0_); }

 private:
  void detect_lines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                    std::vector<Contact>& out) const;
  void detect_points(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                     std::vector<Contact>& out) const;
  void detect_walls(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                    std::vector<Contact>& out) const;
  Eigen::Vector3d interpolate(const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int fibre,
                              double s) const;
  /// Closest points of two deformed polylines over all their segments.
  void closest_on_polylines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int a, int b,
                            Contact& contact, double& distance) const;

  ContactGeometry geometry_;
  LineQuadrature line_;
  Eigen::Vector3d g1_, g2_;  ///< cross-section axes of the slices
  double margin_;
  double x0_ = 0, x1_ = 1;  ///< axial extent of the tow fibres
  std::vector<double> grid_;
  std::vector<int> tow_fibres_;
  bool slicing_ = false;
  bool point_pairs_possible_ = false;
};

}  // namespace fibrecheck
