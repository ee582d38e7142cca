#include "contact_description.h"

#include <sstream>

namespace fibrecheck {

std::string describe(const Contact& c, const std::vector<Fibre>& fibres,
                     const std::vector<WallSpec>& walls) {
  std::ostringstream out;
  out.precision(4);
  if (c.kind == ContactKind::wall)
    out << "fibre " << fibres[c.a].id << " and wall " << walls[c.b].id << " at s = " << c.s_a
        << " of " << fibres[c.a].id;
  else
    out << "fibres " << fibres[c.a].id << " and " << fibres[c.b].id << " at s = " << c.s_a << " of "
        << fibres[c.a].id << " (s = " << c.s_b << " of " << fibres[c.b].id << ")";
  if (c.kind == ContactKind::line) out << ", slice " << c.slice;
  return out.str();
}

}  // namespace fibrecheck
