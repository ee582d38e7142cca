#include "compliance_on_subset.h"

#include <utility>

namespace fibrecheck {

ComplianceOnSubset::ComplianceOnSubset(const Scene& scene, const std::vector<Fibre>& fibres,
                                       std::vector<Contact> contacts)
    : contacts_(std::move(contacts)),
      superposition_(fibres, scene),
      stiffness_(fibres),
      compliance_(superposition_, contacts_) {
  superposition_.attach(contacts_);
  stiffness_.attach(contacts_);
}

}  // namespace fibrecheck
