#pragma once

#include <Eigen/Core>
#include <deque>
#include <vector>

namespace fibrecheck {

/// Anderson mixing of the normals of the deformed contact (Walker & Ni's form), for the
/// reference's geometric updates.
///
/// Why: each geometric update maps the normals a problem was solved with to the normals of the
/// displaced centres its answer leaves. Fibres that lean on each other roll, and on a compacted
/// tow that map contracts by only about 0.7 an update: the plain sequence takes 20–30 exact solves
/// to turn the normals down to round-off, most of them after the gaps have closed. Once the
/// pushing set stops changing the map is smooth, nearly affine, with a few slow turning modes;
/// mixing the last few updates removes those modes as a Krylov method would, where the plain
/// update only shrinks them by their ratio.
///
/// The unknowns are the normals stacked, x; an update gives g = F(x) and its residual f = g − x.
/// With the differences of the last `depth` updates, ΔF and ΔG, the next normals are
/// g − ΔG·γ with γ minimising ‖f − ΔF·γ‖ (each normal then made a unit vector again).
class NormalMixing {
 public:
  explicit NormalMixing(int depth) : depth_(depth) {}

  /// Forgets the updates so far: the next `mix` returns g itself.
  void restart();

  /// The normals to solve with next, from those the last problem was solved with (`x`) and those
  /// of the displaced centres its answer leaves (`g`), both stacked three components a contact.
  Eigen::VectorXd mix(const Eigen::VectorXd& x, const Eigen::VectorXd& g);

 private:
  int depth_;
  Eigen::VectorXd last_f_, last_g_;
  std::deque<Eigen::VectorXd> dF_, dG_;
};

}  // namespace fibrecheck
