#include "ambiguous_sides.h"

#include <cmath>

#include "contact_description.h"

namespace fibrecheck {

std::vector<std::string> ambiguous_side_warnings(const std::vector<Contact>& contacts,
                                                 const std::vector<Fibre>& fibres,
                                                 const std::vector<WallSpec>& walls) {
  std::vector<std::string> warnings;
  for (const Contact& c : contacts) {
    const double r =
        std::min(fibres[c.a].radius, c.kind == ContactKind::wall ? INFINITY : fibres[c.b].radius);
    if (c.overlap > r) {
      warnings.push_back("initial overlap above the radius between " + describe(c, fibres, walls) +
                         ": the contact side is ambiguous");
      break;
    }
  }
  std::size_t held = 0;
  for (const Contact& c : contacts) held += c.normal_held ? 1 : 0;
  if (held > 0)
    warnings.push_back(std::to_string(held) +
                       " contacts whose undeformed centres nearly coincide: their normal was "
                       "chosen, not measured, and the contact side is ambiguous");
  return warnings;
}

}  // namespace fibrecheck
