#include "frictionless_problem.h"

#include <algorithm>
#include <utility>

#include "compliance_on_subset.h"
#include "projected_cg.h"

namespace fibrecheck {

std::vector<Eigen::Vector3d> forces_on_a(const std::vector<Contact>& contacts,
                                         const Eigen::VectorXd& P) {
  std::vector<Eigen::Vector3d> f(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const double p = P[static_cast<Eigen::Index>(k)];
    f[k] = (c.kind == ContactKind::wall ? p : -p) * c.normal +
           (p > 0.0 ? c.friction : Eigen::Vector3d::Zero());
  }
  return f;
}

Eigen::VectorXd contact_overlaps(const Superposition& beams, const ContactGeometry& geometry,
                                 const std::vector<Contact>& contacts, const Eigen::VectorXd& P,
                                 double* energy) {
  std::vector<Eigen::Vector3d> u_a, u_b;
  beams.contact_displacements(contacts, forces_on_a(contacts, P), true, u_a, u_b, energy);
  Eigen::VectorXd d(static_cast<Eigen::Index>(contacts.size()));
  for (std::size_t k = 0; k < contacts.size(); ++k)
    d[static_cast<Eigen::Index>(k)] = geometry.overlap_along_normal(contacts[k], u_a[k], u_b[k]);
  return d;
}

namespace {

/// Where the members' own residual, measured afresh, is above the tolerance that the solve's
/// recurrence met, they are solved again from there, at most this many times.
constexpr int kMaxRepeats = 2;

/// The problem restricted to the members (the other candidates held at zero force), from `P` with
/// overlaps `d`, both of every candidate: the members' forces are replaced by their answer, in at
/// most `max_work` / (members) products with W. True when the solve reached the tolerance.
bool solve_on_members(const Scene& scene, const std::vector<Fibre>& fibres,
                      const std::vector<Contact>& contacts,
                      const std::vector<unsigned char>& member, const Eigen::VectorXd& d,
                      double tolerance, double max_work, Eigen::VectorXd& P) {
  std::vector<Contact> members;
  std::vector<Eigen::Index> where;
  for (Eigen::Index k = 0; k < P.size(); ++k)
    if (member[k]) members.push_back(contacts[static_cast<std::size_t>(k)]), where.push_back(k);
  const Eigen::Index m = static_cast<Eigen::Index>(where.size());
  if (m == 0) return true;
  Eigen::VectorXd x(m), g(m);
  for (Eigen::Index i = 0; i < m; ++i) x[i] = P[where[i]], g[i] = -d[where[i]];
  const ComplianceOnSubset subset(scene, fibres, std::move(members));
  const ComplianceOperator& W = subset.compliance();
  const FibreStiffness& stiffness = subset.stiffness();
  ContactQuadraticProgramme problem;
  problem.compliance = [&W](const Eigen::VectorXd& y, Eigen::VectorXd& z) { W.apply(y, z); };
  problem.preconditioner = [&stiffness](const Eigen::VectorXd& r,
                                        const std::vector<unsigned char>& free,
                                        Eigen::VectorXd& z) { stiffness.apply(r, free, z); };
  problem.largest_eigenvalue = W.largest_eigenvalue();
  const long max_products = std::max(1L, static_cast<long>(max_work / static_cast<double>(m)));
  const ProjectedCgOutcome outcome = solve_by_projected_cg(problem, x, g, tolerance, max_products);
  for (Eigen::Index i = 0; i < m; ++i) P[where[i]] = x[i];
  return outcome.finite && outcome.residual < tolerance;
}

}  // namespace

FrictionlessProblemOutcome solve_frictionless_problem(
    const Scene& scene, const std::vector<Fibre>& fibres, const Superposition& beams,
    const ContactGeometry& geometry, const std::vector<Contact>& contacts, double reach,
    double tolerance, double max_work, const Eigen::VectorXd& d, Eigen::VectorXd& P) {
  FrictionlessProblemOutcome outcome;
  std::vector<unsigned char> member(contacts.size());
  for (Eigen::Index k = 0; k < P.size(); ++k) member[k] = P[k] > 0.0 || d[k] > -reach;
  Eigen::VectorXd left = d;
  for (int repeats = 0; repeats <= kMaxRepeats;) {
    outcome.members = std::count(member.begin(), member.end(), 1);
    if (!solve_on_members(scene, fibres, contacts, member, left, tolerance, max_work, P))
      return outcome;
    left = contact_overlaps(beams, geometry, contacts, P);
    if (contact_residual(P, -left) < tolerance) {
      outcome.settled = true;
      return outcome;
    }
    bool overlapping = false;
    for (Eigen::Index k = 0; k < P.size(); ++k) overlapping |= !member[k] && left[k] > tolerance;
    if (overlapping) {
      for (Eigen::Index k = 0; k < P.size(); ++k) member[k] |= left[k] > -reach;
      ++outcome.growths;
    } else {
      ++repeats;
    }
  }
  return outcome;
}

}  // namespace fibrecheck
