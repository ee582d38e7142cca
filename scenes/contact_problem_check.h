#pragma once

#include <Eigen/Core>

#include "contact_problem.h"

namespace fibrecheck {

/// How far reactions r are from solving a contact problem: the largest violation of its
/// complementarity and Coulomb conditions over the contacts, in mm (the natural map of Alart and
/// Curnier, ‖r_j − proj_j(r_j + ρ_j w_j)‖/ρ_j with ρ_j = 1/W_jj for the normal and the slip, the
/// projection taking P to max(0, ·) and F onto the disk of radius μ times the projected P), and
/// in N the largest reaction left on an excluded contact. Zero exactly at a solution; infinite for
/// reactions that are not all finite.
struct ProblemResidual {
  double overlap_mm = 0.0;  ///< the normal part: an overlap left, or a gap a force pulls across
  double slip_mm = 0.0;     ///< the tangential part: a sticking contact slipping, a slip off μP
  double excluded_N = 0.0;  ///< reactions on excluded contacts
};
ProblemResidual problem_residual(const ContactProblem& problem, const Eigen::VectorXd& r);

/// The scale a residual is judged against: the largest free overlap or slip |q| (mm), or 1 when q
/// is zero.
double residual_scale(const ContactProblem& problem);

/// Whether reactions r solve the problem, judged by their own residual and never by the word of
/// whatever produced them: the overlap and slip parts within `relative_tolerance` of
/// residual_scale, and no reaction on an excluded contact.
bool solves(const ContactProblem& problem, const ProblemResidual& residual,
            double relative_tolerance);

/// Two answers to the same problem, compared where the answer is unique: the normal forces of
/// every contact, the friction forces only where something can slip (a tangential compliance
/// above 1e-12 of the normal one: along a direction nothing can move in any friction within the
/// disk is a solution), and the overlaps and slips left w = q − W·r. Differences are absolute;
/// the scales are the largest normal force and the largest |q| for w.
struct ProblemAgreement {
  double normal_N = 0.0, friction_N = 0.0, w_mm = 0.0;
  double normal_scale_N = 0.0, w_scale_mm = 0.0;
  int contacts = 0;              ///< contacts compared (not excluded)
  int frictions_compared = 0;    ///< of them, where friction is unique
  int frictions_not_unique = 0;  ///< tangents that nothing can move along
  /// The largest of normal_N and friction_N over normal_scale_N, and w_mm over w_scale_mm.
  double relative() const;
};
ProblemAgreement compare_answers(const ContactProblem& problem, const Eigen::VectorXd& a,
                                 const Eigen::VectorXd& b);

}  // namespace fibrecheck
