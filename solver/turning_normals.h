#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "contact_geometry.h"
#include "fibre.h"
#include "scene.h"

namespace fibrecheck {

/// The changes x of the normal forces P of the contacts `contacts` (a list of their own) that
/// remove the overlaps `d` and the misalignments `e` (t·(B′c − A′c), the displaced centres' offset
/// across a slice's normal) of those with `member[k]` set and let the others' forces go (x_k =
/// −P_k), on the deformed fibres, with each pushing slice's normal turning as its fibres roll on
/// each other: a Newton step of the deformed contact on the pushing set `member`. The members'
/// slices' normals in `contacts` are turned to the step's own (their tangents with them).
///
/// Why: on the deformed fibres a slice pushes along the line between the displaced centres
/// (§4.3.3), so a relative displacement δ across that line, in the cross-section plane, turns its
/// force P by δ/ρ, ρ the distance of the centres: a force P·δ/ρ along the fibres' relative
/// displacement, which rolls them further. Solving the problem linearised about fixed normals and
/// then turning them is a fixed point that contracts by that force's share of what holds the
/// fibres across: on compacted tows, where heavily loaded fibres lean on each other, barely. Here
/// the turn is an unknown of its own: a force y_k along the slice's tangent t_k, with y_k =
/// (P_k/ρ_k)·(e_k + t_k·(u_B − u_A)). With W the compliance of the beams at the contacts, normal
/// forces and turns solve
///   [W_nn   W_nt      ] [x]   [d]
///   [W_tn   W_tt − D ] [y] = [−e],   D = diag(ρ_k/P_k),
/// on the members (the let-go forces on the right), symmetric and indefinite, by GMRES
/// preconditioned with the fibres' stiffness at their stations for the normal forces and
/// −1/(D_k − W_tt,kk) (at most 10/D_k in size) for the turns. Each slice's normal then becomes n +
/// (y_k/P_k)·t_k, normalised. Crossings (whose closest points slide instead) and walls keep their
/// normals.
Eigen::VectorXd turning_normals_answer(const Scene& scene, const std::vector<Fibre>& fibres,
                                       const ContactGeometry& geometry,
                                       std::vector<Contact>& contacts,
                                       const std::vector<unsigned char>& member,
                                       const Eigen::VectorXd& P, const Eigen::VectorXd& d,
                                       const Eigen::VectorXd& e);

}  // namespace fibrecheck
