#pragma once

#include <vector>

#include "contact.h"

namespace fibrecheck {

/// After a new detection: the contacts `found` again take over the force and friction they had in
/// `previous`, and a contact of `previous` that pushes but was not found again stays a candidate
/// (appended; dropping it would release its force at once and the fibres would spring back).
/// Returns, for every contact of the new `found`, its index in `previous` or −1 if it is new.
std::vector<long> carry_over(const std::vector<Contact>& previous, std::vector<Contact>& found);

}  // namespace fibrecheck
