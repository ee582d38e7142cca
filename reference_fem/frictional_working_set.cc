#include "frictional_working_set.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibrecheck {

namespace {

/// The largest slip under the loads alone (mm): what the fixed point's stop is measured against.
double largest_slip(const FrictionalProblem& problem) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  double largest = 0.0;
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index i = problem.offset[k] + 1; i < problem.offset[k + 1]; ++i)
      largest = std::max(largest, std::fabs(problem.q[i]));
  return largest;
}

/// The whole problem's contacts in a working set, and the problem restricted to them: their rows
/// of W gathered, their q, excluded and offsets, in the order they joined.
class WorkingSet {
 public:
  WorkingSet(const ContactCompliance& compliance, const FrictionalProblem& whole)
      : compliance_(compliance), whole_(whole), in_set_(whole.offset.size() - 1, 0) {
    part_.mu = whole.mu;
    part_.offset.push_back(0);
  }

  /// Contact k joins (its rows appended; W gathered again by `gather`).
  void add(Eigen::Index k) {
    in_set_[static_cast<std::size_t>(k)] = 1;
    for (Eigen::Index i = whole_.offset[k]; i < whole_.offset[k + 1]; ++i) rows_.push_back(i);
    part_.offset.push_back(static_cast<Eigen::Index>(rows_.size()));
    part_.excluded.push_back(whole_.excluded[k]);
  }

  void gather() {
    part_.W = compliance_.on_subset(rows_);
    part_.q.resize(static_cast<Eigen::Index>(rows_.size()));
    for (std::size_t i = 0; i < rows_.size(); ++i)
      part_.q[static_cast<Eigen::Index>(i)] = whole_.q[rows_[i]];
  }

  /// The candidates outside the set that the reaction `part_r` leaves overlapping join it (their
  /// reactions appended to `part_r`, zero): false when there are none.
  bool grow(const Eigen::VectorXd& part_r, Eigen::VectorXd& grown_r, double threshold) {
    const Eigen::VectorXd w = whole_.q - compliance_.times(whole_reaction(part_r));
    const std::size_t before = rows_.size();
    const Eigen::Index n = static_cast<Eigen::Index>(in_set_.size());
    for (Eigen::Index k = 0; k < n; ++k)
      if (!in_set_[k] && !whole_.excluded[k] && w[whole_.offset[k]] > threshold) add(k);
    if (rows_.size() == before) return false;
    gather();
    grown_r = part_r;
    grown_r.conservativeResize(static_cast<Eigen::Index>(rows_.size()));
    grown_r.tail(static_cast<Eigen::Index>(rows_.size() - before)).setZero();
    return true;
  }

  Eigen::VectorXd whole_reaction(const Eigen::VectorXd& part_r) const {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(whole_.q.size());
    for (std::size_t i = 0; i < rows_.size(); ++i)
      r[rows_[i]] = part_r[static_cast<Eigen::Index>(i)];
    return r;
  }

  const std::vector<Eigen::Index>& rows() const { return rows_; }
  FrictionalProblem& part() { return part_; }

 private:
  const ContactCompliance& compliance_;
  const FrictionalProblem& whole_;
  std::vector<char> in_set_;
  std::vector<Eigen::Index> rows_;
  FrictionalProblem part_;
};

}  // namespace

TrescaSolve tresca_on_working_set(const ContactCompliance& compliance,
                                  const FrictionalProblem& problem, const TrescaOptions& options,
                                  Eigen::VectorXd& r) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  TrescaOptions part_options = options;
  part_options.slack = std::max(options.slack, 1e-9 * largest_slip(problem));
  WorkingSet set(compliance, problem);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index o = problem.offset[k], m = problem.offset[k + 1] - o;
    if (!problem.excluded[k] && r.segment(o, m).cwiseAbs().maxCoeff() > 0.0) set.add(k);
  }
  set.gather();
  Eigen::VectorXd part_r(static_cast<Eigen::Index>(set.rows().size()));
  for (std::size_t i = 0; i < set.rows().size(); ++i)
    part_r[static_cast<Eigen::Index>(i)] = r[set.rows()[i]];
  const GrowProblem grow = [&](FrictionalProblem&, Eigen::VectorXd& inner_r) {
    Eigen::VectorXd grown;
    if (!set.grow(inner_r, grown, options.threshold)) return false;
    inner_r = std::move(grown);
    return true;
  };
  // Newton's method, which may finish the fixed point, does not ask: it is asked at the end, and
  // the fixed point goes on from there with any that join.
  TrescaSolve total;
  Eigen::VectorXd grown;
  for (Eigen::Index round = 0; round <= n; ++round) {
    const TrescaSolve solved = tresca_fixed_point(set.part(), part_options, part_r, grow);
    total.updates += solved.updates;
    total.active_set_passes += solved.active_set_passes;
    total.newton_steps += solved.newton_steps;
    total.finished_by_newton = total.finished_by_newton || solved.finished_by_newton;
    total.settled = solved.settled;
    total.aimed = solved.aimed;
    total.settled_to = std::max(total.settled_to, solved.settled_to);
    total.trouble = solved.trouble;
    if (!solved.settled || !set.grow(part_r, grown, options.threshold)) break;
    part_r = std::move(grown);
  }
  r = set.whole_reaction(part_r);
  return total;
}

}  // namespace fibrecheck
