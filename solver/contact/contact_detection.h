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
/// ContactGeometry under the scene's model (undeformed or displaced centres).
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

  /// Under the deformed model, every crossing moves towards the closest points of the deformed
  /// fibres near where it was: one Newton step, to the closest points of the two fibres' tangent
  /// lines where it acts (displaced by `u_a[k]`, `u_b[k]`; tangents from `grid_u`, which must hold
  /// the fibres of the crossings), at most two grid steps along each fibre. A crossing moves only
  /// where its centres come closer by more than `gain` (mm; at least 1e-12 of the radii). Repeated
  /// on the displacements each move gives, the steps converge to the closest points of the smooth
  /// centrelines; the polyline through the grid would not do, since a crossing's own force kinks
  /// it there and the closest points of kinked polylines jump from side to side. True when one
  /// moved.
  bool follow_crossings(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                        std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& u_a,
                        const std::vector<Eigen::Vector3d>& u_b, double gain = 0.0) const;
  /// One crossing, its sides displaced by u_a and u_b where it acts; true when it moved.
  bool follow_crossing(const std::vector<std::vector<Eigen::Vector3d>>& grid_u, Contact& contact,
                       const Eigen::Vector3d& u_a, const Eigen::Vector3d& u_b,
                       double gain = 0.0) const;

  /// Under the deformed model, crossings found again (`origin[i]` ≥ 0 indexes `before`) keep the
  /// places the steps of follow_crossing took them to, rather than where detection starts them.
  void keep_crossing_places(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                            std::vector<Contact>& found, const std::vector<Contact>& before,
                            const std::vector<long>& origin) const;

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
  /// Newton steps a detected crossing takes towards the closest points.
  static constexpr int kDetectionSteps = 10;
  /// A crossing placed and measured where it now stands, displaced as `grid_u` interpolates.
  void place_crossing(const std::vector<std::vector<Eigen::Vector3d>>& grid_u, Contact& c) const;
  /// The tangent (mm per fraction of the length) of a fibre's deformed centreline at fraction s,
  /// where it is displaced by u: the parabola's through u and the displacements at the grid
  /// stations either side, continuous where the polyline through them kinks.
  Eigen::Vector3d deformed_tangent(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                                   int fibre, double s, const Eigen::Vector3d& u) const;
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
