#pragma once

#include <Eigen/Core>
#include <vector>

#include "contact.h"
#include "fibre.h"

namespace fibrecheck {

/// The inverse of each fibre's compliance at the stations its contacts load, applied in O(m) per
/// fibre, and with it an approximate inverse of the contact compliance W (the preconditioner of
/// the conjugate-gradient rule).
///
/// A simply supported beam loaded only at stations x_1 < … < x_m has a bending moment linear
/// between them, so its deflections there satisfy two tridiagonal relations (the mixed w–M form):
/// p = −A·M and A·w = −B·M/EI, with A the second difference on the stations (w and M zero at the
/// supports) and B the tridiagonal "hat-function mass" [h/6, (h₋ + h)/3, h/6]. Hence the station
/// stiffness K = G⁻¹ = EI·A·B⁻¹·A: one tridiagonal solve between two products, exact for the
/// Green's function of §4.3.1 (48EI/L³ for one station at mid-span).
///
/// W = C·G·Cᵀ, C the map from the fibres' station deflections to the contacts' overlaps. The
/// preconditioner is block-diagonal, one block per line (the slices of one pair of fibres, or of
/// a fibre along a wall; a crossing is a line of one point): Q_line = D·C·K·Cᵀ·D with K each
/// fibre's stiffness at that line's stations alone (the "lumped" preconditioner of dual domain
/// decomposition), D = √(EI_A·EI_B)/(EI_A + EI_B) for two fibres, 1 against a wall. It is the
/// exact inverse of the line's own block of W for two parallel fibres on common supports, whatever
/// the slice count, which is what keeps the iteration count from growing with the slicing. Lines
/// are kept apart because the slices of different lines stand at different stations of a fibre:
/// one K over all of them would stiffen the short pieces between neighbouring stations.
/// K is built on the stations of the contacts it is given only: on a subset of the stations it is
/// still the exact inverse of the Green's function there.
class FibreStiffness {
 public:
  explicit FibreStiffness(const std::vector<Fibre>& fibres);

  /// Registers the contacts' stations on their fibres (call when the contact list changes).
  void attach(const std::vector<Contact>& contacts);

  /// z = Q·r on the contacts with `free[k]` set; the others are neither read nor loaded, and get
  /// z_k = 0.
  void apply(const Eigen::VectorXd& r, const std::vector<unsigned char>& free,
             Eigen::VectorXd& z) const;

  /// K·v for one simply supported beam: `x` the sorted interior stations (mm), `v` the
  /// deflections there (both planes); returns the station loads (N).
  static void beam_stiffness(double L, double EI, const std::vector<double>& x,
                             std::vector<Eigen::Array2d>& v);

 private:
  /// A contact side on a fibre: its distance from the start and the direction, in the fibre's two
  /// bending planes, in which the contact's force loads it (times D_k).
  struct Slot {
    double a;
    int contact;
    Eigen::Array2d direction;
  };
  /// One line: its two sides (side 1 empty against a wall), each sorted by a.
  struct Line {
    int fibre[2];
    std::vector<Slot> side[2];
  };
  /// K·Cᵀ·D·r on one side of a line, written to `out` at its contacts.
  void apply_side(int fibre, const std::vector<Slot>& side, const Eigen::VectorXd& r,
                  const std::vector<unsigned char>& free, double* out) const;

  std::vector<Fibre> fibres_;
  std::vector<Line> lines_;
  mutable std::vector<double> side_a_, side_b_;
};

}  // namespace fibrecheck
