#pragma once

#include <string>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// Warnings about contacts whose side cannot be told from the geometry (DESIGN §2, "Tows and
/// well-posedness"): the first that overlaps by more than a radius before any force acts, and how
/// many have centres so close that their normal was chosen rather than measured. Both solvers
/// report them from their first detection.
std::vector<std::string> ambiguous_side_warnings(const std::vector<Contact>& contacts,
                                                 const std::vector<Fibre>& fibres,
                                                 const std::vector<WallSpec>& walls);

}  // namespace fibrecheck
