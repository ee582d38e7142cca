#pragma once

#include <memory>
#include <optional>

#include "contact_geometry.h"
#include "iteration_state.h"
#include "scene.h"

namespace fibrecheck {

class Superposition;

/// What an update needs besides the state it updates.
struct UpdateContext {
  double step = 0.0;           ///< c, N/mm (the seed's rule takes c times each contact's weight)
  double mu = 0.0;             ///< Coulomb coefficient (Eq. 4.31)
  bool coulomb = false;        ///< Coulomb friction: F projected onto the disk of its Tresca radius
  bool seed_friction = false;  ///< the seed's friction rule (Eqs. 4.29–4.33)
  const ContactGeometry* geometry = nullptr;
  double lambda_max = 0.0;  ///< of the operator the step acts on
  double tolerance = 0.0;   ///< t_d, mm
  long max_products = 0;    ///< applications of W still allowed
};

/// A force update rule of §4.3.2 (DESIGN §2): how the forces of every contact move from the
/// overlaps d just measured. The loop measures, asks the rule to update, and measures again.
class ForceUpdate {
 public:
  virtual ~ForceUpdate() = default;

  /// The step c of P' = P + c·d on a candidate list whose compliance has largest eigenvalue
  /// `lambda_max` (of D½·W·D½ when `weighted`), N/mm.
  virtual double step(double lambda_max) const = 0;
  /// Whether the step is c·D, D the contacts' weights (1/n per slice, Eq. 4.28): the seed's own
  /// rule, whose stability limit is that of D½·W·D½.
  virtual bool weighted() const { return false; }
  /// Whether the iteration may run on a working set of the candidates (frictionless contact): a
  /// candidate without force, momentum or overlap keeps P = 0 under this rule.
  virtual bool allows_working_set() const { return false; }
  /// Whether one update solves the whole candidate list's problem (so that the fibres' shape is
  /// checked against the candidate margin only once it is solved).
  virtual bool solves_each_list() const { return false; }
  /// The candidate list changed.
  virtual void attach(const std::vector<Contact>& contacts) { (void)contacts; }
  /// Every contact's force (and friction) updated from the overlaps and slips last measured.
  /// Returns the applications of W this took: the work, counted as iterations.
  virtual long update(IterationState& state, const UpdateContext& context) = 0;
  /// A new inner problem begins (the Tresca radii changed): momentum is forgotten.
  virtual void restart(IterationState& state) { (void)state; }
};

/// The rule `rule` of the table update_rules(); `c` is the scene's step (rule seed). Rule cg
/// solves each candidate list by projected conjugate gradients on W, applied through
/// `superposition` on the state's contacts.
std::unique_ptr<ForceUpdate> make_force_update(UpdateRule rule, std::optional<double> c,
                                               const Superposition& superposition,
                                               const std::vector<Fibre>& fibres,
                                               const IterationState& state);

}  // namespace fibrecheck
