#include "error_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "compliance_on_subset.h"
#include "compliance_operator.h"
#include "coulomb_answer.h"
#include "fibre_stiffness.h"
#include "frictionless_problem.h"
#include "projected_cg.h"
#include "superposition.h"
#include "turning_normals.h"

namespace fibrecheck {

namespace {

/// A contact whose corrected force or overlap passes zero by more than this share of the final
/// residual switches.
constexpr double kSwitchingShare = 1e-6;
/// The contact problem solved from the final state is solved to this share of its residual: the
/// estimate then carries three digits of the error.
constexpr double kProblemShare = 1e-3;
/// With Coulomb friction, two digits: below that, contacts on the edge of their disks change state
/// at round-off and the Newton steps stall.
constexpr double kFrictionalShare = 1e-2;
constexpr int kMaxCgSteps = 400;
/// The contact problem from the final state is solved on the candidates within this many
/// residuals of touching (and those its answer brings there), in at most kProjectedWork products
/// with W times the candidates they are made over, a solve: 3 000 products over the 25 000
/// candidates near touching of a compacted 1 000-fibre tow. A problem that does not settle in
/// that (the contact problem of a long line contact solved to round-off) stops as soon.
constexpr double kNearTouching = 1.0;
constexpr double kProjectedWork = 7.5e7;
/// Deformed contact: at most this many turns of the normals, stopping when they turn by less
/// than kUnturned.
constexpr int kGeometricPasses = 8;
constexpr double kUnturned = 1e-10;
/// The largest contraction a sequence of turns is taken to have: its tail is then at most 19 times
/// its last change.
constexpr double kLargestContraction = 0.95;
constexpr double kCgReduction = 1e-8;
/// Changes of the pushing set the deformed contact's Newton steps make before they fall back to
/// the projected solve.
constexpr int kSetRounds = 10;
/// A round that changes more of the pushing set than this, or than a hundredth of it, started from
/// too rough a state for Newton's steps (the projected solve takes over).
constexpr int kFewChanges = 10;

/// x with W_AA·x = r on the contacts of `active` (their own list), by conjugate gradients
/// preconditioned with the fibres' stiffness at their stations.
Eigen::VectorXd solve_on(const Scene& scene, const std::vector<Fibre>& fibres,
                         std::vector<Contact> active, const Eigen::VectorXd& r) {
  const ComplianceOnSubset subset(scene, fibres, std::move(active));
  const ComplianceOperator& W = subset.compliance();
  const FibreStiffness& stiffness = subset.stiffness();
  const Eigen::Index n = r.size();
  const std::vector<unsigned char> all(static_cast<std::size_t>(n), 1);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), res = r, z(n), p, q;
  stiffness.apply(res, all, z);
  p = z;
  double rz = res.dot(z);
  const double stop = kCgReduction * r.norm();
  for (int step = 0; step < kMaxCgSteps && res.norm() > stop; ++step) {
    W.apply(p, q);
    const double pq = p.dot(q);
    if (!(pq > 0.0)) break;
    const double alpha = rz / pq;
    x += alpha * p;
    res -= alpha * q;
    stiffness.apply(res, all, z);
    const double rz_next = res.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return x;
}

/// True when the corrected forces `exact` keep the pushing set: none below zero where it pushes
/// (beyond a share kSwitchingShare of the largest force), no overlap beyond `slack` (mm) where it
/// does not: an overlap the estimate would not resolve to its own precision anyway.
bool switching_settled(const Eigen::VectorXd& exact, const Eigen::VectorXd& gap,
                       const std::vector<unsigned char>& pushes, double slack) {
  const double force_slack = kSwitchingShare * exact.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < exact.size(); ++k) {
    if (pushes[k] && exact[k] < -force_slack) return false;
    if (!pushes[k] && gap[k] > slack) return false;
  }
  return true;
}

/// The worst pair's |ΔF|/F on its resultant, as the comparison measures force errors: `f` the
/// forces on fibre A of the state's contacts, `g` those of the answer, contact by contact.
double pair_force_error(const std::vector<Contact>& contacts, const std::vector<Eigen::Vector3d>& f,
                        const std::vector<Eigen::Vector3d>& g) {
  std::map<std::tuple<int, int, int>, std::pair<Eigen::Vector3d, Eigen::Vector3d>> pairs;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    auto& [mine, theirs] = pairs
                               .try_emplace(std::make_tuple(static_cast<int>(c.kind), c.a, c.b),
                                            Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())
                               .first->second;
    mine += f[k];
    theirs += g[k];
  }
  double strongest = 0.0;
  for (const auto& [key, sides] : pairs) strongest = std::max(strongest, sides.second.norm());
  double worst = 0.0;
  for (const auto& [key, sides] : pairs) {
    const double truth = sides.second.norm(), mine = sides.first.norm();
    if (mine == 0.0 && truth == 0.0) continue;
    const double scale = truth > 1e-9 * strongest ? truth : std::max(strongest, 1e-300);
    worst = std::max(worst, std::fabs(mine - truth) / scale);
  }
  return worst;
}

