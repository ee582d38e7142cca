#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// After a new detection: the contacts `found` again take over the force and friction they had in
/// `previous`, and a contact of `previous` that pushes but was not found again stays a candidate
/// (appended; dropping it would release its force at once and the fibres would spring back).
/// Returns, for every contact of the new `found`, its index in `previous` or −1 if it is new.
std::vector<long> carry_over(const std::vector<Contact>& previous, std::vector<Contact>& found);

/// Finds and measures contacts (seed §4.3.3):
///  - point contacts between fibres that cross, by the closest points of their centrelines
///    (Eqs. 4.16–4.24);
///  - line contacts between tow fibres, by n cross-sections ("slices") perpendicular to the tow
///    axis, each a point contact at its slice (Figures 4.11–4.12);
///  - fibre–wall contacts at n stations along each fibre.
/// Candidates are found on the deformed fibres, with a margin before they touch. Every contact's
/// place and normal are those of the undeformed fibres (small-deflection contact): the overlap
/// d = (rA + rB) − n·(Bc − Ac) is then linear in the deflections, and the contact problem has one
/// answer whatever path leads to it — the same for the iterative solver and the reference.
class ContactDetector {
 public:
  ContactDetector(const std::vector<Fibre>& fibres, const Scene& scene, double margin);

  /// Fractions of the length at which each fibre's deformed centreline is sampled for detection.
  const std::vector<double>& grid() const { return grid_; }

  /// All candidate contacts (closer than the margin) of the deformed state given by each fibre's
  /// displacements at `grid()` (`grid_u[fibre][j]`). Forces are zero; places, normals (see
  /// `place_on_undeformed`) and overlaps set.
  std::vector<Contact> detect(const std::vector<std::vector<Eigen::Vector3d>>& grid_u) const;

  /// Measures every contact's overlap again from the displacements of its two sides (`u_a`, `u_b`).
  void measure(std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& u_a,
               const std::vector<Eigen::Vector3d>& u_b) const;

  /// Sets a contact's place and normal from the undeformed fibres: a point contact at the closest
  /// points of the two chords, its normal from A's centre to B's (the part along the tow axis
  /// dropped for slices). Where the centres nearly coincide there is no trustworthy direction: the
  /// normal is A's axis × B's (or the slices' second axis) and `normal_held` is set.
  void place_on_undeformed(Contact& contact) const;

  /// Overlap d = (rA + rB) − n·(Bc − Ac) of one contact along its current normal (Eq. 4.14; the
  /// part along the tow axis dropped for slices; r − n·(Ac − wall point) for walls), given the
  /// displacements of its two sides.
  double overlap_along_normal(const Contact& contact, const Eigen::Vector3d& u_a,
                              const Eigen::Vector3d& u_b) const;

  /// W_kk: how much overlap a unit force removes at this contact alone (mm/N).
  double self_compliance(const Contact& contact) const;

  bool slicing() const { return slicing_; }
  bool point_search() const { return point_pairs_possible_; }
  bool broad_phase() const { return fibres_.size() > 2; }
  bool walls() const { return !walls_.empty(); }

  /// Puts the line-contact stations (slices, and wall stations along each fibre) at the two Gauss
  /// points of each of `cells` equal cells, weighted by half a cell, instead of the n slice
  /// midpoints (the one-point Gauss rule on n cells): the continuous line contact, converging as
  /// the cells are refined. Call before `detect`.
  void use_gauss_stations(int cells);

  /// Number of slices and the axial position (along the tow axis) of slice i.
  int slice_count() const { return static_cast<int>(station_.size()); }
  double slice_position(int i) const { return x0_ + station_[i] * (x1_ - x0_); }
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

  std::vector<Fibre> fibres_;
  std::vector<WallSpec> walls_;
  Eigen::Vector3d axis_;
  Eigen::Vector3d g1_, g2_;  ///< cross-section axes of the slices
  /// Line-contact stations as fractions of the tow's extent (slices) or of a fibre's length
  /// (walls), and the share of the line each carries (Eq. 4.28: 1/n for n slices).
  std::vector<double> station_, weight_;
  double margin_;
  double x0_ = 0, x1_ = 1;  ///< axial extent of the tow fibres
  std::vector<double> grid_;
  std::vector<int> tow_fibres_;
  bool slicing_ = false;
  bool point_pairs_possible_ = false;
};

}  // namespace fibrecheck
