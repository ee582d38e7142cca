#include "study_command.h"

#include <cstdio>
#include <iostream>

#include "compaction_study.h"
#include "exit_codes.h"
#include "input_error.h"
#include "scene.h"
#include "slice_study.h"
#include "solvers.h"
#include "stability_study.h"
#include "tolerance_study.h"
#ifdef FIBRECHECK_WITH_FEM
#include "mpi_session.h"
#endif

namespace fibrecheck {

int run_study(const StudyArguments& args) {
  if (args.scenes.empty()) throw InputError("command line", "", "no scene file given (see --help)");
  const std::vector<Scene> scenes = read_scenes(args.scenes);
  for (int n : args.slices)
    if (n < 1) throw InputError("command line", "--slices", "every slice count must be at least 1");
  if (!have_reference())
    throw InputError("command line", "",
                     "a study measures against the reference: it needs the build with "
                     "-DFIBRECHECK_WITH_FEM=ON");
#ifdef FIBRECHECK_WITH_FEM
  const MpiSession mpi;
#endif
  const Solvers solvers = make_solvers(true);
  if (args.study == "slices") {
    SliceStudyOptions o;
    if (!args.slices.empty()) o.slices = args.slices;
    o.quiet = args.quiet;
    const auto result = run_slice_study(scenes, o, solvers, args.out);
    if (!args.quiet)
      for (const SliceStudyScene& s : result) {
        std::printf("%s (rule %s, t_d %g mm; ground truth's line force within %.1e):\n",
                    s.scene.c_str(), s.rule.c_str(), s.tolerance, s.truth_error_estimate);
        std::printf("  %8s %12s %12s %12s %10s\n", "slices", "deflection", "force", "energy",
                    "time_s");
        for (const SliceStudyPoint& p : s.points)
          std::printf("  %8d %12.3e %12.3e %12.3e %10.4f\n", p.slices, p.errors.deflection,
                      p.errors.force, p.errors.energy, p.time_s);
        std::printf("  observed order: deflection %.2f, force %.2f, energy %.2f\n",
                    s.order.deflection, s.order.force, s.order.energy);
      }
  } else if (args.study == "tolerance") {
    ToleranceStudyOptions o;
    if (!args.tolerances.empty()) o.tolerances = args.tolerances;
    if (!args.fractions.empty()) o.seed_fractions = args.fractions;
    if (!args.refinements.empty()) o.refinements = args.refinements;
    if (args.max_iterations > 0) o.max_iterations = args.max_iterations;
    o.against_slices = args.against_slices;
    o.quiet = args.quiet;
    const auto result = run_tolerance_study(scenes, o, solvers, args.out);
    if (!args.quiet)
      for (const ToleranceStudyScene& s : result)
        for (const SpeedUp& u : s.speedups)
          std::printf(
              "%s: at error %.0e the iterative method (%s) takes %.4g s, the reference "
              "%.4g s: speed-up %.3g\n",
              s.scene.c_str(), u.error_level, u.iterative_method.c_str(), u.iterative_time_s,
              u.reference_time_s, u.speedup());
  } else if (args.study == "compaction") {
    CompactionStudyOptions o;
    o.steps = args.steps;
    o.final_compaction = args.final_compaction;
    o.sections = args.sections;
    o.quiet = args.quiet;
    const auto result = run_compaction_study(scenes, o, solvers, args.out);
    if (!args.quiet)
      for (const CompactionStudyScene& s : result) {
        std::printf("%s:\n", s.scene.c_str());
        for (const CompactionRun& r : s.runs) {
          const CompactionPoint* last = r.points.empty() ? nullptr : &r.points.back();
          std::printf(
              "  %-9s mu %-4g %-8s %-14s %zu steps, last Vf %.3f p %.4g MPa; van Wyk k %.3g "
              "Vf0 %.3f R2 %.3f; Toll k %.3g n %.2f Vf0 %.3f R2 %.3f\n",
              r.solver.c_str(), r.mu, r.friction_model.c_str(), r.status.c_str(), r.points.size(),
              last ? last->fibre_volume_fraction : NAN, last ? last->pressure : NAN, r.van_wyk.k,
              r.van_wyk.vf0, r.van_wyk.r2, r.toll.k, r.toll.n, r.toll.vf0, r.toll.r2);
        }
        for (const CompactionAgreement& a : s.agreement)
          std::printf(
              "  iterative (mu %g, %s) against the reference (%s): pressure %.2e, energy "
              "%.2e over %d steps\n",
              a.mu, a.friction_model.c_str(), a.against.c_str(), a.pressure_error, a.energy_error,
              a.steps);
      }
  } else {
    StabilityStudyOptions o;
    if (!args.fractions.empty()) o.fractions = args.fractions;
    if (!args.ratios.empty()) o.stiffness_ratios = args.ratios;
    if (args.max_iterations > 0) o.max_iterations = args.max_iterations;
    o.quiet = args.quiet;
    const auto result = run_stability_study(scenes, o, solvers, args.out);
    if (!args.quiet)
      for (const StabilityStudyScene& s : result) {
        for (const CataloguePoint& p : s.catalogue)
          std::printf("%-28s %-9s %-13s expected %-13s %s\n", s.scene.c_str(), p.solver.c_str(),
                      p.status.c_str(), p.expected_status.c_str(),
                      p.failures.empty() ? "as expected" : p.failures.c_str());
        if (!s.catalogue.empty()) continue;
        std::printf("%s: rule seed, c_crit = %.4g N/mm\n", s.scene.c_str(), s.c_crit);
        for (const StepPoint& p : s.steps)
          std::printf("  c = %5.2f c_crit: %-15s (%s) after %ld iterations\n", p.fraction,
                      p.status.c_str(), p.criterion.c_str(), p.iterations);
      }
  }
  if (!args.quiet) std::cout << "study written to " << args.out << "\n";
  return kExitConverged;
}

CLI::App* add_study_command(CLI::App& app, StudyArguments& args) {
  CLI::App* study = app.add_subcommand("study", "Studies of accuracy, cost and stability");
  study->require_subcommand(1);
  auto common = [&](CLI::App* s) {
    s->add_option("scenes", args.scenes, "Scene files (JSON)")->required();
    s->add_option("--out", args.out, "Folder of the study's data")->required();
    s->add_option("--max-iterations", args.max_iterations, "Cap on each iterative run")
        ->check(CLI::PositiveNumber);
    s->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
    s->callback([&args, s] { args.study = s->get_name(); });
  };
  CLI::App* slices = study->add_subcommand(
      "slices", "Error of the iterative method against the continuous reference per slice count");
  common(slices);
  slices->add_option("--slices", args.slices, "Slice counts, e.g. 2,4,8,16")->delimiter(',');
  CLI::App* tolerance = study->add_subcommand(
      "tolerance",
      "Error against run time for every rule and the reference; speed-up at equal error");
  common(tolerance);
  tolerance
      ->add_option("--tolerances", args.tolerances,
                   "Overlap tolerances t_d as multiples of the smallest radius")
      ->delimiter(',');
  tolerance
      ->add_option("--seed-fractions", args.fractions,
                   "The seed rule's c as fractions of its stable limit")
      ->delimiter(',');
  tolerance->add_option("--refinements", args.refinements, "The reference's refinements K")
      ->delimiter(',');
  tolerance->add_flag("--against-slices", args.against_slices,
                      "Measure against the reference on the scene's own slices (the solution "
                      "method alone; for tows whose continuous reference is out of reach)");
  CLI::App* stability = study->add_subcommand(
      "stability", "The seed rule's step c against its stable limit; stiffness contrasts");
  common(stability);
  stability->add_option("--fractions", args.fractions, "c as fractions of the stable limit")
      ->delimiter(',');
  stability
      ->add_option("--stiffness-ratios", args.ratios,
                   "Young's modulus of every second fibre times these")
      ->delimiter(',');
  CLI::App* compaction = study->add_subcommand(
      "compaction",
      "Pressure against fibre volume fraction along each scene's load path, both solvers, with "
      "and without friction; van Wyk and Toll fits");
  common(compaction);
  compaction
      ->add_option("--steps", args.steps,
                   "For scenes without steps: this many compaction steps (0: such scenes are "
                   "refused)")
      ->check(CLI::NonNegativeNumber);
  compaction
      ->add_option("--final-compaction", args.final_compaction,
                   "The last step's compaction factor F for --steps")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  compaction
      ->add_option("--sections", args.sections,
                   "Steps whose state is kept for cross-section pictures (the last always is)")
      ->delimiter(',');
  return study;
}

}  // namespace fibrecheck
