#include "tresca_fixed_point.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

#include "bounded_active_set.h"

namespace fibrecheck {

namespace {

/// Where the fixed point has settled (mm of slip): the round-off of the normal forces (the
/// threshold, far below the slips the loads cause), 1e-9 of the largest slip under the loads, or
/// 1e-3 of the scene's tolerance (the fixed point converges linearly, slowly where it is relaxed),
/// or the slack its caller allows.
double settled_slip(const FrictionalProblem& problem, const TrescaOptions& options) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  double slip_scale = 0.0;
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index i = problem.offset[k] + 1; i < problem.offset[k + 1]; ++i)
      slip_scale = std::max(slip_scale, std::fabs(problem.q[i]));
  return std::max({options.threshold, 1e-9 * slip_scale, 1e-3 * options.tolerance, options.slack});
}

/// The violation the radii can be settled to at all (mm). An inner answer's normal forces are
/// determined only to cond(W_FF)·ε of the largest (the pivot ratio of its factor, about
/// 1/cond(W_FF)), and a radius error μ·δP moves a slip by the contact's tangential compliance
/// times that. Where the free set is nearly singular (contacts that constrain the same motion
/// twice, solved regularised) this lies far above the round-off of the slips, and each Tresca
/// problem shares the force among those contacts differently below it.
double round_off_floor(const FrictionalProblem& problem, const std::vector<double>& compliance,
                       const Eigen::VectorXd& r, double pivot_ratio) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  double force = 0.0, slip_per_force = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    force = std::max(force, r[problem.offset[k]]);
    slip_per_force = std::max(slip_per_force, compliance[k]);
  }
  return problem.mu * std::numeric_limits<double>::epsilon() / pivot_ratio * force * slip_per_force;
}

/// Each contact's tangential compliance (mm/N, the slip per unit of friction: the largest
/// diagonal entry of its tangents), and whether anything moves along its tangents.
void tangential_compliances(const FrictionalProblem& problem, std::vector<double>& compliance,
                            std::vector<char>& movable) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  compliance.assign(n, 0.0);
  movable.assign(n, 0);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index o = problem.offset[k];
    for (Eigen::Index i = o + 1; i < problem.offset[k + 1]; ++i)
      compliance[k] = std::max(compliance[k], problem.W.coeff(i, i));
    movable[k] = !problem.excluded[k] && compliance[k] > 1e-12 * problem.W.coeff(o, o);
  }
}

/// The Tresca problem of one tangent per contact as a box: 0 ≤ P (P = 0 where excluded), and
/// −g ≤ F ≤ g along a tangent something moves along (F = 0 along the others).
void tresca_box(const FrictionalProblem& problem, const std::vector<char>& movable,
                Eigen::VectorXd& lo, Eigen::VectorXd& hi) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  lo = Eigen::VectorXd::Zero(problem.q.size());
  hi = Eigen::VectorXd::Constant(problem.q.size(), INFINITY);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index o = problem.offset[k];
    if (problem.excluded[k]) hi[o] = 0.0;
    for (Eigen::Index i = o + 1; i < problem.offset[k + 1]; ++i) {
      lo[i] = movable[k] ? -problem.bounds[k] : 0.0;
      hi[i] = movable[k] ? problem.bounds[k] : 0.0;
    }
  }
}

/// Coulomb's law for the answer `r` of the radii `problem.bounds`: a slipping contact's radius
/// must be μP, a sticking one's friction within μP (a sticking radius may differ from μP without
/// harm). Returns the largest violation times the contact's tangential compliance (mm), and moves
/// each radius by `relaxation` of the way to μP; a contact that slipped on its old circle is put
/// on the new one, and a zero radius (the contact slips freely) must become μP too.
double update_radii(FrictionalProblem& problem, const std::vector<double>& compliance,
                    double relaxation, Eigen::VectorXd& r) {
  const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
  double change = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index o = problem.offset[k];
    const double g = problem.mu * std::max(r[o], 0.0);
    const Eigen::Index t = problem.offset[k + 1] - o - 1;
    const double size = r.segment(o + 1, t).norm();
    const bool slipping = !(problem.bounds[k] > 0.0) || size >= (1.0 - 1e-9) * problem.bounds[k];
    change =
        std::max(change, (slipping ? std::fabs(g - problem.bounds[k]) : std::max(0.0, size - g)) *
                             compliance[k]);
    problem.bounds[k] += relaxation * (g - problem.bounds[k]);
    if (slipping && size > 0.0) r.segment(o + 1, t) *= problem.bounds[k] / size;
  }
  return change;
}