/// The largest deflection difference over the largest deflection, at the result's samples: the
/// state's fibres under forces `g` on `beams`, the answer's under `f` on `answer_beams` (its
/// crossings where it moved them).
double deflection_error(const Scene& scene, const Superposition& beams,
                        const std::vector<Eigen::Vector3d>& g, const Superposition& answer_beams,
                        const std::vector<Eigen::Vector3d>& f) {
  const int samples = scene.output.samples;
  std::vector<double> s(samples);
  for (int j = 0; j < samples; ++j) s[j] = static_cast<double>(j) / (samples - 1);
  double largest = 0.0, difference = 0.0;
  std::vector<Eigen::Vector3d> u, v;
  for (int fibre = 0; fibre < static_cast<int>(scene.fibres.size()); ++fibre) {
    answer_beams.fibre_field(fibre, f, true, s, u);
    beams.fibre_field(fibre, g, true, s, v);
    for (int j = 0; j < samples; ++j) {
      largest = std::max(largest, u[j].norm());
      difference = std::max(difference, (u[j] - v[j]).norm());
    }
  }
  return largest > 0.0 ? difference / largest : 0.0;
}

/// Deformed contact: each crossing steps towards the closest points of the fibres deformed by the
/// forces `f` on `beams` (as the solver's crossings follow them, Eqs. 4.16–4.24 on the tangent
/// lines where it acts). True when one moved.
bool step_crossings(const ContactDetector& detector, const Superposition& beams,
                    const std::vector<Eigen::Vector3d>& f, std::vector<Contact>& contacts) {
  if (!detector.point_search()) return false;
  const std::vector<int> crossing = fibres_with_crossings(contacts);
  if (crossing.empty()) return false;
  std::vector<std::vector<Eigen::Vector3d>> grid_u(detector.geometry().fibres().size());
  for (int fibre : crossing) beams.fibre_field(fibre, f, true, detector.grid(), grid_u[fibre]);
  std::vector<Eigen::Vector3d> u_a, u_b;
  beams.contact_displacements(contacts, f, true, u_a, u_b);
  return detector.follow_crossings(grid_u, contacts, u_a, u_b);
}

double largest_norm(const std::vector<Eigen::Vector3d>& v) {
  double largest = 0.0;
  for (const Eigen::Vector3d& x : v) largest = std::max(largest, x.norm());
  return largest;
}

/// Under the deformed contact the answer's normals turn towards their own fixed point by about a
/// constant factor a pass (fibres leaning on each other roll: 0.85–0.9 on compacted tows), so that
/// the passes allowed can leave half the way still to go, and an estimate that stopped there saw
/// half the error. For a sequence that contracts by ρ the rest of the way is about ρ/(1 − ρ) times
/// its last change: the multiple of the last pass's change of the forces that is added to the
/// answer's forces where the passes ran out with the normals still turning. ρ is the ratio of the
/// last two changes, at most kLargestContraction.
double tail_of_turns(bool still_turning, double contraction) {
  if (!still_turning || !(contraction > 0.0)) return 0.0;
  const double rho = std::min(contraction, kLargestContraction);
  return rho / (1.0 - rho);
}

