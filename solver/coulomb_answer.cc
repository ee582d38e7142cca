#include "coulomb_answer.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "compliance_operator.h"
#include "fibre_stiffness.h"
#include "gmres.h"

namespace fibrecheck {

namespace {

constexpr int kNewtonSteps = 8;
constexpr int kHalvings = 10;
/// The Newton steps' linear systems: GMRES restarted every 30 products, at most 500 of them, to
/// 1e-10 of the right-hand side.
constexpr GmresLimits kLinearSolve{30, 500, 1e-10};
/// A friction this close to μP lies on the edge of its disk: it slips. The normals turning after
/// a state was put on the cone move the frictions off its edge by about 1e-9 of their size.
constexpr double kOnTheEdge = 1e-6;

/// What a state leaves: each contact's overlap along its normal and its slip since the step began.
struct Residual {
  Eigen::VectorXd overlap;
  std::vector<Eigen::Vector3d> slip;
};

Residual measure(const Superposition& beams, const ContactGeometry& geometry,
                 const std::vector<Contact>& contacts) {
  const std::size_t n = contacts.size();
  std::vector<Eigen::Vector3d> f(n), u_a, u_b;
  for (std::size_t k = 0; k < n; ++k) f[k] = contacts[k].force_on_a();
  beams.contact_displacements(contacts, f, true, u_a, u_b);
  Residual r{Eigen::VectorXd(static_cast<Eigen::Index>(n)), std::vector<Eigen::Vector3d>(n)};
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts[k];
    r.overlap[static_cast<Eigen::Index>(k)] = geometry.overlap_along_normal(c, u_a[k], u_b[k]);
    r.slip[k] = c.tangential(c.relative(u_a[k], u_b[k]) - c.origin);
  }
  return r;
}

/// Each contact's state: whether it pushes, whether it sticks, and where it does not, the
/// direction its friction slides along (zero where it carries none).
struct States {
  std::vector<unsigned char> pushes, sticks;
  std::vector<Eigen::Vector3d> direction;
};

States read_states(const std::vector<Contact>& contacts, const Residual& r, double mu) {
  const std::size_t n = contacts.size();
  States s{std::vector<unsigned char>(n, 0), std::vector<unsigned char>(n, 0),
           std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero())};
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts[k];
    s.pushes[k] = c.force > 0.0 || r.overlap[static_cast<Eigen::Index>(k)] > 0.0;
    if (!s.pushes[k] || c.tangents == 0 || !(mu > 0.0)) continue;
    const double size = c.friction.norm(), radius = mu * c.force;
    if (size < (1.0 - kOnTheEdge) * radius) {
      s.sticks[k] = 1;
    } else if (size > 0.0) {
      s.direction[k] = c.friction / size;
    } else if (r.slip[k].norm() > 0.0) {
      s.direction[k] = r.slip[k].normalized();
    } else {
      s.sticks[k] = 1;
    }
  }
  return s;
}

/// The tangential direction across a slipping crossing's friction direction e, n × e.
Eigen::Vector3d across(const Contact& c, const Eigen::Vector3d& e) {
  return c.normal.cross(e);
}

/// Whether contact k slips in a plane with a friction on its disk's edge, which turns as well as
/// grows.
bool slips_across(const Contact& c, const States& s, std::size_t k) {
  return c.tangents == 2 && c.force > 0.0 && s.direction[k].squaredNorm() > 0.0;
}

/// The largest overlap at a pushing contact, overlap at a free one, slip at a sticking one, and
/// slip off the friction's direction at a slipping one (mm).
double left_of(const Residual& r, const States& s) {
  double left = 0.0;
  for (std::size_t k = 0; k < s.pushes.size(); ++k) {
    const double d = r.overlap[static_cast<Eigen::Index>(k)];
    left = std::max(left, s.pushes[k] ? std::fabs(d) : std::max(d, 0.0));
    if (s.sticks[k]) left = std::max(left, r.slip[k].norm());
    if (s.direction[k].squaredNorm() > 0.0) {
      const double along = r.slip[k].dot(s.direction[k]);
      left = std::max(left, (r.slip[k] - along * s.direction[k]).norm() + std::max(0.0, -along));
    }
  }
  return left;
}

