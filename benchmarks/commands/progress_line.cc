#include "progress_line.h"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace fibrecheck {

std::string progress_line(const IterationProgress& p) {
  std::ostringstream line;
  line.precision(3);
  if (p.steps > 0) line << "step " << p.step << " of " << p.steps << ", ";
  line << "iteration " << p.iteration << "/" << p.max_iterations << ", " << p.contacts
       << " candidate contacts, overlap " << p.overlap_residual << " mm, gap-force "
       << p.gap_force_residual << " mm (tolerance " << p.tolerance;
  if (p.working_tolerance < p.tolerance) line << ", now " << p.working_tolerance;
  line << ")";
  if (p.normal_updates > 0) line << ", " << p.normal_updates << " updates of the normals";
  if (p.coulomb) line << ", " << p.radius_updates << " of the Tresca radii";
  line << ", " << std::fixed << std::setprecision(1) << p.elapsed_s << " s";
  return line.str();
}

std::function<void(const IterationProgress&)> progress_printer(bool in_place,
                                                               const std::string& indent) {
  return [in_place, indent](const IterationProgress& p) {
    if (in_place)
      std::cerr << "\r" << indent << progress_line(p) << "\033[K" << std::flush;
    else
      std::cerr << indent << progress_line(p) << "\n";
  };
}

}  // namespace fibrecheck