/// Each slice's misalignment under normal forces `P`: how far its displaced centres lie apart
/// across its normal, t·(B′c − A′c) (mm); zero for other contacts.
Eigen::VectorXd misalignments(const Superposition& beams, const ContactGeometry& geometry,
                              const std::vector<Contact>& contacts, const Eigen::VectorXd& P) {
  std::vector<Eigen::Vector3d> u_a, u_b;
  beams.contact_displacements(contacts, forces_on_a(contacts, P), true, u_a, u_b);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(P.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (c.kind != ContactKind::line || c.tangents != 1) continue;
    const double radii = geometry.fibres()[c.a].radius + geometry.fibres()[c.b].radius;
    const double distance = radii + geometry.deformed_gap(c, u_a[k], u_b[k]);
    e[static_cast<Eigen::Index>(k)] =
        distance * c.tangent.dot(geometry.deformed_normal(c, u_a[k], u_b[k]));
  }
  return e;
}

/// The answer of the deformed contact's Newton steps on a pushing set (turning_normals_answer),
/// from forces `P` with overlaps `d`: the set starts as the contacts that push or overlap, and
/// contacts whose force the answer takes below zero leave it, others the answer makes overlap join
/// it, until it holds (at most kSetRounds times, and only while each round changes few contacts and
/// fewer than the last: from a rough state the full Newton steps swing the set further each round).
/// The members' normals in `contacts` are the answer's. Empty where the set did not settle (the
/// contacts then as they were).
std::optional<Eigen::VectorXd> turning_answer(const Scene& scene, const std::vector<Fibre>& fibres,
                                              const Superposition& all,
                                              const ContactGeometry& geometry,
                                              std::vector<Contact>& contacts,
                                              const Eigen::VectorXd& P, const Eigen::VectorXd& d,
                                              double slack) {
  const Eigen::Index n = P.size();
  std::vector<unsigned char> member(contacts.size());
  for (Eigen::Index k = 0; k < n; ++k) member[k] = P[k] > 0.0 || d[k] > 0.0;
  const Eigen::VectorXd e = misalignments(all, geometry, contacts, P);
  int last_changes = std::numeric_limits<int>::max();
  for (int round = 0; round < kSetRounds; ++round) {
    std::vector<Eigen::Index> where;
    std::vector<Contact> taking_part;
    std::vector<unsigned char> pushes;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!member[k] && !(P[k] > 0.0)) continue;
      where.push_back(k);
      taking_part.push_back(contacts[static_cast<std::size_t>(k)]);
      pushes.push_back(member[k]);
    }
    const Eigen::Index m = static_cast<Eigen::Index>(where.size());
    Eigen::VectorXd from(m), left(m), across(m);
    for (Eigen::Index i = 0; i < m; ++i)
      from[i] = P[where[i]], left[i] = d[where[i]], across[i] = e[where[i]];
    const std::vector<Contact> held = taking_part;
    const Eigen::VectorXd x =
        turning_normals_answer(scene, fibres, geometry, taking_part, pushes, from, left, across);
    Eigen::VectorXd exact = P;
    for (Eigen::Index i = 0; i < m; ++i) {
      exact[where[i]] += x[i];
      contacts[static_cast<std::size_t>(where[i])] = taking_part[static_cast<std::size_t>(i)];
    }
    const Eigen::VectorXd gap = contact_overlaps(all, geometry, contacts, exact);
    const double force_slack = kSwitchingShare * exact.cwiseAbs().maxCoeff();
    int changes = 0;
    for (Eigen::Index k = 0; k < n; ++k) {
      const bool leaves = member[k] && exact[k] < -force_slack;
      const bool joins = !member[k] && gap[k] > slack;
      if (leaves || joins) member[k] = !member[k], ++changes;
    }
    if (changes == 0) return exact.cwiseMax(0.0);
    for (Eigen::Index i = 0; i < m; ++i)
      contacts[static_cast<std::size_t>(where[i])] = held[static_cast<std::size_t>(i)];
    const int members = static_cast<int>(std::count(member.begin(), member.end(), 1));
    if (changes >= last_changes || changes > std::max(kFewChanges, members / 100)) break;
    last_changes = changes;
  }
  return std::nullopt;
}

