#include "solvers.h"

#include <iostream>

#include "input_error.h"
#include "iterative_solver.h"
#include "progress_line.h"
#ifdef FIBRECHECK_WITH_FEM
#include "reference_solver.h"
#endif

namespace fibrecheck {

bool have_reference() {
#ifdef FIBRECHECK_WITH_FEM
  return true;
#else
  return false;
#endif
}

Solvers make_solvers(bool quiet, double progress_every_s) {
  Solvers s;
  s.iterative = [progress_every_s](const Scene& scene) {
    SolverOptions o = SolverOptions::from_scene(scene);
    if (progress_every_s > 0.0) {
      o.progress = progress_printer(false, "    ");
      o.progress_interval_s = progress_every_s;
    }
    return solve_iteratively(scene, o);
  };
#ifdef FIBRECHECK_WITH_FEM
  auto options = [quiet](LineContact mode) {
    ReferenceOptions o;
    o.line_contact = mode;
    o.communicator = MPI_COMM_SELF;  // the harness runs on one process
    if (!quiet) o.progress = [](const std::string& line) { std::cerr << "    " << line << "\n"; };
    return o;
  };
  s.reference_slices = [options](const Scene& scene) {
    return solve_reference(scene, options(LineContact::slices));
  };
  s.reference_continuous = [options](const Scene& scene) {
    ReferenceOptions o = options(LineContact::continuous);
    o.refine_until_converged = true;
    o.max_refine = finest_refinement(scene);
    return solve_reference(scene, o);
  };
  s.reference_refined = [options](const Scene& scene, int K) {
    ReferenceOptions o = options(LineContact::continuous);
    o.refine = K;
    return solve_reference(scene, o);
  };
#else
  (void)quiet;
  auto missing = [](const Scene& scene) -> Result {
    throw InputError(scene.source.empty() ? scene.name : scene.source, "",
                     "running the reference needs the build with -DFIBRECHECK_WITH_FEM=ON");
  };
  s.reference_slices = missing;
  s.reference_continuous = missing;
  s.reference_refined = [missing](const Scene& scene, int) { return missing(scene); };
#endif
  return s;
}

}  // namespace fibrecheck
