#pragma once

#include <vector>

#include "fibre.h"
#include "iteration_state.h"

namespace fibrecheck {

/// Coulomb friction in the iterative solver as a Tresca fixed point: each contact's friction stays
/// in a disk of fixed radius (the inner problem, convex, solved by the update rule), and the radii
/// are set to μ times the normal forces they produced until they no longer move the slips by more
/// than t_d. The reference solves its own frictional problem its own way (it must not share a
/// solution method with what it checks); this is the iterative solver's.
class TrescaRadii {
 public:
  TrescaRadii(double mu, double tolerance) : mu_(mu), tolerance_(tolerance) {}

  /// After an inner problem settled: the radii moved towards μP (relaxed while the violation of
  /// Coulomb's law stops falling). Returns false when Coulomb's law holds — the radii were μP
  /// within the tolerance for two inner problems in a row — and true when a new inner problem
  /// must be solved.
  bool update(IterationState& state, const std::vector<Fibre>& fibres);

  long updates() const { return updates_; }

  /// The radii made μ times the contacts' current normal forces: every contact on its circle
  /// slips with |F| = μP, and none exceeds μP. Done once the radii settle (each friction then
  /// moves by less than the tolerance allows), and after normal forces were set from outside.
  void onto_coulomb_cone(IterationState& state) const;

 private:
  /// How far Coulomb's law is from holding, as the slip the violations could still cause (mm).
  double violation(const IterationState& state, const std::vector<Fibre>& fibres) const;
  /// A contact that slips on its circle (a zero radius lets a contact slip freely).
  bool on_its_circle(const IterationState& state, std::size_t k) const;
  void adapt_relaxation(double change, bool settled);
  /// Every radius μP of the contact's current force: the state was put on the cone and has not
  /// moved since.
  bool on_the_cone(const IterationState& state) const;

  double mu_, tolerance_;
  long updates_ = 0;
  double relaxation_ = 1.0;  ///< of the radius updates, from 1 down to 1/64
  double last_change_ = INFINITY;
  int falling_ = 0;
  bool settled_before_ = false;
  bool put_on_cone_ = false;  ///< the last update settled the radii and put the state on the cone
};

}  // namespace fibrecheck