/// The answer of the problem linearised about the contacts' normals, from forces `P` with overlaps
/// `d`: the residual equation on the pushing set (on the deformed fibres with the slices' normals
/// turning, turning_answer), or where that set switches, the contact problem solved from `P`.
/// Counts its passes into `estimate` and says whether it settled.
Eigen::VectorXd linearised_answer(const Scene& scene, const std::vector<Fibre>& fibres,
                                  const Superposition& all, const ContactGeometry& geometry,
                                  std::vector<Contact>& contacts, const Eigen::VectorXd& P,
                                  const Eigen::VectorXd& d, ErrorEstimate& estimate) {
  const Eigen::Index n = P.size();
  const double residual = std::max(contact_residual(P, -d), 1e-300);
  ++estimate.passes;
  if (geometry.deformed()) {
    if (auto exact =
            turning_answer(scene, fibres, all, geometry, contacts, P, d, kProblemShare * residual))
      return *exact;
  } else {
    std::vector<unsigned char> pushes(contacts.size());
    std::vector<Contact> active;
    std::vector<Eigen::Index> where;
    for (Eigen::Index k = 0; k < n; ++k) {
      pushes[k] = P[k] > 0.0 || d[k] > 0.0;
      if (pushes[k]) active.push_back(contacts[static_cast<std::size_t>(k)]), where.push_back(k);
    }
    Eigen::VectorXd exact = P;
    if (!where.empty()) {
      Eigen::VectorXd r(static_cast<Eigen::Index>(where.size()));
      for (std::size_t i = 0; i < where.size(); ++i) r[static_cast<Eigen::Index>(i)] = d[where[i]];
      const Eigen::VectorXd x = solve_on(scene, fibres, std::move(active), r);
      for (std::size_t i = 0; i < where.size(); ++i)
        exact[where[i]] += x[static_cast<Eigen::Index>(i)];
    }
    const Eigen::VectorXd gap = contact_overlaps(all, geometry, contacts, exact);
    if (switching_settled(exact, gap, pushes, kProblemShare * residual)) return exact.cwiseMax(0.0);
  }
  Eigen::VectorXd exact = P;
  ++estimate.passes;
  estimate.settled =
      solve_frictionless_problem(scene, fibres, all, geometry, contacts, kNearTouching * residual,
                                 kProblemShare * residual, kProjectedWork, d, exact)
          .settled &&
      estimate.settled;
  return exact;
}

}  // namespace

