#include "contact.h"

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

}  // namespace fibrecheck
