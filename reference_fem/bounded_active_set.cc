#include "bounded_active_set.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "contact_compliance.h"
#include "free_set_factor.h"
#include "subset_solve.h"

namespace fibrecheck {

namespace {

/// The variables' states and values during one solve: −1 held at lo, +1 held at hi, 0 free.
class BoundedSet {
 public:
  BoundedSet(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& q,
             const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, Eigen::VectorXd& r,
             int& free_solves, FreeSetFactor& factor)
      : W_(W),
        q_(q),
        lo_(lo),
        hi_(hi),
        r_(r),
        state_(q.size(), 0),
        free_solves_(free_solves),
        factor_(factor),
        free_(q.size(), 0) {
    for (Eigen::Index i = 0; i < q.size(); ++i)
      state_[i] = r[i] <= lo[i] ? -1 : (r[i] >= hi[i] ? 1 : 0);
  }

  /// The free variables' equations W_FF·z_F = q_F − W_FB·r_B solved, the held ones kept: false
  /// when they cannot be solved. The kept factor answers them (free_set_factor.h: the free set
  /// changes by the few variables a step held or a pass freed), its answer `judged` by its
  /// residual or not; where even a fresh one cannot, solve_on_subset factorises them afresh.
  bool free_solve(Eigen::VectorXd& z, bool judged) {
    ++free_solves_;
    const Eigen::Index n = q_.size();
    std::vector<Eigen::Index> index;
    for (Eigen::Index i = 0; i < n; ++i) {
      free_[i] = state_[i] == 0 ? 1 : 0;
      if (free_[i]) index.push_back(i);
    }
    z = r_;
    by_factor_ = false;
    const Eigen::Index m = static_cast<Eigen::Index>(index.size());
    if (m == 0) return true;
    Eigen::VectorXd x;
    if (factor_.solve(free_, load_, x, judged)) {
      for (Eigen::Index i : index) z[i] = x[i];
      by_factor_ = true;
      return true;
    }
    Eigen::VectorXd b(m);
    for (Eigen::Index k = 0; k < m; ++k) b[k] = load_[index[k]];
    if (!solve_on_subset(W_, index, b, x)) return false;
    for (Eigen::Index k = 0; k < m; ++k) z[index[k]] = x[k];
    return true;
  }

  /// Solves on the free set, stepping back to the box: the variables that reach a bound first
  /// (several at once where they reach it together: the slices of a line contact slipping as one)
  /// are held there, and the free set solved again, until the answer lies in the box. The solves
  /// on the way only choose where each step stops; the answer it ends on is judged by its residual
  /// (and where it fails, the solves go on judged). The right-hand side q − W_FB·r_B is made once
  /// and then follows the variables as they are held, a column each: it skips the columns held at
  /// zero, most of them on a tow (the candidates that do not push, and their tangents).
  bool settle() {
    const Eigen::Index n = q_.size();
    Eigen::VectorXd held = r_;
    for (Eigen::Index i = 0; i < n; ++i)
      if (state_[i] == 0) held[i] = 0.0;
    load_ = q_ - AssembledCompliance(W_).times(held);
    Eigen::VectorXd z, reach(n);
    bool judged = false;
    for (Eigen::Index guard = 0; guard <= n; ++guard) {
      if (!free_solve(z, judged)) return false;
      double alpha = INFINITY;
      for (Eigen::Index i = 0; i < n; ++i) {
        reach[i] = INFINITY;
        if (state_[i] != 0 || (z[i] >= lo_[i] && z[i] <= hi_[i])) continue;
        const double bound = z[i] < lo_[i] ? lo_[i] : hi_[i];
        reach[i] = std::clamp((bound - r_[i]) / (z[i] - r_[i]), 0.0, 1.0);
        alpha = std::min(alpha, reach[i]);
      }
      if (alpha == INFINITY) {
        if (!judged && by_factor_ && !factor_.answers(free_, load_, z)) {
          judged = true;
          continue;
        }
        r_ = z;
        return true;
      }
      r_ += alpha * (z - r_);
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!(reach[i] <= alpha + 1e-12)) continue;
        state_[i] = z[i] < lo_[i] ? -1 : 1;
        r_[i] = state_[i] < 0 ? lo_[i] : hi_[i];
        hold(i);
      }
      r_ = r_.cwiseMax(lo_).cwiseMin(hi_);
    }
    return true;
  }

