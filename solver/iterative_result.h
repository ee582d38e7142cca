#pragma once

#include <string>
#include <vector>

#include "contact_detection.h"
#include "convergence.h"
#include "iteration_state.h"
#include "iterative_solver.h"
#include "superposition.h"
#include "termination.h"

namespace fibrecheck {

/// What the iteration hands over besides its final state.
struct IterationRecord {
  Termination termination;
  long iterations = 0;
  double step = 0.0;        ///< c, N/mm
  double lambda_max = 0.0;  ///< of the operator the step acted on
  long tresca_updates = 0;
  long geometric_updates = 0;
  long exact_answers = 0;
  Residuals residuals;  ///< at the last evaluation
  std::vector<std::string> warnings;
  std::vector<HistoryEntry> history;
};

/// The result of the iteration in the shared schema (DESIGN §5), from its final forces: strain
/// energies (Eq. 4.34 by the trapezium rule at the slice spacing, and ½ΣP·v), every fibre's
/// displacements and moments at the output samples, the contacts, walls, friction figures, the
/// stages the scene ran and the validity of small deflections.
Result iterative_result(const Scene& scene, const SolverOptions& options,
                        const std::vector<Fibre>& fibres, const Superposition& superposition,
                        const ContactDetector& detector, IterationState& state,
                        const IterationRecord& record);

}  // namespace fibrecheck
