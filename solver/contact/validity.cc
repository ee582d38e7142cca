#include "validity.h"

#include <cmath>
#include <sstream>

namespace fibrecheck {

void assess_validity(Result& r, const std::vector<Fibre>& fibres) {
  r.max_deflection_over_radius = 0.0;
  r.max_slope = 0.0;
  std::string steepest;
  for (std::size_t f = 0; f < fibres.size() && f < r.fibres.size(); ++f) {
    const Fibre& fibre = fibres[f];
    const std::vector<Eigen::Vector3d>& u = r.fibres[f].displacement;
    auto across = [&](const Eigen::Vector3d& v) { return v - v.dot(fibre.t) * fibre.t; };
    for (std::size_t j = 0; j < u.size(); ++j) {
      r.max_deflection_over_radius =
          std::max(r.max_deflection_over_radius, across(u[j]).norm() / fibre.radius);
      if (j == 0) continue;
      const double ds = fibre.length / static_cast<double>(u.size() - 1);
      const double slope = across(u[j] - u[j - 1]).norm() / ds;
      if (slope > r.max_slope) r.max_slope = slope, steepest = fibre.id;
    }
  }
  std::ostringstream out;
  out.precision(3);
  if (r.max_slope > kMaxSlope) {
    out << "outside small-deflection theory: fibre " << steepest << " has a slope of "
        << r.max_slope << " rad (largest deflection " << r.max_deflection_over_radius
        << " radii), above " << kMaxSlope
        << " rad; the linear beams of the model no longer describe the fibres";
    r.warnings.push_back(out.str());
  }
  for (const Fibre& fibre : fibres) {
    const double share = 8.8 * std::pow(fibre.radius / fibre.length, 2);
    if (share > kMaxShearShare) {
      std::ostringstream stubby;
      stubby.precision(3);
      stubby << "fibre " << fibre.id << " is stubby (L/r = " << fibre.length / fibre.radius
             << "): shear deformation, which Euler–Bernoulli beams leave out, would add about "
             << 100.0 * share << " % to its deflection";
      r.warnings.push_back(stubby.str());
      break;
    }
  }
}

}  // namespace fibrecheck
