#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// The beam model of all fibres at once (seed §4.3.1): each fibre's deflection is the superposition
/// of its external loads and its contact forces, each force resolved into the fibre's two bending
/// planes (e1, e2) and its axial part dropped. Evaluation at the k load points of a fibre, or at n
/// sorted stations, costs O(k + n) through the running sums of beam.h.
class Superposition {
 public:
  Superposition(const std::vector<Fibre>& fibres, const Scene& scene);

  /// Registers the contacts' load points on their fibres (call when the contact list changes).
  void attach(const std::vector<Contact>& contacts);
  /// The load points of the attached contacts on `fibres` moved (crossings following the deformed
  /// fibres): their places are read again from `contacts`, the same list as attached.
  void move_points(const std::vector<Contact>& contacts, const std::vector<int>& fibres);

  /// Displacements (mm) of fibre A's and fibre B's centreline at every contact, under the contact
  /// forces `force_on_a` (what fibre A receives; B receives the opposite) and, if `external`, the
  /// scene's loads. Optionally returns the exact strain energy ½ΣP·v (N·mm).
  void contact_displacements(const std::vector<Contact>& contacts,
                             const std::vector<Eigen::Vector3d>& force_on_a, bool external,
                             std::vector<Eigen::Vector3d>& u_a, std::vector<Eigen::Vector3d>& u_b,
                             double* exact_energy = nullptr) const;

  /// Displacement (mm) and optionally bending moments (N·mm, both planes) of one fibre at sorted
  /// fractions `s`, under the same loads.
  void fibre_field(int fibre, const std::vector<Eigen::Vector3d>& force_on_a, bool external,
                   const std::vector<double>& s, std::vector<Eigen::Vector3d>& u,
                   std::vector<Eigen::Vector2d>* moment = nullptr) const;

  /// Strain energy Σ∫M²/(2EI)dx by the trapezium rule on `intervals` equal intervals per fibre
  /// (Eqs. 4.34–4.35).
  double trapezium_energy(const std::vector<Eigen::Vector3d>& force_on_a, int intervals) const;

  /// Sum of the magnitudes of the axial parts the beam model drops, N.
  double axial_load_dropped(const std::vector<Contact>& contacts,
                            const std::vector<Eigen::Vector3d>& force_on_a) const;

 private:
  /// A load point on a fibre: a contact side (contact ≥ 0, sign +1 for A, −1 for B) or an external
  /// point load (contact = −1 − index).
  struct Slot {
    double a;  ///< distance from start, mm
    int contact;
    int sign;
  };
  struct ExternalPointLoad {
    double a;
    Eigen::Vector2d p;  ///< components along e1, e2, N
  };

  /// The running sums of beam.h for both bending planes at once.
  struct PlaneSums;

  /// First pass over a fibre's loads, O(k): each load's components along e1, e2 (N) in slot order
  /// into `p`, and all of them into the "a ≥ x" sums.
  void load_components(int fibre, const std::vector<Eigen::Vector3d>& force_on_a, bool external,
                       std::vector<Eigen::Array2d>& p, PlaneSums& sums) const;

  std::vector<Fibre> fibres_;
  std::vector<std::vector<ExternalPointLoad>> point_loads_;  ///< per fibre
  std::vector<Eigen::Vector2d> distributed_;                 ///< per fibre, q along e1, e2 (N/mm)
  std::vector<double> external_axial_;                       ///< per fibre, dropped axial N
  std::vector<std::vector<Slot>> slots_;                     ///< per fibre, sorted by a
  long total_slots_ = 0;
};

}  // namespace fibrecheck
