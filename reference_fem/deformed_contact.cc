// The deformed contact in the reference: a sequence of exact contact solves, each linearised about
// the configuration of the reference's own finite-element fibres that the one before left.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "normal_mixing.h"
#include "reference_solver_class.h"

namespace fibrecheck {

namespace {

/// Geometric updates a step may take before the reference says its normals did not settle.
constexpr int kMaxGeometricUpdates = 200;
/// New meshes a step takes for crossings that move, whatever their steps. Each move is a Newton
/// step towards the closest points, on tangents estimated from the detection grid; a crossing's
/// place sets its normal to first order but its gap only to second, so the moves go on to the
/// closest points rather than until the gap stops changing.
constexpr int kMaxCrossingMoves = 5;
/// New meshes a step may take in all while the moves converge: each further move's largest step
/// at most nine tenths of the one before (crossings that slide with friction close in by about
/// half a move). Near the answer the grid's tangents and the new mesh's own solution can leave
/// steps that no longer shrink, back and forth.
constexpr int kMostCrossingMoves = 30;
/// A change of the unit normals below which the next solve would be the last one again.
constexpr double kUnturned = 1e-12;
/// A change of the unit normals below which the answer's forces act along its own displaced
/// centres: the seed's test alone cannot tell, since the gaps close about the wrong normals too.
constexpr double kSettledTurn = 1e-8;
/// Updates the mixing of the normals remembers.
constexpr int kMixedUpdates = 4;

}  // namespace

// The seed's test on the contacts as they stand (Eq. 4.15): the largest |gap| of the displaced
// centres where a contact pushes, and the largest overlap where none does (mm).
double ReferenceSolver::deformed_residual(const std::vector<Eigen::Vector3d>& u_a,
                                          const std::vector<Eigen::Vector3d>& u_b) const {
  double residual = 0.0;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const double gap = detector_.geometry().deformed_gap(contacts_[k], u_a[k], u_b[k]);
    residual = std::max(residual, contacts_[k].force > 0.0 ? std::fabs(gap) : -gap);
  }
  return residual;
}

double ReferenceSolver::largest_relative_displacement(
    const std::vector<Eigen::Vector3d>& u_a, const std::vector<Eigen::Vector3d>& u_b) const {
  double largest = 0.0;
  for (std::size_t k = 0; k < contacts_.size(); ++k)
    largest = std::max(largest, (u_b[k] - u_a[k]).norm());
  return largest;
}

// The largest distance (mm) a crossing of `moved` lies along either fibre from where it is now.
double ReferenceSolver::largest_crossing_step(const std::vector<Contact>& moved) const {
  double largest = 0.0;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    if (contacts_[k].kind != ContactKind::point) continue;
    const double along_a = std::fabs(moved[k].s_a - contacts_[k].s_a) * fibres_[moved[k].a].length;
    const double along_b = std::fabs(moved[k].s_b - contacts_[k].s_b) * fibres_[moved[k].b].length;
    largest = std::max({largest, along_a, along_b});
  }
  return largest;
}

// Whether crossings that would move by up to `step` get a new mesh: the first kMaxCrossingMoves
// times, then while each move's step is at most nine tenths of the last one's.
bool ReferenceSolver::crossings_move_on(double step) {
  const bool converging = step <= 0.9 * last_crossing_step_;
  if (crossing_moves_ >= kMostCrossingMoves) return false;
  if (crossing_moves_ >= kMaxCrossingMoves && !converging) return false;
  ++crossing_moves_;
  last_crossing_step_ = step;
  return true;
}

// The overlaps d0 and the compliance W of the current candidates again, on the same mesh, about the
// normals they have now: the stored influence matrices and loads' displacements, nothing solved
// again, and W filled in place (its pattern is that of the same candidates).
void ReferenceSolver::assemble_about_normals() {
  dealii::TimerOutput::Scope scope(timer_, "assemble_system");
  const std::vector<std::vector<ContactSide>> sides = assemble_compliance(G_, true);
  if (mu_ > 0.0) assemble_frictional_problem(G_, sides, true);
}

