#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// Finds and measures contacts (seed §4.3.3) on the deformed fibres:
///  - point contacts between fibres that cross, by the closest points of their deformed centrelines
///    approximated by straight segments (Eqs. 4.16–4.24);
///  - line contacts between tow fibres, by n cross-sections ("slices") perpendicular to the tow
///    axis, each a point contact at its slice (Figures 4.11–4.12);
///  - fibre–wall contacts at n stations along each fibre.
/// Candidates are found with a margin before they touch, so a contact's normal is known from a
/// non-overlapping state.
class ContactDetector {
 public:
  ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene, double margin);

  /// Fractions of the length at which each fibre's deformed centreline is sampled for detection.
  const std::vector<double>& grid() const { return grid_; }

  /// All candidate contacts (overlap > −margin) of the deformed state given by each fibre's
  /// displacements at `grid()` (`grid_u[fibre][j]`). Forces are zero; overlaps and normals set.
  std::vector<Contact> detect(const std::vector<std::vector<Eigen::Vector3d>>& grid_u) const;

  /// Measures every contact again from the exact displacements of its two sides (`u_a`, `u_b`):
  /// overlap d (Eq. 4.14) and normal. Point contacts that carry no force then look for their
  /// closest points again on the deformed polylines `grid_u` (only fibres with point contacts need
  /// them) and move there for the next evaluation; a contact that pushes keeps its place and its
  /// normal. Returns how many normals were held because the centres nearly coincided.
  int measure(std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& u_a,
              const std::vector<Eigen::Vector3d>& u_b,
              const std::vector<std::vector<Eigen::Vector3d>>& grid_u) const;

  /// Overlap d = (rA + rB) − n·(Bc − Ac) of one contact along its current normal (Eq. 4.14; the
  /// part along the tow axis dropped for slices; r − n·(Ac − wall point) for walls), given the
  /// displacements of its two sides.
  double overlap_along_normal(const Contact& contact, const Eigen::Vector3d& u_a,
                              const Eigen::Vector3d& u_b) const;

  /// W_kk: how much overlap a unit force removes at this contact alone (mm/N).
  double self_compliance(const Contact& contact) const;

  /// Fibres that carry point contacts need their deformed polylines every iteration.
  bool needs_polylines() const { return point_pairs_possible_; }

  bool slicing() const { return slicing_; }
  bool point_search() const { return point_pairs_possible_; }
  bool broad_phase() const { return fibres_.size() > 2; }
  bool walls() const { return !walls_.empty(); }

  /// Axial position (along the tow axis) of slice i.
  double slice_position(int i) const { return x0_ + (i + 0.5) * (x1_ - x0_) / slices_; }
  /// Where a contact is, for messages: "fibres A and B at 0.5 of A".
  std::string describe(const Contact& contact) const;
  const std::vector<WallSpec>& wall_specs() const { return walls_; }

 private:
  void detect_lines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                    std::vector<Contact>& out) const;
  void detect_points(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                     std::vector<Contact>& out) const;
  void detect_walls(const std::vector<std::vector<Eigen::Vector3d>>& grid_u,
                    std::vector<Contact>& out) const;
  Eigen::Vector3d interpolate(const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int fibre,
                              double s) const;
  /// Closest points of two deformed polylines, searching segments [ia0, ia1) × [ib0, ib1).
  void closest_on_polylines(const std::vector<std::vector<Eigen::Vector3d>>& grid_u, int a, int b,
                            int ia0, int ia1, int ib0, int ib1, Contact& contact,
                            double& distance) const;
  void set_normal_and_overlap(Contact& contact, const Eigen::Vector3d& difference, double radii,
                              bool first) const;

  std::vector<Fibre> fibres_;
  std::vector<WallSpec> walls_;
  Eigen::Vector3d axis_;
  Eigen::Vector3d g1_, g2_;  ///< cross-section axes of the slices
  int slices_;
  double margin_;
  double x0_ = 0, x1_ = 1;  ///< axial extent of the tow fibres
  std::vector<double> grid_;
  std::vector<int> tow_fibres_;
  bool slicing_ = false;
  bool point_pairs_possible_ = false;
};

}  // namespace fibrecheck
