#include "turning_normals.h"

#include <algorithm>

#include "compliance_operator.h"
#include "fibre_stiffness.h"
#include "gmres.h"
#include "superposition.h"

namespace fibrecheck {

namespace {

constexpr GmresLimits kLinearSolve{50, 200, 1e-8};

/// A slice whose normal follows its displaced centres and that pushes.
bool turns(const Contact& c, const ContactGeometry& geometry, double P) {
  return geometry.deformed() && c.kind == ContactKind::line && c.tangents == 1 && !c.normal_held &&
         P > 0.0;
}

}  // namespace

Eigen::VectorXd turning_normals_answer(const Scene& scene, const std::vector<Fibre>& fibres,
                                       const ContactGeometry& geometry,
                                       std::vector<Contact>& contacts,
                                       const std::vector<unsigned char>& member,
                                       const Eigen::VectorXd& P, const Eigen::VectorXd& d,
                                       const Eigen::VectorXd& e) {
  const Eigen::Index m = P.size();
  std::vector<Eigen::Index> turning;
  std::vector<double> rolling, across;  // D_k, and the preconditioner's −1/(D_k − W_tt,kk)
  Eigen::VectorXd let_go = Eigen::VectorXd::Zero(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const Contact& c = contacts[static_cast<std::size_t>(k)];
    if (!member[k]) let_go[k] = -P[k];
    if (!member[k] || !turns(c, geometry, P[k])) continue;
    const double distance = fibres[c.a].radius + fibres[c.b].radius - d[k];
    Contact along = c;
    along.normal = c.tangent;
    const double D = distance / P[k];
    turning.push_back(k);
    rolling.push_back(D);
    across.push_back(-1.0 / std::max(D - self_compliance(along, fibres), 0.1 * D));
  }
  const Eigen::Index n = m + static_cast<Eigen::Index>(turning.size());

  Superposition beams(fibres, scene);
  beams.attach(contacts);
  FibreStiffness stiffness(fibres);
  stiffness.attach(contacts);

  // The normal rows of the members and the turns' rows, from normal forces and turns `v`; the
  // rows of the others are v itself.
  std::vector<Eigen::Vector3d> force_on_a(static_cast<std::size_t>(m)), u_a, u_b;
  auto rows = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    for (Eigen::Index k = 0; k < m; ++k) {
      const Contact& c = contacts[static_cast<std::size_t>(k)];
      force_on_a[k] = (c.kind == ContactKind::wall ? v[k] : -v[k]) * c.normal;
    }
    for (std::size_t j = 0; j < turning.size(); ++j) {
      const Eigen::Index k = turning[j];
      force_on_a[k] -= v[m + static_cast<Eigen::Index>(j)] * contacts[k].tangent;
    }
    beams.contact_displacements(contacts, force_on_a, false, u_a, u_b);
    out.resize(n);
    for (Eigen::Index k = 0; k < m; ++k) {
      const Contact& c = contacts[static_cast<std::size_t>(k)];
      out[k] = c.normal.dot(c.kind == ContactKind::wall ? u_a[k] : c.relative(u_a[k], u_b[k]));
    }
    for (std::size_t j = 0; j < turning.size(); ++j) {
      const Eigen::Index k = turning[j], i = m + static_cast<Eigen::Index>(j);
      const Contact& c = contacts[static_cast<std::size_t>(k)];
      out[i] = c.tangent.dot(c.relative(u_a[k], u_b[k])) - rolling[j] * v[i];
    }
  };
  Eigen::VectorXd held;
  auto apply = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    held = v;
    for (Eigen::Index k = 0; k < m; ++k)
      if (!member[k]) held[k] = 0.0;
    rows(held, out);
    for (Eigen::Index k = 0; k < m; ++k)
      if (!member[k]) out[k] = v[k];
  };
  Eigen::VectorXd z;
  auto precondition = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    out.resize(n);
    stiffness.apply(v.head(m), member, z);
    out.head(m) = z;
    for (Eigen::Index k = 0; k < m; ++k)
      if (!member[k]) out[k] = v[k];
    for (std::size_t j = 0; j < turning.size(); ++j) {
      const Eigen::Index i = m + static_cast<Eigen::Index>(j);
      out[i] = across[j] * v[i];
    }
  };
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n), from_let_go;
  rows((Eigen::VectorXd(n) << let_go, Eigen::VectorXd::Zero(n - m)).finished(), from_let_go);
  b.head(m) = d;
  for (std::size_t j = 0; j < turning.size(); ++j)
    b[m + static_cast<Eigen::Index>(j)] = -e[turning[j]];
  b -= from_let_go;
  for (Eigen::Index k = 0; k < m; ++k)
    if (!member[k]) b[k] = 0.0;
  Eigen::VectorXd x = gmres(apply, precondition, b, kLinearSolve);

  for (std::size_t j = 0; j < turning.size(); ++j) {
    const Eigen::Index k = turning[j];
    Contact& c = contacts[static_cast<std::size_t>(k)];
    const double y = x[m + static_cast<Eigen::Index>(j)];
    geometry.turn(c, (c.normal + (y / P[k]) * c.tangent).normalized());
  }
  return x.head(m) + let_go;
}

}  // namespace fibrecheck