/// The contacts with each friction component turned into a contact of its own, pushing along ∓t
/// (a friction F along t on A is a normal force F along −t between two fibres, +t at a wall), in
/// the order of the frictional operator's components: what the fibres' stiffness preconditions.
std::vector<Contact> turned_into_normals(const std::vector<Contact>& contacts) {
  std::vector<Contact> turned;
  turned.reserve(3 * contacts.size());
  for (const Contact& c : contacts) {
    turned.push_back(c);
    const double side = c.kind == ContactKind::wall ? 1.0 : -1.0;
    for (const Eigen::Vector3d& t : {c.tangent, c.second_tangent()}) {
      Contact along = c;
      if (c.tangents > 0) along.normal = side * t;
      turned.push_back(along);
    }
  }
  return turned;
}

/// One Newton step with the contacts' states held: the normal forces of the pushing contacts and
/// the frictions of the sticking ones solve the overlaps and slips left, the slipping frictions
/// follow their normal forces along their directions.
void newton_step(const std::vector<Fibre>& fibres, const Superposition& beams,
                 const std::vector<Contact>& turned, const Residual& r, const States& s, double mu,
                 std::vector<Contact>& contacts) {
  const std::size_t n = contacts.size();
  const Eigen::Index m = static_cast<Eigen::Index>(3 * n);
  std::vector<unsigned char> free(static_cast<std::size_t>(m), 0);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  for (std::size_t k = 0; k < n; ++k) {
    const Contact& c = contacts[k];
    free[3 * k] = s.pushes[k];
    if (s.pushes[k]) b[static_cast<Eigen::Index>(3 * k)] = r.overlap[static_cast<Eigen::Index>(k)];
    if (slips_across(c, s, k)) {
      free[3 * k + 1] = 1;
      b[static_cast<Eigen::Index>(3 * k + 1)] = r.slip[k].dot(across(c, s.direction[k]));
    }
    if (!s.sticks[k]) continue;
    free[3 * k + 1] = 1;
    b[static_cast<Eigen::Index>(3 * k + 1)] = r.slip[k].dot(c.tangent);
    if (c.tangents == 2) {
      free[3 * k + 2] = 1;
      b[static_cast<Eigen::Index>(3 * k + 2)] = r.slip[k].dot(c.second_tangent());
    }
  }
  auto restrict = [&free](Eigen::VectorXd& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (!free[static_cast<std::size_t>(i)]) v[i] = 0.0;
  };
  // The slipping frictions' components for normal forces P + scale·δP: μ(P + δP)·e − F at
  // scale 1, μ·δP·e at scale 0 with no P; a crossing's turns across e by its own unknown.
  auto slipping = [&](const Eigen::VectorXd& x, double P_share, double F_share) {
    Eigen::VectorXd out = x;
    for (std::size_t k = 0; k < n; ++k) {
      if (!(s.direction[k].squaredNorm() > 0.0)) continue;
      const Contact& c = contacts[k];
      const Eigen::Index i = static_cast<Eigen::Index>(3 * k);
      const double P = P_share * c.force + x[i];
      Eigen::Vector3d change = mu * P * s.direction[k] - F_share * c.friction;
      if (slips_across(c, s, k)) change += x[i + 1] * across(c, s.direction[k]);
      out[i + 1] = change.dot(c.tangent);
      out[i + 2] = c.tangents == 2 ? change.dot(c.second_tangent()) : 0.0;
    }
    return out;
  };
  // A slipping crossing's equation is its slip across its friction's direction; turning the
  // friction by y/(μP) turns that direction too, by the slip along it.
  auto slips_measured_across = [&](const Eigen::VectorXd& x, Eigen::VectorXd& w) {
    for (std::size_t k = 0; k < n; ++k) {
      if (!slips_across(contacts[k], s, k)) continue;
      const Contact& c = contacts[k];
      const Eigen::Index i = static_cast<Eigen::Index>(3 * k);
      const Eigen::Vector3d slip = w[i + 1] * c.tangent + w[i + 2] * c.second_tangent();
      w[i + 1] = slip.dot(across(c, s.direction[k])) +
                 r.slip[k].dot(s.direction[k]) / (mu * c.force) * x[i + 1];
      w[i + 2] = 0.0;
    }
  };
  const ComplianceOperator W(beams, contacts, false, true);
  FibreStiffness stiffness(fibres);
  stiffness.attach(turned);
  Eigen::VectorXd q;
  W.apply(slipping(Eigen::VectorXd::Zero(m), 1.0, 1.0), q);
  slips_measured_across(Eigen::VectorXd::Zero(m), q);
  restrict(q);
  b -= q;
  const Eigen::VectorXd x = gmres(
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        W.apply(slipping(v, 0.0, 0.0), out);
        slips_measured_across(v, out);
        restrict(out);
      },
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) { stiffness.apply(v, free, out); }, b,
      kLinearSolve);
  const Eigen::VectorXd change = slipping(x, 1.0, 1.0);
  for (std::size_t k = 0; k < n; ++k) {
    Contact& c = contacts[k];
    const Eigen::Index i = static_cast<Eigen::Index>(3 * k);
    if (!s.pushes[k]) continue;
    c.force = std::max(c.force + x[i], 0.0);
    if (c.tangents > 0)
      c.friction += change[i + 1] * c.tangent + change[i + 2] * c.second_tangent();
    c.friction = onto_coulomb_disk(c.tangential(c.friction), mu * c.force);
  }
}

