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

/// Two fibres whose pinned supports overlap (support points closer than the sum of the radii, by
/// more than `tolerance`): the overlap sits where neither fibre can move, whether or not a slice
/// or a contact point falls on it (slices sit at the midpoints of their intervals, never at a
/// support). Returns the message naming the pair and the point.
std::optional<std::string> find_overlapping_supports(const std::vector<Fibre>& fibres,
                                                     double tolerance);

/// Overlapping supports (above), or the first contact that overlaps by more than `tolerance` (mm;
/// `overlap[k]`) where nothing can move it (`self_compliance[k]` ≤ immovable_compliance): such an
/// overlap has no answer. Returns the message naming the pair and the position, or nothing when
/// every overlap can be resolved.
std::optional<std::string> find_unresolvable_overlap(const std::vector<Contact>& contacts,
                                                     const std::vector<double>& overlap,
                                                     const std::vector<double>& self_compliance,
                                                     double tolerance,
                                                     const std::vector<Fibre>& fibres,
                                                     const std::vector<WallSpec>& walls);

}  // namespace fibrecheck
