#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact_geometry.h"
#include "iteration_state.h"
#include "superposition.h"

namespace fibrecheck {

/// The working set of frictionless contact under rules auto and accelerated. Most candidates of a
/// compacted tow never push, and one that neither pushes nor has momentum nor comes near touching
/// keeps P = 0 under the projected update: the iteration runs on the others. While it is on, the
/// state's contacts are the working set of the candidate list; the overlaps of every candidate are
/// measured again at each revision, and a candidate joins when its overlap, extrapolated from its
/// own rise since the last revision over three more intervals, comes within 2·t_d of touching.
/// Revisions come 20 iterations after one that let a candidate join, and twice as far apart
/// (up to 160) while none does. The step stays that of the whole candidate list.
class WorkingSet {
 public:
  /// `superposition` is the solver's, attached to the state's contacts; `margin` (mm) is how far
  /// from touching the candidates were found; `tolerance` is t_d (mm).
  WorkingSet(Superposition& superposition, const std::vector<Fibre>& fibres, const Scene& scene,
             const ContactGeometry& geometry, double margin, double tolerance)
      : superposition_(superposition),
        candidate_superposition_(fibres, scene),
        geometry_(geometry),
        margin_(margin),
        tolerance_(tolerance) {}

  bool active() const { return active_; }
  /// The place in the candidate list of each of the state's contacts, while active.
  const std::vector<int>& members() const { return members_; }
  std::size_t candidates() const { return candidates_.size(); }

  /// The state's contacts become the candidate list, and the state the working set of it.
  void enter(IterationState& state);
  /// Measures every candidate again and revises the set; true when it changed.
  bool revise(IterationState& state);
  /// Measures every candidate again; true when one outside the set overlaps by more than `t`
  /// (the set leaves it without force, so the contact criterion does not hold for it).
  bool outside_overlaps(const IterationState& state, double t);
  /// Counts an iteration; true when a revision is due.
  bool due() {
    if (++since_revision_ < revision_interval_) return false;
    since_revision_ = 0;
    return true;
  }
  /// Every candidate back in the state, each member with its force and iterates.
  void leave(IterationState& state);

 private:
  /// The overlap of every candidate under the members' forces; its slot in the state (or −1).
  void measure_candidates(const IterationState& state);
  /// Whether candidate i belongs to the set (`first`: the first revision after entering).
  bool needed(const IterationState& state, int i, bool first) const;
  void rebuild(IterationState& state, std::vector<int> members);

  Superposition& superposition_;
  Superposition candidate_superposition_;  ///< attached to candidates_
  const ContactGeometry& geometry_;
  double margin_, tolerance_;
  bool active_ = false;
  std::vector<Contact> candidates_;
  std::vector<int> members_;            ///< index in candidates_ of each contact of the state
  std::vector<double> synced_overlap_;  ///< of every candidate at the last revision
  int revision_interval_ = 20;
  int since_revision_ = 0;
  // Scratch of the revisions.
  std::vector<Eigen::Vector3d> force_, u_a_, u_b_;
  std::vector<int> slot_;
  std::vector<double> overlap_;
};

}  // namespace fibrecheck
