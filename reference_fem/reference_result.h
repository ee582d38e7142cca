#pragma once

#include <deal.II/base/timer.h>

#include <string>
#include <vector>

#include "contact_detection.h"
#include "fibre.h"
#include "reference_solver.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// Why the reference could not solve a step's contact problem (empty `why` when it could).
struct ReferenceTrouble {
  std::string why;
  bool non_finite = false;           ///< the finite-element solutions were not finite
  bool friction_unsettled = false;   ///< the frictional problem did not settle
  bool normals_unsettled = false;    ///< deformed contact: the normals did not settle
  bool beyond_reach = false;         ///< the contact problem would not fit in memory
  bool fibres_beyond_reach = false;  ///< nor would the finite elements alone: nothing is meshed
};

/// How the reference's outer loop ended.
enum class OuterEnd {
  settled,             ///< re-detection found nothing new that overlaps
  no_answer,           ///< the contact problem could not be solved (ReferenceTrouble)
  candidates_changing  ///< the outer iterations ran out with the candidates still changing
};

/// A step's result before its solution is written in (DESIGN §5): scene, solver `fem`, rule
/// `active_set`, and the status, criterion and message of how the outer loop ended — converged
/// when it settled; when the problem had no answer, diverged (non-finite finite-element solutions),
/// max_iterations (friction did not settle), beyond_reach (it would not fit in memory) or
/// unresolvable (an overlap nothing can move).
Result reference_outcome(const std::string& scene, OuterEnd end, const ReferenceTrouble& trouble,
                         int max_outer_iterations);

/// The stages that ran (DESIGN §2, "leave out what a scene does not need"), in the order the
/// result files list them.
std::vector<std::string> reference_stages(const ContactDetector& detector,
                                          const ReferenceOptions& options, bool friction,
                                          unsigned int processes);

/// The warnings of a solved step, after its solution is in `r`: the ambiguous sides of the first
/// detection first, then the small-deflection checks (assess_validity, which also sets the largest
/// deflection and slope), that friction_model `seed` is solved as exact Coulomb, and an overlap
/// left above the scene's tolerance `tolerance` (mm) by round-off.
void add_reference_warnings(Result& r, const std::vector<std::string>& ambiguous,
                            const std::vector<Fibre>& fibres, const Scene& scene, double tolerance);

/// What a run cost, for its message.
struct ReferenceCounts {
  long unknowns = 0;
  long active_set_passes = 0;
  bool friction = false;
  long tresca_updates = 0;
  long newton_steps = 0;
  long newton_finishes =
      0;            ///< fixed points that stalled and Newton's method on Coulomb's law settled
  bool cg = false;  ///< the beams solved by CG (BeamSolver::cg_amg)
  long cg_iterations = 0;
  bool saddle_point = false;  ///< the contact problem held as saddle points (ContactAssembly)
};

/// The message's tail: the unknowns, how the contact problem was held, the active-set passes, the
/// friction's fixed-point updates, Newton steps and the fixed points Newton finished, the CG
/// iterations of the last mesh, and the wall time (s) of each phase.
std::string reference_summary(const ReferenceCounts& counts, const dealii::TimerOutput& timer);

}  // namespace fibrecheck
