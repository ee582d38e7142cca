#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// Where a contact acts, along which normal it pushes and how much it overlaps (seed §4.3.2–4.3.3),
/// the same for the iterative solver and the reference. Two models (DESIGN §2):
///  - deformed (the seed's): the overlap d′ = (rA + rB) − ‖B′c − A′c‖ and the normal along
///    B′c − A′c come from the displaced centres at every measurement (Eqs. 4.14–4.15; for a slice
///    the difference in its cross-section plane, §4.3.3), so the normal turns as fibres slide past
///    each other; walls keep their normal;
///  - linearised (small deflections): place and normal of the undeformed fibres, the overlap
///    d = (rA + rB) − n·(Bc − Ac) linear in the deflections, so the frictionless problem has one
///    answer whatever path leads to it.
/// Where the centres come closer than half the contact distance no direction can be trusted (two
/// fibres passing through each other have no preferred side): the contact keeps its normal there
/// and its overlap is measured along it, in both models.
class ContactGeometry {
 public:
  ContactGeometry(const std::vector<Fibre>& fibres, const std::vector<WallSpec>& walls,
                  const Eigen::Vector3d& tow_axis,
                  ContactGeometryModel model = ContactGeometryModel::linearised);

  ContactGeometryModel model() const { return model_; }
  bool deformed() const { return model_ == ContactGeometryModel::deformed; }

  /// Sets a contact's place and normal from the undeformed fibres: a crossing at the closest
  /// points of the two chords (Eqs. 4.16–4.24), its normal from A's centre to B's (the part along
  /// the tow axis dropped for slices). Where the centres nearly coincide there is no trustworthy
  /// direction: the normal is A's axis × B's (or the slices' second axis) and `normal_held` is set.
  /// A wall contact keeps the wall's normal and its place. Sets the tangential directions too.
  void place_on_undeformed(Contact& contact) const;

  /// place_on_undeformed, then (deformed model) the normal and tangents follow the displaced
  /// centres, given the displacements (mm) of the contact's two sides there.
  void place(Contact& contact, const Eigen::Vector3d& u_a, const Eigen::Vector3d& u_b) const;
  /// The same at the place the contact has (a crossing moved to the deformed fibres' closest
  /// points): its normal and tangents only.
  void place_at(Contact& contact, const Eigen::Vector3d& u_a, const Eigen::Vector3d& u_b) const;

  /// Overlap d = (rA + rB) − n·(Bc − Ac) of one contact along its normal (Eq. 4.14; the part along
  /// the tow axis dropped for slices; r − n·(Ac − wall point) for walls), mm, given the
  /// displacements (mm) of its two sides: linear in them.
  double overlap_along_normal(const Contact& contact, const Eigen::Vector3d& u_a,
                              const Eigen::Vector3d& u_b) const;

  /// The overlap of the model: along the normal (linearised), or d′ = (rA + rB) − ‖B′c − A′c‖ of
  /// the displaced centres (deformed; along the normal where they nearly coincide), mm.
  double overlap(const Contact& contact, const Eigen::Vector3d& u_a,
                 const Eigen::Vector3d& u_b) const;

  /// Whether the displaced centres have passed through each other: B′c − A′c points against the
  /// contact's normal. Such a contact keeps its normal, along which its overlap is measured.
  bool passed_through(const Contact& contact, const Eigen::Vector3d& u_a,
                      const Eigen::Vector3d& u_b) const;

  /// The seed's own gap of the displaced centres, ‖B′c − A′c‖ − (rA + rB) (Eq. 4.15; in the
  /// cross-section plane for slices, to the wall plane for walls), whatever the model, mm.
  double deformed_gap(const Contact& contact, const Eigen::Vector3d& u_a,
                      const Eigen::Vector3d& u_b) const;

  /// The normal of the deformed centres (seed §4.3.4): from A's displaced centre to B's (the part
  /// along the tow axis dropped for slices), the wall's normal for walls, the contact's own normal
  /// where the centres coincide.
  Eigen::Vector3d deformed_normal(const Contact& contact, const Eigen::Vector3d& u_a,
                                  const Eigen::Vector3d& u_b) const;

  /// Every contact's overlap from the displacements of its two sides (`u_a[k]`, `u_b[k]`), and
  /// with `slip` its slip since the step began. Under the deformed model each contact's normal
  /// (and tangents) follow the displaced centres first, and its friction force the new tangents;
  /// without `follow_normals` the overlap is that of the problem linearised about the normals the
  /// contacts have (along them, linear in the displacements).
  void measure(std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& u_a,
               const std::vector<Eigen::Vector3d>& u_b, bool slip = false,
               bool follow_normals = true) const;

  /// Under the deformed model: the normal, tangents and friction of one contact follow its
  /// displaced centres (nothing for walls, or where the centres nearly coincide). The friction
  /// turns into the new tangent plane keeping its size: projected instead, a contact slipping on
  /// the edge of its disk would fall inside it and count as sticking with all its slip.
  void follow(Contact& contact, const Eigen::Vector3d& u_a, const Eigen::Vector3d& u_b) const;

  /// The contact's normal made `normal` (a unit vector), its tangents and friction turned with it
  /// as `follow` turns them.
  void turn(Contact& contact, const Eigen::Vector3d& normal) const;

  const std::vector<Fibre>& fibres() const { return fibres_; }
  const std::vector<WallSpec>& walls() const { return walls_; }
  const Eigen::Vector3d& tow_axis() const { return axis_; }

 private:
  std::vector<Fibre> fibres_;
  std::vector<WallSpec> walls_;
  /// The normal of the undeformed centres at the contact's place (for a crossing at the closest
  /// points of the chords, Eqs. 4.16–4.24, when `at_chords`).
  void place_normal(Contact& contact, bool at_chords) const;
  void set_tangents(Contact& contact) const;
  /// B′c − A′c (the part along the tow axis dropped for slices), mm.
  Eigen::Vector3d centre_difference(const Contact& contact, const Eigen::Vector3d& u_a,
                                    const Eigen::Vector3d& u_b) const;
  /// Whether a contact keeps its normal on the deformed fibres, its displaced centres B′c − A′c
  /// being `difference`: nearly coincident, or passed through each other.
  bool keeps_normal(const Contact& contact, const Eigen::Vector3d& difference) const;

  ContactGeometryModel model_;
  Eigen::Vector3d axis_;
  Eigen::Vector3d g2_;  ///< second cross-section axis of the slices
};

}  // namespace fibrecheck
