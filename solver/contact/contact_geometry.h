#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// Where a contact acts and how much it overlaps (seed §4.3.2–4.3.3), for small deflections: every
/// contact's place and normal are those of the undeformed fibres, so the overlap
/// d = (rA + rB) − n·(Bc − Ac) is linear in the deflections and the contact problem has one answer
/// whatever path leads to it — the same for the iterative solver and the reference.
class ContactGeometry {
 public:
  ContactGeometry(const std::vector<Fibre>& fibres, const std::vector<WallSpec>& walls,
                  const Eigen::Vector3d& tow_axis);

  /// Sets a contact's place and normal from the undeformed fibres: a crossing at the closest
  /// points of the two chords (Eqs. 4.16–4.24), its normal from A's centre to B's (the part along
  /// the tow axis dropped for slices). Where the centres nearly coincide there is no trustworthy
  /// direction: the normal is A's axis × B's (or the slices' second axis) and `normal_held` is set.
  /// A wall contact keeps the wall's normal and its place. Sets the tangential directions too.
  void place_on_undeformed(Contact& contact) const;

  /// Overlap d = (rA + rB) − n·(Bc − Ac) of one contact along its normal (Eq. 4.14; the part along
  /// the tow axis dropped for slices; r − n·(Ac − wall point) for walls), mm, given the
  /// displacements (mm) of its two sides.
  double overlap_along_normal(const Contact& contact, const Eigen::Vector3d& u_a,
                              const Eigen::Vector3d& u_b) const;

  /// The normal of the deformed centres (seed §4.3.4): from A's displaced centre to B's (the part
  /// along the tow axis dropped for slices), the wall's normal for walls, the contact's own normal
  /// where the centres coincide.
  Eigen::Vector3d deformed_normal(const Contact& contact, const Eigen::Vector3d& u_a,
                                  const Eigen::Vector3d& u_b) const;

  /// Every contact's overlap from the displacements of its two sides (`u_a[k]`, `u_b[k]`), and
  /// with `slip` its slip since the step began.
  void measure(std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& u_a,
               const std::vector<Eigen::Vector3d>& u_b, bool slip = false) const;

  const std::vector<Fibre>& fibres() const { return fibres_; }
  const std::vector<WallSpec>& walls() const { return walls_; }
  const Eigen::Vector3d& tow_axis() const { return axis_; }

 private:
  std::vector<Fibre> fibres_;
  std::vector<WallSpec> walls_;
  void place_normal(Contact& contact) const;
  void set_tangents(Contact& contact) const;

  Eigen::Vector3d axis_;
  Eigen::Vector3d g2_;  ///< second cross-section axis of the slices
};

}  // namespace fibrecheck
