#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact_problem.h"

namespace fibrecheck {

/// One answer of a Siconos solver to an exported contact problem.
struct PeerAnswer {
  std::string solver;          ///< our name for it: lemke, pgs, newton, nsgs
  std::string siconos_solver;  ///< Siconos' own name of the solver
  int dimension = 1;  ///< 1: the linear complementarity problem; 2, 3: Coulomb (fc2d, fc3d)
  int info = -1;      ///< Siconos' return code: 0 when it reached its tolerance
  int iterations = 0;
  double error = 0.0;        ///< Siconos' own error measure at the end (relative)
  double time_s = 0.0;       ///< the solver alone, without building the problem
  Eigen::VectorXd reaction;  ///< in the problem's layout (excluded contacts 0)
};

/// The Siconos solvers that take `problem`: μ = 0 as a linear complementarity problem (Lemke's
/// pivoting, projected Gauss–Seidel, a semismooth Newton method on its min map); friction with one
/// tangent per contact as a 2-D Coulomb problem (nonsmooth Gauss–Seidel, Lemke on its LCP form)
/// and, like friction with two tangents, as a 3-D one (nonsmooth Gauss–Seidel, the Alart–Curnier
/// nonsmooth Newton method). A contact with fewer tangents than the problem's dimension gets a
/// direction that nothing couples to (its friction there is zero).
std::vector<std::string> applicable_solvers(const ContactProblem& problem);

/// Solves `problem` with the named solver to Siconos' relative error `tolerance`, from r = 0.
/// Excluded contacts are left out. Throws std::invalid_argument for a solver that does not apply.
PeerAnswer solve_with_siconos(const ContactProblem& problem, const std::string& solver,
                              double tolerance, int max_iterations);

}  // namespace fibrecheck