/// The radius updates' relaxation: halved (down to 1/64) when the violation grows, grown by half
/// (up to 1) after three updates in a row that lowered it.
struct Relaxation {
  double factor = 1.0;
  double last_change = INFINITY;
  int falling = 0;

  void adapt(double change) {
    if (change > last_change)
      factor = std::max(factor * 0.5, 1.0 / 64.0), falling = 0;
    else if (++falling >= 3)
      factor = std::min(factor * 1.5, 1.0), falling = 0;
    last_change = change;
  }
};

/// Why the fixed point did not settle: its last inner problem was not solved, or the radii still
/// moved the slips by `change` (mm) after `updates` updates, and Newton's method on Coulomb's law
/// did not settle from there either (its residual `coulomb`, mm).
std::string unsettled_message(const FrictionalProblem& problem, const TrescaOptions& options,
                              bool one_tangent, const FrictionalSolve& inner, int updates,
                              double change, double coulomb) {
  std::ostringstream out;
  out.precision(3);
  if (!inner.settled && one_tangent)
    out << "the frictional contact problem's Tresca problem was not solved in "
        << options.max_active_set_passes << " active-set passes, and Newton's method on Coulomb's "
        << "law from there leaves " << coulomb << " mm";
  else if (!inner.settled)
    out << "the frictional contact problem did not settle: after " << inner.newton_steps
        << " Newton steps on its Tresca problem Coulomb's law is still violated by "
        << inner.residual << " mm, and Newton's method on Coulomb's law from there leaves "
        << coulomb << " mm";
  else
    out << "the Tresca fixed point of the frictional contact problem did not settle: after "
        << updates << " updates the disk radii still move the slips by " << change
        << " mm, and Newton's method on Coulomb's law from there leaves " << coulomb << " mm";
  out << " (mu = " << problem.mu << "; the solution is unique only for small mu)";
  return out.str();
}

/// Newton's method on Coulomb's law itself (solve_frictional without radii) from `start`: true
/// when it settles to `settled` (mm), the answer in `r`; otherwise `r` and the radii stay as they
/// were. `residual` is what it left (mm).
bool finish_by_newton(FrictionalProblem& problem, const TrescaOptions& options, double settled,
                      const Eigen::VectorXd& start, TrescaSolve& result, Eigen::VectorXd& r,
                      double& residual) {
  const Eigen::VectorXd radii = problem.bounds;
  Eigen::VectorXd answer = start;
  problem.bounds.resize(0);
  const FrictionalSolve coulomb =
      solve_frictional(problem, settled, options.max_newton_steps, answer);
  problem.bounds = radii;
  result.newton_steps += coulomb.newton_steps;
  residual = coulomb.residual;
  result.finished_by_newton = coulomb.settled;
  if (coulomb.settled) r = answer;
  return coulomb.settled;
}

}  // namespace

