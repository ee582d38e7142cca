#pragma once

#include <Eigen/Core>
#include <vector>

#include "force_update.h"

namespace fibrecheck {

/// The seed's update (§4.3.2), P' = max(0, P + c·d) for every contact from the same state (c·w_k
/// with `weighted`, w_k = 1/n per slice, Eq. 4.28); with Coulomb friction the same step on the
/// slip, F' the point of the disk |F| ≤ bound_k nearest to F + c·s (Eq. 4.31). Writes the next
/// forces and frictions. With `restart_test` returns −(d, s)·(r' − r_k) against the state's
/// iterates, summed in fixed blocks (the same decision on any number of threads); 0 otherwise.
double projected_step(const IterationState& state, const UpdateContext& context, bool weighted,
                      bool restart_test, Eigen::VectorXd& next,
                      std::vector<Eigen::Vector3d>& next_friction);

/// Gives every contact its next force and friction (the seed's friction rule instead keeps the
/// last resultant, split along the deformed normal and capped by μP', Eqs. 4.29–4.33), and
/// gathers the forces fibre A receives.
void apply_forces(IterationState& state, const UpdateContext& context, const Eigen::VectorXd& next,
                  const std::vector<Eigen::Vector3d>& next_friction);

}  // namespace fibrecheck