/// The state a share `alpha` of the way from `from` to `to`: forces and frictions in proportion,
/// which keeps each friction within its disk, since both ends have theirs within.
std::vector<Contact> part_of_the_way(const std::vector<Contact>& from,
                                     const std::vector<Contact>& to, double alpha) {
  std::vector<Contact> between = from;
  for (std::size_t k = 0; k < between.size(); ++k) {
    between[k].force += alpha * (to[k].force - from[k].force);
    between[k].friction += alpha * (to[k].friction - from[k].friction);
  }
  return between;
}

}  // namespace

CoulombAnswer coulomb_answer(const std::vector<Fibre>& fibres, const Superposition& beams,
                             const ContactGeometry& geometry, double mu, double share,
                             std::vector<Contact>& contacts) {
  CoulombAnswer answer;
  const std::vector<Contact> turned = turned_into_normals(contacts);
  Residual r = measure(beams, geometry, contacts);
  States s = read_states(contacts, r, mu);
  double left = left_of(r, s);
  const double wanted = share * std::max(left, 1e-300);
  std::vector<Contact> best = contacts;
  double least = left;
  while (answer.steps < kNewtonSteps && left > wanted) {
    std::vector<Contact> newton = contacts;
    newton_step(fibres, beams, turned, r, s, mu, newton);
    ++answer.steps;
    Residual rn = measure(beams, geometry, newton);
    States sn = read_states(newton, rn, mu);
    double left_newton = left_of(rn, sn);
    // A step that changes no contact's state and leaves more than the state did went too far
    // along a direction the linearisation does not hold on: it is halved until it leaves less.
    for (int halving = 1; !(left_newton < left) && sn.pushes == s.pushes && sn.sticks == s.sticks &&
                          halving <= kHalvings;
         ++halving) {
      std::vector<Contact> trial = part_of_the_way(contacts, newton, std::ldexp(1.0, -halving));
      Residual rt = measure(beams, geometry, trial);
      States st = read_states(trial, rt, mu);
      const double left_trial = left_of(rt, st);
      if (!(left_trial < left)) continue;
      newton = std::move(trial);
      rn = std::move(rt);
      sn = std::move(st);
      left_newton = left_trial;
    }
    contacts = std::move(newton);
    r = std::move(rn);
    s = std::move(sn);
    left = left_newton;
    if (left < least) best = contacts, least = left;
  }
  contacts = std::move(best);
  left = least;
  answer.settled = left <= wanted;
  return answer;
}

}  // namespace fibrecheck
