#include "reference_result.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <sstream>

#include "reference_solver_class.h"
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
    const bool capped = trouble.friction_unsettled || trouble.normals_unsettled;
    r.status = trouble.non_finite     ? Status::diverged
               : capped               ? Status::max_iterations
               : trouble.beyond_reach ? Status::beyond_reach
                                      : Status::unresolvable;
    r.criterion = trouble.non_finite     ? Criterion::non_finite
                  : capped               ? Criterion::max_iterations
                  : trouble.beyond_reach ? Criterion::memory
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
        "the reference solves Coulomb's law exactly; friction_model \"seed\" names the "
        "iterative solver's approximation of it (Eqs. 4.29-4.33), which it is compared with");
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
  summary << "unknowns " << counts.unknowns;
  if (counts.saddle_point) summary << ", contact problem held as saddle points";
  summary << ", active-set passes " << counts.active_set_passes;
  if (counts.friction)
    summary << ", friction: Tresca updates " << counts.tresca_updates << ", Newton steps "
            << counts.newton_steps;
  if (counts.newton_finishes > 0)
    summary << " (" << counts.newton_finishes
            << " Tresca fixed points stalled and finished by Newton's method on Coulomb's law)";
  if (counts.cg) summary << ", CG iterations " << counts.cg_iterations << " (last mesh)";
  summary << "; wall time per phase (s):";
  for (const auto& [phase, seconds] : timer.get_summary_data(dealii::TimerOutput::total_wall_time))
    summary << " " << phase << " " << seconds;
  return summary.str();
}

// describe_run: what the result says besides the solution — warnings, outer iterations, the
// finite elements' figures, the stages, the wall time and the run's cost in its message.
void ReferenceSolver::describe_run(Result& r, const std::vector<std::string>& ambiguous, int outer,
                                   std::chrono::steady_clock::time_point start) {
  add_reference_warnings(r, ambiguous, fibres_, scene_, tolerance_);
  if (options_.contact_assembly == ContactAssembly::saddle_point && !saddle_point_possible())
    r.warnings.push_back(
        "saddle points were asked for (--contact-assembly saddle_point), but they hold only a "
        "frictionless problem on MUMPS's beams that is not exported; this run, " +
        std::string(mu_ > 0.0 ? "with friction"
                    : options_.beam_solver != BeamSolver::direct
                        ? "with --beam-solver cg_amg"
                        : "exporting its contact problem") +
        ", held the compliance matrix");
  if (friction_settled_to_ > 0.0) {
    std::ostringstream out;
    out.precision(3);
    out << "Coulomb's law was settled to " << friction_settled_to_ << " mm of slip where "
        << friction_aimed_
        << " mm was aimed at: the sticking contacts' equations are nearly singular (contacts that "
           "constrain the same motion twice), and the round-off of their answers leaves the "
           "friction determined only that far";
    r.warnings.push_back(out.str());
  }
  r.iterations = outer;
  r.finite_elements->active_set_iterations = active_set_iterations_;
  r.finite_elements->unknowns = static_cast<long>(
      dealii::Utilities::MPI::sum(model_ ? model_->unknowns() : std::size_t(0), comm_));
  r.stages = reference_stages(detector_, options_, mu_ > 0.0, processes_);
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ReferenceCounts counts;
  counts.unknowns = r.finite_elements->unknowns;
  counts.active_set_passes = active_set_iterations_;
  counts.friction = mu_ > 0.0;
  counts.tresca_updates = tresca_updates_;
  counts.newton_steps = newton_steps_;
  counts.newton_finishes = newton_finishes_;
  counts.cg = options_.beam_solver == BeamSolver::cg_amg;
  counts.cg_iterations = model_ ? model_->cg_iterations() : 0;
  counts.saddle_point = saddle_point();
  if (!r.message.empty()) r.message += "; ";
  r.message += reference_summary(counts, timer_);
  if (options_.print_timing) {
    if (processes_ == 1)
      timer_.print_summary();
    else
      timer_.print_wall_time_statistics(comm_);
  }
}

}  // namespace fibrecheck
