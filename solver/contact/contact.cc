#include "contact.h"

#include <algorithm>

namespace fibrecheck {

const char* to_string(ContactKind kind) {
  switch (kind) {
    case ContactKind::point:
      return "point";
    case ContactKind::line:
      return "line";
    case ContactKind::wall:
      return "wall";
  }
  return "?";
}

std::vector<int> fibres_with_crossings(const std::vector<Contact>& contacts) {
  std::vector<int> fibres;
  for (const Contact& c : contacts)
    if (c.kind == ContactKind::point) fibres.push_back(c.a), fibres.push_back(c.b);
  std::sort(fibres.begin(), fibres.end());
  fibres.erase(std::unique(fibres.begin(), fibres.end()), fibres.end());
  return fibres;
}

}  // namespace fibrecheck
