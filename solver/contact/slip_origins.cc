#include "slip_origins.h"

#include <algorithm>
#include <cmath>

namespace fibrecheck {

SlipOrigins::SlipOrigins(const std::vector<Contact>& contacts,
                         const std::vector<Eigen::Vector3d>& u_a,
                         const std::vector<Eigen::Vector3d>& u_b, const Result& finished) {
  for (std::size_t k = 0; k < contacts.size(); ++k)
    relative_[contacts[k].key()] = contacts[k].relative(u_a[k], u_b[k]);
  for (const FibreResult& f : finished.fibres) samples_.push_back(f.displacement);
}

Eigen::Vector3d SlipOrigins::sampled(int fibre, double s) const {
  if (fibre < 0 || static_cast<std::size_t>(fibre) >= samples_.size()) return {0, 0, 0};
  const std::vector<Eigen::Vector3d>& u = samples_[fibre];
  if (u.size() < 2) return {0, 0, 0};
  const double x = std::clamp(s, 0.0, 1.0) * static_cast<double>(u.size() - 1);
  const std::size_t j = std::min(static_cast<std::size_t>(x), u.size() - 2);
  const double w = x - static_cast<double>(j);
  return (1.0 - w) * u[j] + w * u[j + 1];
}

void SlipOrigins::set(std::vector<Contact>& contacts) const {
  for (Contact& c : contacts) {
    auto it = relative_.find(c.key());
    if (it != relative_.end()) {
      c.origin = it->second;
      continue;
    }
    const Eigen::Vector3d u_a = sampled(c.a, c.s_a);
    const Eigen::Vector3d u_b =
        c.kind == ContactKind::wall ? Eigen::Vector3d::Zero().eval() : sampled(c.b, c.s_b);
    c.origin = c.relative(u_a, u_b);
  }
}

}  // namespace fibrecheck