// After an exact solve on given normals: the finite-element fibres under its forces, the normals
// (and tangents, and the crossings' places) moved to their displaced centres, and the problem
// linearised about them solved again, until the answer meets the seed's test in the deformed
// configuration to 1e-3 of the scene's tolerance (or to the round-off of the finite elements) with
// normals that no longer turn by more than kSettledTurn (or whose turn stalls just above it, at the
// round-off of the finite elements; or that no longer turn at all, and the residual left is the
// linearised solve's own). The normals each problem is linearised about are those of the displaced
// centres mixed with the updates before (normal_mixing.h): the plain sequence contracts by about
// 0.7 an update on compacted tows. A crossing whose closest points lie elsewhere needs a new mesh
// (while its moves converge, crossings_move_on): the outer loop takes it from there.
void ReferenceSolver::follow_the_deformed_fibres() {
  const double settled = std::max(threshold_, 1e-3 * tolerance_);
  std::vector<Eigen::Vector3d> u_a, u_b;
  double residual = INFINITY, before = INFINITY, turned_before = INFINITY;
  NormalMixing mixing(kMixedUpdates);
  for (int update = 0; update < kMaxGeometricUpdates; ++update) {
    deform();
    displacements_at_contacts(u_a, u_b);
    std::vector<Contact> moved = contacts_;
    if (detector_.point_search() && detector_.follow_crossings(grid_u_, moved, u_a, u_b) &&
        crossings_move_on(largest_crossing_step(moved))) {
      moved_crossings_ = std::move(moved);
      remesh_ = true;
      return;
    }
    residual = deformed_residual(u_a, u_b);
    double turned = 0.0;
    std::vector<Contact> followed = contacts_;
    for (std::size_t k = 0; k < followed.size(); ++k) {
      detector_.geometry().follow(followed[k], u_a[k], u_b[k]);
      turned = std::max(turned, (followed[k].normal - contacts_[k].normal).norm());
    }
    // Normals that did not turn give the same solve again: what is left is that solve's own.
    // Settled, or within t_d and no longer falling: the round-off of the finite elements.
    const bool gaps_closed =
        residual <= settled || (residual < tolerance_ && residual > 0.5 * before);
    const bool turn_stalled = turned < 1e2 * kSettledTurn && turned > 0.5 * turned_before;
    if (turned <= kUnturned || (gaps_closed && (turned <= kSettledTurn || turn_stalled))) {
      if (update > 0) settle_the_friction();
      return;
    }
    report_geometric_update(residual, turned);
    // Mixing that made the normals turn more than the update before starts again from here.
    if (turned > turned_before) mixing.restart();
    mix_normals(mixing, followed);
    before = residual;
    turned_before = turned;
    contacts_ = std::move(followed);
    ++geometric_updates_;
    assemble_about_normals();
    // The normals will turn again by about as much as they just did: the friction need not settle
    // tighter than a tenth of the slip a turn that size misdirects.
    friction_slack_ = 0.1 * turned * largest_relative_displacement(u_a, u_b);
    solve(Start::last_answer);
    friction_slack_ = 0.0;
    if (!trouble_.why.empty()) return;
  }
  std::ostringstream out;
  out.precision(3);
  out << "the normals of the deformed contact did not settle: after " << kMaxGeometricUpdates
      << " exact solves, each linearised about the fibres the one before left, a contact still "
         "pushes across (or overlaps by) "
      << residual << " mm";
  trouble_.why = out.str();
  trouble_.normals_unsettled = true;
}

// The normals `followed` has (those of the displaced centres) replaced by the mixing of them with
// the updates before.
void ReferenceSolver::mix_normals(NormalMixing& mixing, std::vector<Contact>& followed) const {
  const Eigen::Index n = static_cast<Eigen::Index>(contacts_.size());
  Eigen::VectorXd x(3 * n), g(3 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    x.segment<3>(3 * k) = contacts_[k].normal;
    g.segment<3>(3 * k) = followed[k].normal;
  }
  const Eigen::VectorXd next = mixing.mix(x, g);
  for (Eigen::Index k = 0; k < n; ++k)
    if (followed[k].kind != ContactKind::wall && next.segment<3>(3 * k) != g.segment<3>(3 * k))
      detector_.geometry().turn(followed[k], next.segment<3>(3 * k));
}

// The answer's friction settled to the Tresca fixed point's own stop: the last solve of the
// geometric updates settled it only to a tenth of the slip the turn before misdirects, and the
// updates may end on a turn stalled near 1e-6 rad (the round-off of the finite elements), far
// above the round-off of the friction.
void ReferenceSolver::settle_the_friction() {
  if (mu_ > 0.0) solve(Start::last_answer);
}

// A line per geometric update, for options_.progress: a step on compacted tows can take many.
void ReferenceSolver::report_geometric_update(double residual, double turned) const {
  if (!options_.progress) return;
  std::ostringstream out;
  out.precision(3);
  out << "  geometric update " << geometric_updates_ + 1 << ": the seed's test leaves " << residual
      << " mm, normals turn by up to " << turned;
  if (mu_ > 0.0) out << "; " << tresca_updates_ << " Tresca updates so far";
  options_.progress(out.str());
}

}  // namespace fibrecheck
