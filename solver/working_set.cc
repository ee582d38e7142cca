#include "working_set.h"

#include <algorithm>

namespace fibrecheck {

void WorkingSet::enter(IterationState& state) {
  candidates_ = state.contacts;
  candidate_superposition_.attach(candidates_);
  synced_overlap_.clear();
  members_.resize(candidates_.size());
  for (std::size_t i = 0; i < candidates_.size(); ++i) members_[i] = static_cast<int>(i);
  active_ = true;
  revision_interval_ = 20;
  since_revision_ = 0;
  revise(state);
}

void WorkingSet::measure_candidates(const IterationState& state) {
  const int n = static_cast<int>(candidates_.size());
  const int m = static_cast<int>(state.contacts.size());
  force_.assign(candidates_.size(), Eigen::Vector3d::Zero());
  slot_.assign(candidates_.size(), -1);
  for (int i = 0; i < m; ++i) {
    force_[members_[i]] = state.contacts[i].force_on_a();
    slot_[members_[i]] = i;
  }
  candidate_superposition_.contact_displacements(candidates_, force_, true, u_a_, u_b_);
  overlap_.resize(candidates_.size());
#pragma omp parallel for schedule(static) if (n > 4096)
  for (int i = 0; i < n; ++i) overlap_[i] = geometry_.overlap(candidates_[i], u_a_[i], u_b_[i]);
}

bool WorkingSet::needed(const IterationState& state, int i, bool first) const {
  const int k = slot_[i];
  const double predicted =
      first ? overlap_[i] + margin_
            : overlap_[i] + 3.0 * std::max(0.0, overlap_[i] - synced_overlap_[i]);
  if (predicted > -2.0 * tolerance_) return true;
  if (k < 0) return false;
  const bool momentum = state.iterate.size() == static_cast<Eigen::Index>(state.contacts.size());
  return state.contacts[k].force > 0.0 ||
         (momentum && (state.iterate[k] > 0.0 || state.previous[k] > 0.0));
}

bool WorkingSet::revise(IterationState& state) {
  measure_candidates(state);
  const bool first = synced_overlap_.size() != candidates_.size();
  if (first) synced_overlap_ = overlap_;
  const int n = static_cast<int>(candidates_.size());
  std::vector<int> members;
  members.reserve(members_.size() + 64);
  for (int i = 0; i < n; ++i)
    if (needed(state, i, first)) members.push_back(i);
  synced_overlap_.swap(overlap_);
  int newcomers = 0;
  for (int i : members) newcomers += slot_[i] < 0;
  revision_interval_ = newcomers > 0 ? 20 : std::min(2 * revision_interval_, 160);
  if (members == members_ && state.contacts.size() == members.size()) return false;
  rebuild(state, std::move(members));
  return true;
}

bool WorkingSet::outside_overlaps(const IterationState& state, double t) {
  measure_candidates(state);
  for (std::size_t i = 0; i < candidates_.size(); ++i)
    if (slot_[i] < 0 && overlap_[i] > t) return true;
  return false;
}

void WorkingSet::rebuild(IterationState& state, std::vector<int> members) {
  // Members keep their state and momentum, newcomers start from P = 0.
  const bool momentum = state.iterate.size() == static_cast<Eigen::Index>(state.contacts.size());
  std::vector<Contact> working(members.size());
  Eigen::VectorXd iterate = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(members.size()));
  Eigen::VectorXd previous = iterate;
  for (std::size_t j = 0; j < members.size(); ++j) {
    const int k = slot_[members[j]];
    working[j] = k >= 0 ? state.contacts[k] : candidates_[members[j]];
    // On the deformed fibres a candidate that joins takes the normal of its displaced centres.
    if (k < 0 && geometry_.deformed())
      geometry_.follow(working[j], u_a_[members[j]], u_b_[members[j]]);
    working[j].overlap = synced_overlap_[members[j]];
    if (k < 0) working[j].force = 0.0;
    if (k >= 0 && momentum) iterate[j] = state.iterate[k], previous[j] = state.previous[k];
  }
  state.contacts = std::move(working);
  members_ = std::move(members);
  if (momentum) state.iterate = std::move(iterate), state.previous = std::move(previous);
  superposition_.attach(state.contacts);
  state.forces_gathered = false;
}

void WorkingSet::leave(IterationState& state) {
  if (!active_) return;
  const bool momentum = state.iterate.size() == static_cast<Eigen::Index>(state.contacts.size());
  Eigen::VectorXd iterate = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(candidates_.size()));
  Eigen::VectorXd previous = iterate;
  for (Contact& c : candidates_) c.force = 0.0;
  // On the deformed fibres the others take the normals of their displaced centres at the last
  // revision, as a newcomer does: measured along an older normal their overlaps would be too large.
  if (geometry_.deformed() && u_a_.size() == candidates_.size()) {
    const int n = static_cast<int>(candidates_.size());
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int i = 0; i < n; ++i) geometry_.follow(candidates_[i], u_a_[i], u_b_[i]);
  }
  for (std::size_t i = 0; i < state.contacts.size(); ++i) {
    candidates_[members_[i]] = state.contacts[i];
    if (momentum)
      iterate[members_[i]] = state.iterate[i], previous[members_[i]] = state.previous[i];
  }
  state.contacts = std::move(candidates_);
  candidates_.clear();
  if (momentum) state.iterate = std::move(iterate), state.previous = std::move(previous);
  superposition_.attach(state.contacts);
  state.forces_gathered = false;
  active_ = false;
}

}  // namespace fibrecheck
