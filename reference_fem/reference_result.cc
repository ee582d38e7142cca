#include "reference_result.h"

#include <algorithm>
#include <sstream>

#include "validity.h"

namespace fibrecheck {

Result reference_outcome(const std::string& scene, OuterEnd end, const ReferenceTrouble& trouble,
                         int max_outer_iterations) {
  Result r;
  r.scene = scene;
  r.solver = "fem";
  r.rule = "active_set";
  r.status = Status::max_iterations;
  r.criterion = Criterion::max_iterations;
  if (end == OuterEnd::settled) {
    r.status = Status::converged;
    r.criterion = Criterion::active_set;
  } else if (end == OuterEnd::no_answer) {
    r.status = trouble.non_finite           ? Status::diverged
               : trouble.friction_unsettled ? Status::max_iterations
                                            : Status::unresolvable;
    r.criterion = trouble.non_finite           ? Criterion::non_finite
                  : trouble.friction_unsettled ? Criterion::max_iterations
                                               : Criterion::unresolvable;
    r.message = trouble.why;
  } else {
    r.message = "the candidates still changed after " + std::to_string(max_outer_iterations) +
                " outer iterations";
  }
  return r;
}

std::vector<std::string> reference_stages(const ContactDetector& detector,
                                          const ReferenceOptions& options, bool friction,
                                          unsigned int processes) {
  std::vector<std::string> stages = {"gmsh_mesh", "fem_beams", "active_set"};
  if (detector.point_search()) stages.push_back("point_contacts");
  if (detector.slicing()) stages.push_back("slices");
  if (detector.walls()) stages.push_back("walls");
  if (options.line_contact == LineContact::continuous) stages.push_back("continuous_line_contact");
  stages.push_back(options.beam_solver == BeamSolver::direct ? "mumps" : "cg_boomeramg");
  if (friction) stages.push_back("friction_coulomb");
  if (processes > 1) stages.push_back("mpi_" + std::to_string(processes) + "_processes");
  return stages;
}

void add_reference_warnings(Result& r, const std::vector<std::string>& ambiguous,
                            const std::vector<Fibre>& fibres, const Scene& scene,
                            double tolerance) {
  r.warnings.insert(r.warnings.begin(), ambiguous.begin(), ambiguous.end());
  assess_validity(r, fibres);
  if (scene.contact.friction > 0.0 && scene.contact.friction_model == FrictionModel::seed)
    r.warnings.push_back(
        "the reference solves Coulomb's law exactly; "
        "friction_model \"seed\" names the "
        "iterative solver's approximation of it (Eqs. "
        "4.29-4.33), which it is compared with");
  if (r.status == Status::converged && r.max_overlap > tolerance) {
    std::ostringstream out;
    out.precision(3);
    out << "an overlap of " << r.max_overlap << " mm remains, above the scene's tolerance of "
        << tolerance << " mm: the round-off of the finite-element solves and of the contact "
        << "compliance matrix (close contact points make it ill-conditioned)";
    r.warnings.push_back(out.str());
  }
}

std::string reference_summary(const ReferenceCounts& counts, const dealii::TimerOutput& timer) {
  std::ostringstream summary;
  summary.precision(3);
  summary << "unknowns " << counts.unknowns << ", active-set passes " << counts.active_set_passes;
  if (counts.friction)
    summary << ", friction: Tresca updates " << counts.tresca_updates << ", Newton steps "
            << counts.newton_steps;
  if (counts.cg) summary << ", CG iterations " << counts.cg_iterations << " (last mesh)";
  summary << "; wall time per phase (s):";
  for (const auto& [phase, seconds] : timer.get_summary_data(dealii::TimerOutput::total_wall_time))
    summary << " " << phase << " " << seconds;
  return summary.str();
}

}  // namespace fibrecheck
