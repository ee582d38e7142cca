#include "tresca_radii.h"

#include <algorithm>
#include <cmath>

#include "compliance_operator.h"
#include "contact_results.h"

namespace fibrecheck {

bool TrescaRadii::on_its_circle(const IterationState& state, std::size_t k) const {
  const double bound = state.bound[static_cast<Eigen::Index>(k)];
  return !(bound > 0.0) || state.contacts[k].friction.norm() >= (1.0 - 1e-9) * bound;
}

// A slipping contact's radius must be μP and a sticking one's friction within μP: each violation
// times the contact's compliance is the slip it could still cause. Stick and slip are judged
// against the radii the inner problem had (a contact on its circle slips, whatever μP it came
// short of by a hair); the radii are made μP exactly once they settle (see `update`), so that the
// answer satisfies Coulomb's law as the result reports it.
double TrescaRadii::violation(const IterationState& state, const std::vector<Fibre>& fibres) const {
  double change = 0.0;
  for (std::size_t k = 0; k < state.contacts.size(); ++k) {
    const Contact& c = state.contacts[k];
    const double g = mu_ * c.force;
    const double bound = state.bound[static_cast<Eigen::Index>(k)];
    const double size = c.friction.norm();
    change = std::max(change,
                      (on_its_circle(state, k) ? std::fabs(g - bound) : std::max(0.0, size - g)) *
                          self_compliance(c, fibres));
  }
  const FrictionFigures tresca = tresca_figures(state.contacts, state.bound);
  return std::max({change, tresca.stick_residual, tresca.slip_residual});
}

// The plain map radius ← μP settles into cycles on compacted tows (a radius whose own normal force
// falls faster than it grows): the step is halved when the violation grows, and grown again while
// it falls steadily.
void TrescaRadii::adapt_relaxation(double change, bool settled) {
  if (settled)
    relaxation_ = 1.0;
  else if (change > last_change_)
    relaxation_ = std::max(relaxation_ * 0.5, 1.0 / 64.0), falling_ = 0;
  else if (++falling_ >= 3)
    relaxation_ = std::min(relaxation_ * 1.5, 1.0), falling_ = 0;
  last_change_ = change;
}

bool TrescaRadii::update(IterationState& state, const std::vector<Fibre>& fibres) {
  const double change = violation(state, fibres);
  ++updates_;
  // Settled twice in a row: the last inner problem had the radii μP of the one before, so that
  // scaling its slipping contacts to their own μP moves nothing by more than the tolerance.
  const bool settled = change < tolerance_;
  const bool exact_before = relaxation_ == 1.0 && settled_before_;
  // The end: the state was put on the cone (|F| = μP exactly) when the radii settled, and the
  // slips that left have been measured within the tolerance (the inner problem solved again where
  // they were not) without moving a force since — or, where that solve moved the forces again,
  // put on the cone a second time, which moves them by far less.
  const bool done = settled && exact_before;
  if (done && on_the_cone(state)) return false;
  if (done && put_on_cone_) {
    onto_coulomb_cone(state);
    return false;
  }
  put_on_cone_ = done;
  settled_before_ = settled;
  adapt_relaxation(change, settled);
  for (std::size_t k = 0; k < state.contacts.size(); ++k) {
    const Eigen::Index i = static_cast<Eigen::Index>(k);
    Contact& c = state.contacts[k];
    Eigen::Vector3d& F = c.friction;
    const double size = F.norm();
    const bool slipping = on_its_circle(state, k);
    state.bound[i] += relaxation_ * (mu_ * c.force - state.bound[i]);
    // A contact that slipped on its old circle slips on the new one. At the end, one that slipped
    // with no friction (it pushed only after the last inner problem, with a force too small to
    // matter) takes μP along its slip, as the projected step would.
    const double slip = c.slip.norm();
    if (slipping && size > 0.0)
      F *= state.bound[i] / size;
    else if (slipping && slip > 0.0 && done)
      F = state.bound[i] / slip * c.slip;
    if (state.friction_iterate.size() == state.contacts.size()) state.friction_iterate[k] = F;
  }
  state.forces_gathered = false;  // the frictions moved with their radii
  if (done) onto_coulomb_cone(state);
  return true;
}

bool TrescaRadii::on_the_cone(const IterationState& state) const {
  for (std::size_t k = 0; k < state.contacts.size(); ++k)
    if (state.bound[static_cast<Eigen::Index>(k)] != mu_ * state.contacts[k].force) return false;
  return true;
}

void TrescaRadii::onto_coulomb_cone(IterationState& state) const {
  for (std::size_t k = 0; k < state.contacts.size(); ++k) {
    Contact& c = state.contacts[k];
    const double size = c.friction.norm(), g = mu_ * c.force;
    if (size > 0.0 && (on_its_circle(state, k) || size > g)) c.friction *= g / size;
    state.bound[static_cast<Eigen::Index>(k)] = g;
    if (state.friction_iterate.size() == state.contacts.size())
      state.friction_iterate[k] = c.friction;
  }
  state.forces_gathered = false;
}

}  // namespace fibrecheck
