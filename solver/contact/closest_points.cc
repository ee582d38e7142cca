#include "closest_points.h"

#include <algorithm>
#include <cmath>

namespace fibrecheck {

namespace {

double clamp01(double x) {
  return std::min(1.0, std::max(0.0, x));
}

ClosestPoints finish(const Eigen::Vector3d& a1, const Eigen::Vector3d& da,
                     const Eigen::Vector3d& b1, const Eigen::Vector3d& db, double mu_a, double mu_b,
                     bool parallel) {
  ClosestPoints r;
  r.mu_a = mu_a;
  r.mu_b = mu_b;
  r.a = a1 + mu_a * da;
  r.b = b1 + mu_b * db;
  r.distance = (r.b - r.a).norm();
  r.parallel = parallel;
  return r;
}

}  // namespace

ClosestPoints segment_closest_points(const Eigen::Ref<const Eigen::Vector3d>& a1,
                                     const Eigen::Ref<const Eigen::Vector3d>& a2,
                                     const Eigen::Ref<const Eigen::Vector3d>& b1,
                                     const Eigen::Ref<const Eigen::Vector3d>& b2) {
  const Eigen::Vector3d da = a2 - a1;  // A2 − A1
  const Eigen::Vector3d db = b2 - b1;  // B2 − B1
  const Eigen::Vector3d w = a1 - b1;   // A1 − B1
  const double aa = da.squaredNorm();
  const double bb = db.squaredNorm();
  const double ab = da.dot(db);
  const double wa = w.dot(da);
  const double wb = w.dot(db);
  const double tiny = 1e-300;

  if (aa <= tiny && bb <= tiny) return finish(a1, da, b1, db, 0.0, 0.0, false);
  if (aa <= tiny) return finish(a1, da, b1, db, 0.0, clamp01(wb / bb), false);
  if (bb <= tiny) return finish(a1, da, b1, db, clamp01(-wa / aa), 0.0, false);

  // Eq. 4.24: the denominator of Eq. 4.22, relative to its scale.
  const double denominator = aa * bb - ab * ab;
  if (denominator <= 1e-14 * aa * bb) {
    // Parallel: project B's ends onto A and take the middle of the common stretch.
    const double t1 = -wa / aa;        // B1 on A
    const double t2 = (ab - wa) / aa;  // B2 on A
    const double lo = std::max(0.0, std::min(t1, t2));
    const double hi = std::min(1.0, std::max(t1, t2));
    const double mu_a = lo <= hi ? 0.5 * (lo + hi) : (std::max(t1, t2) < 0.0 ? 0.0 : 1.0);
    const double mu_b = clamp01((wb + mu_a * ab) / bb);  // Eq. 4.23 for this µA
    // Where the stretches do not overlap, the nearest end of B decides µA again.
    return finish(a1, da, b1, db, clamp01((mu_b * ab - wa) / aa), mu_b, true);
  }

  // Eq. 4.22 and Eq. 4.23, then clamping to the segments.
  double mu_a = clamp01((wb * ab - wa * bb) / denominator);
  double mu_b = (wb + mu_a * ab) / bb;
  if (mu_b < 0.0) {
    mu_b = 0.0;
    mu_a = clamp01(-wa / aa);
  } else if (mu_b > 1.0) {
    mu_b = 1.0;
    mu_a = clamp01((ab - wa) / aa);
  }
  return finish(a1, da, b1, db, mu_a, mu_b, false);
}

}  // namespace fibrecheck
