#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact_problem.h"
#include "contact_problem_check.h"

namespace fibrecheck {

/// How a Siconos solver is asked and how its answer is judged.
struct PeerSettings {
  double tolerance = 1e-12;   ///< Siconos' own relative error, passed to it
  int max_iterations = 100000;
  /// Hand Siconos the problem scaled to order one: per contact j the factor d_j = 1/√W_nn(j) on
  /// its unknowns (normal and tangents alike, so that Coulomb's cone is unchanged), and q over the
  /// largest |d·q|; the answer is scaled back.
  bool scaled = true;
  /// An answer solves the problem when its residual (problem_residual, mm) is within this of the
  /// largest |q|: the judgement is ours, whatever Siconos returned.
  double residual_tolerance = 1e-9;
};

/// One answer of a Siconos solver to an exported contact problem.
struct PeerAnswer {
  std::string solver;          ///< our name for it: lemke, pgs, newton, nsgs
  std::string siconos_solver;  ///< Siconos' own name of the solver
  int dimension = 1;  ///< 1: the linear complementarity problem; 2, 3: Coulomb (fc2d, fc3d)
  bool scaled = true;  ///< whether Siconos was handed the scaled problem
  int info = -1;      ///< Siconos' return code: 0 when it says it reached its tolerance
  int iterations = 0;
  double error = 0.0;        ///< Siconos' own error measure at the end (relative)
  double time_s = 0.0;       ///< the solver alone, without building the problem
  Eigen::VectorXd reaction;  ///< in the problem's layout (excluded contacts 0)
  ProblemResidual residual;  ///< of `reaction`, computed by fibrecheck
  double relative_residual = 0.0;  ///< the larger of its overlap and slip parts over the largest |q|
  /// `reaction` solves the problem by its own residual (PeerSettings::residual_tolerance).
  bool converged = false;
};

/// The Siconos solvers that take `problem`: μ = 0 as a linear complementarity problem (Lemke's
/// pivoting, projected Gauss–Seidel, a semismooth Newton method on its min map); friction with one
/// tangent per contact as a 2-D Coulomb problem (nonsmooth Gauss–Seidel, Lemke on its LCP form)
/// and, like friction with two tangents, as a 3-D one (nonsmooth Gauss–Seidel, the Alart–Curnier
/// nonsmooth Newton method). A contact with fewer tangents than the problem's dimension gets a
/// direction that nothing couples to (its friction there is zero).
std::vector<std::string> applicable_solvers(const ContactProblem& problem);

/// Solves `problem` with the named solver, from r = 0, and judges the answer by its residual.
/// Excluded contacts are left out. Throws std::invalid_argument for a solver that does not apply.
PeerAnswer solve_with_siconos(const ContactProblem& problem, const std::string& solver,
                              const PeerSettings& settings);

}  // namespace fibrecheck
