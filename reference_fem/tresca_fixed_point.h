#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

#include "frictional_contact.h"

namespace fibrecheck {

struct TrescaOptions {
  double threshold = 0.0;  ///< mm: the overlaps and slips the inner problems resolve
  double tolerance = 0.0;  ///< mm: the scene's overlap tolerance t_d
  /// mm: the radii need settle no further than this, where the problem is itself one step of a
  /// sequence that will change it by about as much (0: settle to the fixed point's own stop).
  double slack = 0.0;
  int max_active_set_passes = 100000;
  int max_newton_steps = 100;
  int max_updates = 500;
  int stall_updates = 20;
};

struct TrescaSolve {
  bool settled = false;  ///< every inner problem solved and the disk radii settled
  int updates = 0;       ///< radius updates (fixed-point iterations)
  long active_set_passes = 0;
  long newton_steps = 0;
  /// The fixed point stalled and Newton's method on Coulomb's law settled it.
  bool finished_by_newton = false;
  /// mm: the violation of Coulomb's law the radii were to settle to, and the one they were judged
  /// by: larger where the sticking contacts' equations leave the slips determined only that far.
  double aimed = 0.0, settled_to = 0.0;
  std::string trouble;  ///< why it did not settle (empty when it did)
};

/// Coulomb's law at every contact of one load step (DESIGN §3), solved exactly as a Tresca fixed
/// point. With each contact's disk radius g_j held fixed, the frictional problem is convex (a
/// Tresca problem): for slices and walls alone (one tangent per contact) it is the box-constrained
/// QP 0 ≤ P, |F| ≤ g, solved exactly by bounded_active_set; with crossings (two tangents, a disk)
/// by the semismooth Newton method of solve_frictional with `problem.bounds` set. The radii then
/// move to μ times the normal forces they produced, and the two repeat until the radii produce the
/// normal forces they assumed: the largest violation of Coulomb's law, times the contact's
/// tangential compliance (the slip it stands for, mm), below the larger of `threshold`, 1e-9 of the
/// largest slip under the loads and 1e-3 of the scene's tolerance — a thousand times tighter than
/// the iterative solver's stopping criterion — or `slack` where that is larger; or, with one
/// tangent per contact, the floor the round-off of the inner answers sets, where that is larger
/// still (the free set nearly singular: the answer then says how far it was settled). Coulomb's law
/// itself, solved by Newton's method, cycles between sticking and slipping sets on compacted tows;
/// so does the plain map g ← μP, which is therefore relaxed (halved down to 1/64 while the
/// violation grows, grown again while it falls). Where even so the violation reaches no new low in
/// `stall_updates` updates, Newton's method on Coulomb's law itself (solve_frictional without
/// bounds) finishes from the answer of the fixed point's smallest violation (a stalled fixed point
/// wanders off it): started that close it settles, where from the frictionless answer it cycles.
/// Where it does not, the fixed point goes on from where it was, and Newton's method is tried once
/// more if the updates run out. An inner problem with disks whose semismooth Newton method cycles
/// (friction wedging stiff fibres onto a tow) hands over to Newton's method on Coulomb's law the
/// same way, from where its solve stopped. The fixed point stalls where a contact's friction loads
/// its own normal force about as much as the normal force moves the radius (μ·∂P/∂g near 1, the
/// radius creeping a little further at every update), or where contacts that constrain nearly the
/// same motion share a normal force in a way each Tresca problem settles differently. The iterative
/// solver has a Tresca fixed point of its own; this one is written apart from it on purpose, since
/// the reference must not share a solution method with what it checks.
///
/// `r` holds the start (the frictionless answer and the friction carried over) on entry and the
/// answer on return; `problem.excluded` marks the contacts nothing can move, and `problem.bounds`
/// is set here. `grow`, where given, is asked after every inner problem whether contacts left out
/// of `problem` must join it (a working set, frictional_working_set.h): it appends them (and their
/// reactions, zero, to `r`) and returns true, and the inner problem is solved again with them.
using GrowProblem = std::function<bool(FrictionalProblem& problem, Eigen::VectorXd& r)>;
TrescaSolve tresca_fixed_point(FrictionalProblem& problem, const TrescaOptions& options,
                               Eigen::VectorXd& r, const GrowProblem& grow = {});

}  // namespace fibrecheck
