#pragma once

#include <vector>

#include "compliance_operator.h"
#include "contact.h"
#include "fibre.h"
#include "fibre_stiffness.h"
#include "scene.h"
#include "superposition.h"

namespace fibrecheck {

/// W and its preconditioner, the fibres' stiffness at their stations, on a list of contacts of
/// its own: a subset of the candidates (the pushing set, or those near touching), on beams that
/// carry those contacts alone. The other candidates are held at zero force.
class ComplianceOnSubset {
 public:
  ComplianceOnSubset(const Scene& scene, const std::vector<Fibre>& fibres,
                     std::vector<Contact> contacts);
  ComplianceOnSubset(const ComplianceOnSubset&) = delete;
  ComplianceOnSubset& operator=(const ComplianceOnSubset&) = delete;

  const ComplianceOperator& compliance() const { return compliance_; }
  const FibreStiffness& stiffness() const { return stiffness_; }

 private:
  std::vector<Contact> contacts_;
  Superposition superposition_;
  FibreStiffness stiffness_;
  ComplianceOperator compliance_;  ///< refers to superposition_ and contacts_
};

}  // namespace fibrecheck
