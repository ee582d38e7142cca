#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "contact.h"
#include "result.h"

namespace fibrecheck {

/// The friction history a load step starts from (DESIGN §2): the relative displacement of every
/// contact at the end of the previous step, from which the next step's slip is measured. A contact
/// the previous step had keeps its own, exactly; one it did not have (it was too far apart to be a
/// candidate) takes the previous step's displacement samples at its two places, interpolated
/// linearly. Without a previous step every origin is zero (the unloaded state).
class SlipOrigins {
 public:
  SlipOrigins() = default;
  /// From a finished step: its contacts with the displacements of their two sides (`u_a[k]`,
  /// `u_b[k]`, mm) and its result's fibre samples.
  SlipOrigins(const std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& u_a,
              const std::vector<Eigen::Vector3d>& u_b, const Result& finished);

  /// Sets each contact's `origin`.
  void set(std::vector<Contact>& contacts) const;

 private:
  Eigen::Vector3d sampled(int fibre, double s) const;

  std::unordered_map<std::uint64_t, Eigen::Vector3d> relative_;
  std::vector<std::vector<Eigen::Vector3d>> samples_;  ///< per fibre, at equal fractions
};

}  // namespace fibrecheck
