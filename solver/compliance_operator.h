#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "fibre.h"
#include "superposition.h"

namespace fibrecheck {

/// The contact compliance (Delassus) operator W: (W·x)_k is the overlap that forces x_k along the
/// contact normals remove at contact k. The force update P ← max(0, P + c·d) of §4.3.2 is a
/// projected Richardson iteration on this operator, stable only for c < 2/λmax(W). W is applied
/// matrix-free through the beam superposition, O(k + n) per fibre.
class ComplianceOperator {
 public:
  /// With `weighted`, the operator is D½·W·D½, D the contacts' weights (1/n per slice): the one
  /// the seed's rule iterates on, whose step is c·D (Eq. 4.28), so that it is stable for
  /// c < 2/λmax(D½·W·D½).
  /// With `frictional`, the operator acts on three components per contact, the normal force P and
  /// the friction force along the contact's tangents (zero where it has fewer than two), and
  /// returns the overlap and the slip they remove: the Delassus operator of the frictional problem.
  ComplianceOperator(const Superposition& superposition, const std::vector<Contact>& contacts,
                     bool weighted = false, bool frictional = false)
      : superposition_(superposition),
        contacts_(contacts),
        weighted_(weighted),
        frictional_(frictional) {}

  int components() const { return frictional_ ? 3 : 1; }

  /// y = W·x (or D½·W·D½·x).
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  /// λmax(W) by power iteration from the all-ones vector (W is symmetric positive semi-definite
  /// with non-negative diagonal), stopping when the Rayleigh quotient changes by less than
  /// `tolerance` relative or after `max_iterations`. Returns 0 when there are no contacts.
  double largest_eigenvalue(int max_iterations = 60, double tolerance = 1e-4) const;

 private:
  const Superposition& superposition_;
  const std::vector<Contact>& contacts_;
  bool weighted_;
  bool frictional_;
};

/// W_kk of the beam formulas: how much overlap a unit force removes at this contact alone (mm/N),
/// the compliance a²b²/(3EIL) at the contact of each fibre (DESIGN §7) times the part of the normal
/// across it.
double self_compliance(const Contact& contact, const std::vector<Fibre>& fibres);

}  // namespace fibrecheck
