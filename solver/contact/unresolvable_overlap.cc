#include "unresolvable_overlap.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact_description.h"

namespace fibrecheck {

double immovable_compliance(const std::vector<Fibre>& fibres) {
  double scale = 0.0;
  for (const Fibre& f : fibres) scale = std::max(scale, std::pow(f.length, 3) / (48.0 * f.EI));
  return 1e-12 * scale;
}

std::optional<std::string> find_unresolvable_overlap(const std::vector<Contact>& contacts,
                                                     const std::vector<double>& overlap,
                                                     const std::vector<double>& self_compliance,
                                                     double tolerance,
                                                     const std::vector<Fibre>& fibres,
                                                     const std::vector<WallSpec>& walls) {
  const double immovable = immovable_compliance(fibres);
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (overlap[k] > tolerance && self_compliance[k] <= immovable) {
      std::ostringstream out;
      out.precision(3);
      out << "overlap " << overlap[k] << " mm between " << describe(contacts[k], fibres, walls)
          << " where neither can move (pinned supports): it cannot be resolved";
      return out.str();
    }
  return std::nullopt;
}

}  // namespace fibrecheck