ErrorEstimate estimate_iteration_error(const Scene& scene, const std::vector<Fibre>& fibres,
                                       const ContactDetector& detector,
                                       const std::vector<Contact>& contacts,
                                       std::vector<Contact>* answer_out, bool answer_only) {
  const ContactGeometry& geometry = detector.geometry();
  const auto start = std::chrono::steady_clock::now();
  ErrorEstimate estimate;
  const Eigen::Index n = static_cast<Eigen::Index>(contacts.size());
  if (n == 0) return estimate;
  Superposition all(fibres, scene);
  all.attach(contacts);
  Eigen::VectorXd P(n);
  for (Eigen::Index k = 0; k < n; ++k) P[k] = contacts[static_cast<std::size_t>(k)].force;
  double energy = 0.0, exact_energy = 0.0;
  const Eigen::VectorXd d = contact_overlaps(all, geometry, contacts, P, &energy);
  std::vector<Contact> answer = contacts;
  const double mu =
      scene.contact.friction_model == FrictionModel::coulomb ? scene.contact.friction : 0.0;
  // With Coulomb friction the frictions are unknowns too (coulomb_answer); without, under the
  // seed's friction rule, or where the frictional Newton steps do not settle (from a rough state
  // the contacts that slip can wedge the fibres, and its linear systems are then near singular),
  // they are held and the normal forces alone solve the residual equation.
  auto solve = [&](const Superposition& beams, const Eigen::VectorXd& from,
                   const Eigen::VectorXd& left) -> Eigen::VectorXd {
    if (!(mu > 0.0))
      return linearised_answer(scene, fibres, beams, geometry, answer, from, left, estimate);
    const std::vector<Contact> held = answer;
    for (Eigen::Index k = 0; k < n; ++k) answer[static_cast<std::size_t>(k)].force = from[k];
    const CoulombAnswer coulomb =
        coulomb_answer(fibres, beams, geometry, mu, kFrictionalShare, answer);
    estimate.passes += coulomb.steps;
    if (!coulomb.settled) {
      answer = held;
      estimate.settled = false;
      return linearised_answer(scene, fibres, beams, geometry, answer, from, left, estimate);
    }
    Eigen::VectorXd forces(n);
    for (Eigen::Index k = 0; k < n; ++k) forces[k] = answer[static_cast<std::size_t>(k)].force;
    return forces;
  };
  Eigen::VectorXd exact = solve(all, P, d);
  // The deformed contact: the answer's normals point between its own displaced centres, and its
  // crossings act at the closest points of its own deformed fibres, so the crossings step there
  // and the normals turn to those of the corrected state, and the problem linearised about them is
  // solved again from there, until neither moves.
  std::optional<Superposition> moved;
  const Superposition* beams = &all;
  std::vector<Eigen::Vector3d> last_change;
  double contraction = 0.0;
  bool still_turning = false;
  for (int pass = 0; geometry.deformed() && pass < kGeometricPasses; ++pass) {
    if (answer_only && !estimate.settled) break;
    const std::vector<Eigen::Vector3d> f = forces_on_a(answer, exact);
    const bool stepped = step_crossings(detector, *beams, f, answer);
    if (stepped && !moved) {
      moved.emplace(fibres, scene);
      moved->attach(answer);
      beams = &*moved;
    } else if (stepped) {
      moved->move_points(answer, fibres_with_crossings(answer));
    }
    std::vector<Eigen::Vector3d> u_a, u_b;
    beams->contact_displacements(answer, f, true, u_a, u_b);
    double turned = 0.0;
    for (std::size_t k = 0; k < answer.size(); ++k) {
      const Eigen::Vector3d before = answer[k].normal;
      geometry.follow(answer[k], u_a[k], u_b[k]);
      turned = std::max(turned, (answer[k].normal - before).norm());
    }
    still_turning = !(turned < kUnturned && !stepped);
    if (!still_turning) break;
    const Eigen::VectorXd d_turned = contact_overlaps(*beams, geometry, answer, exact);
    exact = solve(*beams, exact, d_turned);
    const std::vector<Eigen::Vector3d> after = forces_on_a(answer, exact);
    std::vector<Eigen::Vector3d> change(after.size());
    for (std::size_t k = 0; k < after.size(); ++k) change[k] = after[k] - f[k];
    contraction = last_change.empty() ? 0.0 : largest_norm(change) / largest_norm(last_change);
    last_change = std::move(change);
  }
  // The answer's forces, with the rest of the way of turns still under way when the passes ran
  // out (tail_of_turns).
  std::vector<Eigen::Vector3d> g = forces_on_a(answer, exact);
  const double tail = tail_of_turns(still_turning, contraction);
  for (std::size_t k = 0; tail > 0.0 && k < g.size(); ++k) g[k] += tail * last_change[k];
  {
    std::vector<Eigen::Vector3d> u_a, u_b;
    beams->contact_displacements(answer, g, true, u_a, u_b, &exact_energy);
  }
  const std::vector<Eigen::Vector3d> f = forces_on_a(contacts, P);
  estimate.force = pair_force_error(contacts, f, g);
  estimate.deflection = deflection_error(scene, all, f, *beams, g);
  estimate.energy =
      exact_energy != 0.0 ? std::fabs(energy - exact_energy) / std::fabs(exact_energy) : 0.0;
  if (answer_out) {
    for (Eigen::Index k = 0; k < n; ++k) answer[static_cast<std::size_t>(k)].force = exact[k];
    *answer_out = std::move(answer);
  }
  estimate.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return estimate;
}

}  // namespace fibrecheck
