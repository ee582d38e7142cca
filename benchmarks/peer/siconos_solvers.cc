#include "siconos_solvers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

// Siconos numerics: C headers.
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "LinearComplementarityProblem.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "lcp_cst.h"

namespace fibrecheck {

namespace {

struct Choice {
  const char* name;
  int dimension;  ///< 1 LCP, 2 fc2d, 3 fc3d
  int id;         ///< Siconos' solver id
  const char* siconos_name;
};

constexpr Choice kChoices[] = {
    {"lemke", 1, SICONOS_LCP_LEMKE, "SICONOS_LCP_LEMKE"},
    {"pgs", 1, SICONOS_LCP_PGS, "SICONOS_LCP_PGS"},
    {"newton", 1, SICONOS_LCP_NEWTON_MIN_FBLSA, "SICONOS_LCP_NEWTON_MIN_FBLSA"},
    {"nsgs", 2, SICONOS_FRICTION_2D_NSGS, "SICONOS_FRICTION_2D_NSGS"},
    {"lemke", 2, SICONOS_FRICTION_2D_LEMKE, "SICONOS_FRICTION_2D_LEMKE"},
    {"nsgs", 3, SICONOS_FRICTION_3D_NSGS, "SICONOS_FRICTION_3D_NSGS"},
    {"newton", 3, SICONOS_FRICTION_3D_NSN_AC, "SICONOS_FRICTION_3D_NSN_AC"},
};

int most_tangents(const ContactProblem& p) {
  int most = 0;
  for (const ProblemContact& c : p.contacts)
    if (!c.excluded) most = std::max(most, c.tangents);
  return most;
}

/// The dimension a solver works in for this problem: LCP solvers for μ = 0, the others in 2-D
/// when one tangent is enough, 3-D always for the Alart–Curnier Newton method (Siconos has it in
/// 3-D only).
int dimension_for(const ContactProblem& p, const Choice& c) {
  const int tangents = most_tangents(p);
  if (tangents == 0 || !(p.mu > 0.0)) return c.dimension == 1 ? 1 : 0;
  if (c.dimension == 1) return 0;
  if (c.dimension == 2) return tangents == 1 ? 2 : 0;
  return 3;
}

const Choice* find_choice(const ContactProblem& p, const std::string& solver) {
  for (const Choice& c : kChoices)
    if (solver == c.name && dimension_for(p, c) == c.dimension) return &c;
  // The 3-D solvers take a problem with one tangent too; nsgs prefers the 2-D one above.
  return nullptr;
}

}  // namespace

std::vector<std::string> applicable_solvers(const ContactProblem& problem) {
  std::vector<std::string> names;
  for (const Choice& c : kChoices)
    if (dimension_for(problem, c) == c.dimension &&
        std::find(names.begin(), names.end(), c.name) == names.end())
      names.push_back(c.name);
  return names;
}

PeerAnswer solve_with_siconos(const ContactProblem& p, const std::string& solver,
                              const PeerSettings& settings) {
  const Choice* choice = find_choice(p, solver);
  if (!choice) {
    std::string known;
    for (const std::string& name : applicable_solvers(p))
      known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument("the solver \"" + solver +
                                "\" does not take this problem (these do: " + known + ")");
  }
  const int d = choice->dimension;
  // The contacts that take part, and where each of their unknowns goes in Siconos' layout
  // (contact i's normal at d·i, its tangents after it; −1 for a direction nothing couples to).
  std::vector<std::size_t> kept;
  for (std::size_t j = 0; j < p.contacts.size(); ++j)
    if (!p.contacts[j].excluded) kept.push_back(j);
  const int m = static_cast<int>(kept.size());
  const int size = d * m;
  std::vector<Eigen::Index> source(static_cast<std::size_t>(size), -1);
  std::vector<int> target(static_cast<std::size_t>(p.offset.back()), -1);
  for (int i = 0; i < m; ++i) {
    const std::size_t j = kept[static_cast<std::size_t>(i)];
    const int components = std::min<int>(d, static_cast<int>(p.offset[j + 1] - p.offset[j]));
    for (int a = 0; a < components; ++a) {
      source[static_cast<std::size_t>(d * i + a)] = p.offset[j] + a;
      target[static_cast<std::size_t>(p.offset[j] + a)] = d * i + a;
    }
  }
  // The scaling: every unknown of contact i times scale[i] = 1/√W_nn, and q over q_scale, so that
  // Siconos sees M = D·W·D with a unit diagonal on the normals and |q| ≤ 1; r = q_scale·D·r̃.
  std::vector<double> scale(static_cast<std::size_t>(m), 1.0);
  double q_scale = 1.0;
  if (settings.scaled) {
    for (int i = 0; i < m; ++i) {
      const double W_nn = p.W.coeff(p.offset[kept[static_cast<std::size_t>(i)]],
                                    p.offset[kept[static_cast<std::size_t>(i)]]);
      if (W_nn > 0.0) scale[static_cast<std::size_t>(i)] = 1.0 / std::sqrt(W_nn);
    }
    double largest = 0.0;
    for (int i = 0; i < size; ++i) {
      const Eigen::Index s = source[static_cast<std::size_t>(i)];
      if (s >= 0) largest = std::max(largest, scale[static_cast<std::size_t>(i / d)] * std::fabs(p.q[s]));
    }
    if (largest > 0.0) q_scale = largest;
  }
  auto factor = [&](int i) { return scale[static_cast<std::size_t>(i / d)]; };
  // Dense, column-major: M = D·W·D, q = −D·q/q_scale (Siconos' velocity u = M·r + q is the gap and
  // the slip opened, −w in the problem's terms).
  NumericsMatrix* M = NM_create(NM_DENSE, size, size);
  std::fill(M->matrix0, M->matrix0 + static_cast<std::size_t>(size) * size, 0.0);
  for (int k = 0; k < p.W.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.W, k); it; ++it) {
      const int row = target[static_cast<std::size_t>(it.row())];
      const int col = target[static_cast<std::size_t>(it.col())];
      if (row >= 0 && col >= 0)
        M->matrix0[static_cast<std::size_t>(col) * size + row] =
            factor(row) * it.value() * factor(col);
    }
  std::vector<double> q(static_cast<std::size_t>(size), 0.0), mu(static_cast<std::size_t>(m), p.mu);
  for (int i = 0; i < size; ++i) {
    const Eigen::Index s = source[static_cast<std::size_t>(i)];
    if (s >= 0) {
      q[static_cast<std::size_t>(i)] = -factor(i) * p.q[s] / q_scale;
    } else {
      // A direction nothing couples to: unit compliance of the contact's normal size, no load.
      const int normal = (i / d) * d;
      M->matrix0[static_cast<std::size_t>(i) * size + i] =
          std::max(M->matrix0[static_cast<std::size_t>(normal) * size + normal], 1e-300);
    }
  }
  std::vector<double> r(static_cast<std::size_t>(size), 0.0),
      u(static_cast<std::size_t>(size), 0.0);
  SolverOptions* options = solver_options_create(choice->id);
  options->dparam[SICONOS_DPARAM_TOL] = settings.tolerance;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = settings.max_iterations;
  PeerAnswer answer;
  answer.solver = solver;
  answer.siconos_solver = choice->siconos_name;
  answer.dimension = d;
  answer.scaled = settings.scaled;
  const auto start = std::chrono::steady_clock::now();
  if (d == 1) {
    LinearComplementarityProblem lcp;
    lcp.size = size;
    lcp.M = M;
    lcp.q = q.data();
    answer.info = size > 0 ? linearComplementarity_driver(&lcp, r.data(), u.data(), options) : 0;
  } else {
    FrictionContactProblem fc;
    fc.dimension = d;
    fc.numberOfContacts = m;
    fc.M = M;
    fc.q = q.data();
    fc.mu = mu.data();
    answer.info = m > 0 ? (d == 2 ? fc2d_driver(&fc, r.data(), u.data(), options)
                                  : fc3d_driver(&fc, r.data(), u.data(), options))
                        : 0;
  }
  answer.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  answer.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  answer.error = options->dparam[SICONOS_DPARAM_RESIDU];
  solver_options_delete(options);
  NM_free(M);
  answer.reaction = Eigen::VectorXd::Zero(p.offset.back());
  for (int i = 0; i < size; ++i) {
    const Eigen::Index s = source[static_cast<std::size_t>(i)];
    if (s >= 0) answer.reaction[s] = q_scale * factor(i) * r[static_cast<std::size_t>(i)];
  }
  // Siconos' info says what it believes; the residual of the answer says what it is.
  answer.residual = problem_residual(p, answer.reaction);
  answer.relative_residual =
      std::max(answer.residual.overlap_mm, answer.residual.slip_mm) / residual_scale(p);
  answer.converged = solves(p, answer.residual, settings.residual_tolerance);
  return answer;
}

}  // namespace fibrecheck
