#include "primal_dual_active_set.h"

#include <functional>
#include <string>
#include <unordered_set>

namespace fibrecheck {

ActiveSetSolve primal_dual_active_set(const ContactCompliance& W, const Eigen::VectorXd& d0,
                                      double tolerance, const std::vector<char>& excluded,
                                      int max_passes, Eigen::VectorXd& P,
                                      std::vector<char>& pushing) {
  ActiveSetSolve result;
  const Eigen::Index n = d0.size();
  pushing.resize(n, 0);
  for (Eigen::Index k = 0; k < n; ++k)
    if (excluded[k]) pushing[k] = 0;
  std::unordered_set<std::size_t> seen;
  const auto key = [&] {
    return std::hash<std::string>()(std::string(pushing.begin(), pushing.end()));
  };
  seen.insert(key());
  for (result.passes = 1; result.passes <= max_passes; ++result.passes) {
    std::vector<Eigen::Index> index;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k]) index.push_back(k);
    Eigen::VectorXd ds(static_cast<Eigen::Index>(index.size())), Ps;
    for (std::size_t i = 0; i < index.size(); ++i) ds[i] = d0[index[i]];
    if (!W.solve_on_subset(index, ds, Ps)) return result;
    P = Eigen::VectorXd::Zero(n);
    for (std::size_t i = 0; i < index.size(); ++i) P[index[i]] = Ps[i];
    const Eigen::VectorXd d = d0 - W.times(P);
    bool changed = false;
    for (Eigen::Index k = 0; k < n; ++k) {
      const char next = excluded[k] ? 0 : pushing[k] ? (P[k] > 0.0) : (d[k] > tolerance);
      changed |= next != pushing[k];
      pushing[k] = next;
    }
    if (!changed) {
      result.solved = true;
      return result;
    }
    if (!seen.insert(key()).second) break;  // a set came back: it cycles
  }
  // Where it stopped: the forces of the set it had, none negative, for the other method.
  P = P.cwiseMax(0.0);
  for (Eigen::Index k = 0; k < n; ++k)
    if (P[k] == 0.0) pushing[k] = 0;
  return result;
}

}  // namespace fibrecheck