  double objective() const { return 0.5 * r_.dot(W_ * r_) - q_.dot(r_); }

  /// The held variables whose bound the objective wants to leave (w = q − W·r beyond `tolerance`
  /// pointing inside), with how far, and how many are free; fixed and set-aside ones stay.
  std::vector<std::pair<double, Eigen::Index>> leaving(double tolerance,
                                                       const std::vector<char>& set_aside,
                                                       std::size_t& free_count) const {
    const Eigen::VectorXd w = q_ - W_ * r_;
    std::vector<std::pair<double, Eigen::Index>> out;
    free_count = 0;
    for (Eigen::Index i = 0; i < q_.size(); ++i) {
      if (state_[i] == 0) {
        ++free_count;
        continue;
      }
      if (lo_[i] >= hi_[i] || set_aside[i]) continue;
      if (state_[i] < 0 && w[i] > tolerance) out.push_back({w[i], i});
      if (state_[i] > 0 && w[i] < -tolerance) out.push_back({-w[i], i});
    }
    return out;
  }

  void free(Eigen::Index i) { state_[i] = 0; }

 private:
  const Eigen::SparseMatrix<double>& W_;
  const Eigen::VectorXd& q_;
  const Eigen::VectorXd& lo_;
  const Eigen::VectorXd& hi_;
  Eigen::VectorXd& r_;
  std::vector<signed char> state_;
  int& free_solves_;
  FreeSetFactor& factor_;
  Eigen::VectorXd load_;    ///< q − W_FB·r_B of the present free set
  std::vector<char> free_;  ///< the free set of the last solve
  bool by_factor_ = false;  ///< the last solve's answer came from the kept factor

  /// Variable i held at its bound: its column joins W_FB·r_B.
  void hold(Eigen::Index i) {
    if (r_[i] == 0.0) return;
    for (Eigen::SparseMatrix<double>::InnerIterator it(W_, i); it; ++it)
      load_[it.row()] -= it.value() * r_[i];
  }
};

}  // namespace

BoundedSolve bounded_active_set(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                double tolerance, int max_passes, Eigen::VectorXd& r) {
  FreeSetFactor factor(W);
  return bounded_active_set(factor, q, lo, hi, tolerance, max_passes, r);
}

BoundedSolve bounded_active_set(FreeSetFactor& factor, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                double tolerance, int max_passes, Eigen::VectorXd& r) {
  const Eigen::SparseMatrix<double>& W = factor.matrix();
  BoundedSolve result;
  const Eigen::Index n = q.size();
  if (r.size() != n) r = Eigen::VectorXd::Zero(n);
  r = r.cwiseMax(lo).cwiseMin(hi);
  BoundedSet set(W, q, lo, hi, r, result.free_solves, factor);
  bool one_at_a_time = false;
  std::vector<char> set_aside(n, 0);
  std::vector<Eigen::Index> added;
  double before = INFINITY;
  for (result.passes = 0; result.passes < max_passes; ++result.passes) {
    if (!set.settle()) {
      if (!one_at_a_time) {
        one_at_a_time = true;
        continue;
      }
      result.singular = true;
      return result;
    }
    // A pass that gained nothing (round-off decides it): one variable at a time, and a single one
    // that gains nothing is set aside until something changes.
    const double now = set.objective();
    const bool progress = now < before - 1e-14 * std::fabs(before);
    if (progress) {
      std::fill(set_aside.begin(), set_aside.end(), 0);
      one_at_a_time = false;
    } else if (std::isfinite(before)) {
      if (one_at_a_time && added.size() == 1) set_aside[added[0]] = 1;
      one_at_a_time = true;
    }
    before = std::min(before, now);
    std::size_t free_count = 0;
    std::vector<std::pair<double, Eigen::Index>> leaving =
        set.leaving(tolerance, set_aside, free_count);
    if (leaving.empty()) {
      result.solved = true;
      return result;
    }
    const std::size_t add =
        one_at_a_time ? 1 : std::min(leaving.size(), std::max<std::size_t>(8, free_count));
    std::partial_sort(leaving.begin(), leaving.begin() + static_cast<long>(add), leaving.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
    added.clear();
    for (std::size_t k = 0; k < add; ++k) {
      set.free(leaving[k].second);
      added.push_back(leaving[k].second);
    }
  }
  return result;
}

}  // namespace fibrecheck
