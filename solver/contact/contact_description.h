#pragma once

#include <string>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// Where a contact is, for messages a person reads: "fibres A and B at s = 0.5 of A (s = 0.5 of
/// B)", "fibre A and wall floor at s = 0.25 of A", with the slice for line contacts.
std::string describe(const Contact& contact, const std::vector<Fibre>& fibres,
                     const std::vector<WallSpec>& walls);

}  // namespace fibrecheck
