#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace fibrecheck {

/// Solves W_SS·x = b for the rows and columns `index` of the symmetric positive semi-definite W
/// (the pushing or free contacts of an active-set method), by a sparse LDLᵀ with a fill-reducing
/// ordering: W_SS is as sparse as W, since contacts interact only through the fibres they share.
/// When W_SS is singular (contacts that constrain the same motion twice, several pairs meeting at
/// one point) it is regularised by 1e-10 of its largest diagonal entry: where b is consistent the
/// answer closes it to 1e-10, where it is not the answer grows along the null direction, which the
/// active set's step back to its bounds turns into dropping a variable. Returns false when even
/// that fails or the answer is not finite.
bool solve_on_subset(const Eigen::SparseMatrix<double>& W, const std::vector<Eigen::Index>& index,
                     const Eigen::VectorXd& b, Eigen::VectorXd& x);

}  // namespace fibrecheck
