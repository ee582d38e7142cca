#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// Self-compliances W_kk (mm/N) at or below this no force can move: 1e-12 of the largest
/// mid-span compliance L³/(48EI) of the fibres (a contact at a pinned support of both fibres, or a
/// normal along both axes).
double immovable_compliance(const std::vector<Fibre>& fibres);

/// The first contact that overlaps by more than `tolerance` (mm; `overlap[k]`) where nothing can
/// move it (`self_compliance[k]` ≤ immovable_compliance): such an overlap has no answer. Returns
/// the message naming the pair and the position, or nothing when every overlap can be resolved.
std::optional<std::string> find_unresolvable_overlap(const std::vector<Contact>& contacts,
                                                     const std::vector<double>& overlap,
                                                     const std::vector<double>& self_compliance,
                                                     double tolerance,
                                                     const std::vector<Fibre>& fibres,
                                                     const std::vector<WallSpec>& walls);

}  // namespace fibrecheck
