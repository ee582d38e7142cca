#pragma once

#include <cmath>
#include <deque>
#include <vector>

#include "contact.h"

namespace fibrecheck {

/// How far a state is from "every contact just touching" (seed §4.3.6), reported separately:
///  - overlap: the largest overlap d anywhere (must be < t_d);
///  - gap_force: the largest gap −d at a contact that carries force (no gap may carry a force).
struct Residuals {
  double overlap = 0.0;      ///< mm, max(0, max d)
  double gap_force = 0.0;    ///< mm, max over P > 0 of max(0, −d)
  double max_overlap = 0.0;  ///< mm, max d over all candidates (may be negative)
  double total() const { return overlap > gap_force ? overlap : gap_force; }
};

Residuals measure_residuals(const std::vector<Contact>& contacts);

/// The energy criterion of §4.3.6: converged when the last n_i energies all lie within an absolute
/// tolerance t_U of the current one.
class EnergyWindow {
 public:
  EnergyWindow(int window, double tolerance) : window_(window), tolerance_(tolerance) {}
  /// Adds the current energy; true when the window is full and settled.
  bool push(double energy);

 private:
  int window_;
  double tolerance_;
  std::deque<double> energies_;
};

/// Watches the residual for instability: growth without bound or no progress at all for a long
/// stretch (the update oscillating, as P' = P + c·d does for c ≥ 2/λmax(W)).
///
/// Growth is a residual 1e4 times the first one since the last reset (or t, or 1e-8 of the
/// scene's extent: a step that starts just touching under a t_d of 1e-11 mm may well push its
/// overlaps to 1e-6 mm on the way), or, whatever the
/// resets, one beyond `extent` (a gap or overlap longer than the scene's fibres, and a hundred
/// times the very first residual): fibres flying apart are found in new contact with every fibre
/// they pass, and waiting for 1e4 times a large overlap would let the candidate lists, and each
/// iteration's cost and memory, grow without bound first.
class DivergenceMonitor {
 public:
  explicit DivergenceMonitor(double tolerance, double extent = INFINITY)
      : tolerance_(tolerance), extent_(extent) {}
  enum class Verdict { fine, growth, stalled };
  Verdict observe(long iteration, double residual);
  /// Judges from the next residual on as from a new start (the extent keeps the very first).
  void reset() { reference_ = -1.0; }
  /// A step known to exceed its stable limit (c·λmax(W) > 2) is judged after 200 iterations
  /// without progress instead of max(5000, iteration/5): the linear part of the update then grows
  /// or oscillates at once, and waiting only delays the answer.
  void set_unstable_step(bool unstable) { unstable_step_ = unstable; }

 private:
  static constexpr double kReferenceOfExtent = 1e-8;
  double tolerance_, extent_;
  bool unstable_step_ = false;
  double reference_ = -1.0;
  double first_ = -1.0;  ///< the very first residual (or t), never reset
  double best_ = 0.0;
  long best_iteration_ = 0;
};

}  // namespace fibrecheck
