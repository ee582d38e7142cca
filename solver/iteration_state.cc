#include "iteration_state.h"

#include "parallel_work.h"

namespace fibrecheck {

void IterationState::gather_forces() {
  force_on_a.resize(contacts.size());
  const Contact* const contact = contacts.data();
  Eigen::Vector3d* const force = force_on_a.data();
  const int n = static_cast<int>(contacts.size());
#pragma omp parallel for schedule(static) if (n > kParallelContacts)
  for (int k = 0; k < n; ++k) force[k] = contact[k].force_on_a();
  forces_gathered = true;
}

void IterationState::take_over(std::vector<Contact> found, const std::vector<long>& origin,
                               bool coulomb, double mu) {
  const bool had_momentum = iterate.size() == static_cast<Eigen::Index>(contacts.size());
  const bool had_bounds = bound.size() == static_cast<Eigen::Index>(contacts.size());
  const bool had_friction_momentum = friction_iterate.size() == contacts.size();
  Eigen::VectorXd next_iterate(static_cast<Eigen::Index>(found.size()));
  Eigen::VectorXd next_previous(next_iterate.size());
  std::vector<Eigen::Vector3d> next_friction(coulomb ? found.size() : 0);
  std::vector<Eigen::Vector3d> next_previous_friction(next_friction.size());
  Eigen::VectorXd next_bound = Eigen::VectorXd::Zero(coulomb ? next_iterate.size() : 0);
  for (std::size_t i = 0; i < found.size(); ++i) {
    const bool known = had_momentum && origin[i] >= 0;
    next_iterate[i] = known ? iterate[origin[i]] : found[i].force;
    next_previous[i] = known ? previous[origin[i]] : found[i].force;
    if (!coulomb) continue;
    next_bound[i] = had_bounds && origin[i] >= 0 ? bound[origin[i]] : mu * found[i].force;
    const bool known_friction = had_friction_momentum && origin[i] >= 0;
    next_friction[i] = known_friction ? friction_iterate[origin[i]] : found[i].friction;
    next_previous_friction[i] = known_friction ? previous_friction[origin[i]] : found[i].friction;
  }
  contacts = std::move(found);
  iterate = std::move(next_iterate);
  previous = std::move(next_previous);
  friction_iterate = std::move(next_friction);
  bound = std::move(next_bound);
  previous_friction = std::move(next_previous_friction);
}

}  // namespace fibrecheck
