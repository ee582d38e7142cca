#include "carry_over.h"

#include <algorithm>
#include <unordered_map>

namespace fibrecheck {

std::vector<long> carry_over(const std::vector<Contact>& previous, std::vector<Contact>& found) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t k = 0; k < previous.size(); ++k) index[previous[k].key()] = k;
  std::vector<long> origin(found.size(), -1);
  for (std::size_t i = 0; i < found.size(); ++i) {
    auto it = index.find(found[i].key());
    if (it == index.end()) continue;
    const Contact& old = previous[it->second];
    found[i].force = old.force;
    found[i].friction = old.friction;
    found[i].origin = old.origin;
    origin[i] = static_cast<long>(it->second);
    index.erase(it);
  }
  // In the order of `previous`, so that the result does not depend on the hash table's.
  std::vector<std::size_t> left;
  for (const auto& [key, k] : index)
    if (previous[k].force > 0.0) left.push_back(k);
  std::sort(left.begin(), left.end());
  for (std::size_t k : left) {
    found.push_back(previous[k]);
    origin.push_back(static_cast<long>(k));
  }
  return origin;
}

}  // namespace fibrecheck