TrescaSolve tresca_fixed_point(FrictionalProblem& problem, const TrescaOptions& options,
                               Eigen::VectorXd& r, const GrowProblem& grow) {
  TrescaSolve result;
  problem.bounds.resize(0);
  result.aimed = settled_slip(problem, options);
  double settled = result.aimed;
  bool one_tangent = true;
  std::vector<double> compliance;
  std::vector<char> movable;
  std::unique_ptr<FreeSetFactor> free_set;
  // What follows the problem's contacts: their radii (μP for those that join), the tangential
  // compliances and the free set's factor.
  const auto take_contacts = [&] {
    const Eigen::Index before = problem.bounds.size();
    const Eigen::Index n = static_cast<Eigen::Index>(problem.offset.size()) - 1;
    problem.bounds.conservativeResize(n);
    for (Eigen::Index k = before; k < n; ++k) {
      problem.bounds[k] = problem.mu * std::max(r[problem.offset[k]], 0.0);
      one_tangent &= problem.offset[k + 1] - problem.offset[k] <= 2;
    }
    tangential_compliances(problem, compliance, movable);
    free_set = std::make_unique<FreeSetFactor>(problem.W);
  };
  take_contacts();
  FrictionalSolve inner;
  Relaxation relaxation;
  // Newton's method starts from the answer of the smallest violation so far (on a stalled fixed
  // point the last answer may be far from it).
  Eigen::VectorXd best;
  double change = INFINITY, lowest = INFINITY, coulomb_residual = INFINITY;
  int updates = 0, lowest_at = 0;
  bool newton_tried = false, exact_radii = false;
  for (updates = 1; updates <= options.max_updates; ++updates) {
    if (one_tangent) {
      Eigen::VectorXd lo, hi;
      tresca_box(problem, movable, lo, hi);
      const BoundedSolve box = bounded_active_set(*free_set, problem.q, lo, hi, options.threshold,
                                                  options.max_active_set_passes, r);
      result.active_set_passes += box.passes;
      settled =
          std::max(result.aimed, round_off_floor(problem, compliance, r, free_set->pivot_ratio()));
      inner.settled = box.solved;
      inner.newton_steps = 0;
      inner.residual = box.solved ? 0.0 : INFINITY;
    } else {
      inner = solve_frictional(problem, options.threshold, options.max_newton_steps, r);
      result.newton_steps += inner.newton_steps;
    }
    if (!inner.settled) break;
    if (grow && grow(problem, r)) {
      lowest = INFINITY, lowest_at = updates;
      take_contacts();
      continue;
    }
    // Settled with relaxed radii, the fixed point takes one more inner problem and puts the radii
    // on μP exactly (as the plain update does): a relaxed radius leaves a contact that slips a
    // hair inside its disk (counted as sticking, with all its slip) or outside the cone.
    if (exact_radii) {
      update_radii(problem, compliance, 1.0, r);
      break;
    }
    const double factor = relaxation.factor;
    change = update_radii(problem, compliance, factor, r);
    relaxation.adapt(change);
    if (change <= settled && factor == 1.0) {
      result.settled_to = settled;
      break;
    }
    exact_radii = change <= settled;
    if (exact_radii) result.settled_to = settled;
    if (change < lowest) lowest = change, lowest_at = updates, best = r;
    if (!newton_tried && updates - lowest_at >= options.stall_updates) {
      newton_tried = true;
      if (finish_by_newton(problem, options, settled, best, result, r, coulomb_residual)) break;
    }
  }
  result.updates = std::min(updates, options.max_updates);
  // Judged by the floor the stop was decided on (the last inner answer's may lie lower).
  result.settled_to = std::max(result.settled_to, settled);
  // An inner problem its semismooth Newton method did not solve: it can cycle on a Tresca problem
  // with disks where Newton's method on Coulomb's law itself, started from where it stopped,
  // settles (friction wedging stiff fibres onto a tow).
  if (!inner.settled) {
    const Eigen::VectorXd stopped = r;
    inner.settled =
        finish_by_newton(problem, options, result.settled_to, stopped, result, r, coulomb_residual);
  }
  if (inner.settled && change > result.settled_to && !result.finished_by_newton)
    finish_by_newton(problem, options, result.settled_to, best.size() == r.size() ? best : r,
                     result, r, coulomb_residual);
  if (result.finished_by_newton) change = coulomb_residual;
  result.settled = inner.settled && !(change > result.settled_to);
  if (!result.settled)
    result.trouble = unsettled_message(problem, options, one_tangent, inner, result.updates, change,
                                       coulomb_residual);
  return result;
}

}  // namespace fibrecheck
