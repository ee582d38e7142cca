#include "study_command.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "compaction_study.h"
#include "exit_codes.h"
#include "input_error.h"
#include "program_runner.h"
#include "scale_study.h"
#include "scene.h"
#include "slice_study.h"
#include "solvers.h"
#include "stability_study.h"
#include "tolerance_study.h"
#ifdef FIBRECHECK_WITH_FEM
#include "mpi_session.h"
#endif

namespace fibrecheck {

namespace {

int run_scale(const StudyArguments& args) {
  ScaleStudyOptions o;
  o.fibres = args.fibres;
  o.slices = args.tow_slices;
  o.seed = args.tow_seed;
  o.rules = args.rules;
  o.seed_c = args.seed_c;
  // An empty list on the command line ('' or 0) means none.
  auto sizes = [](std::vector<int> list) {
    list.erase(std::remove(list.begin(), list.end(), 0), list.end());
    return list;
  };
  o.reference_fibres = sizes(args.reference_fibres);
  o.processes = args.processes;
  o.peer_fibres = sizes(args.peer_fibres);
  o.peer_solvers = args.peer_solvers;
  o.program = this_program();
  o.peer_program = program_beside_this("fibrecheck-siconos");
  o.quiet = args.quiet;
  if (!o.reference_fibres.empty() && !have_reference())
    throw InputError("command line", "--reference-fibres",
                     "this build has no finite-element reference (-DFIBRECHECK_WITH_FEM=ON); "
                     "give --reference-fibres with no sizes to run the iterative solver only");
  if (o.processes > 1 && !o.reference_fibres.empty()) {
    o.mpiexec = find_on_path("mpiexec");
    if (o.mpiexec.empty())
      throw InputError("command line", "--processes",
                       "no mpiexec on PATH (Debian: openmpi-bin); use --processes 1");
  }
  const ScaleStudy study = run_scale_study(o, run_program, args.out);
  if (!args.quiet) {
    std::printf("%7s %-9s %-12s %3s %-14s %10s %9s %10s %10s %10s %10s\n", "fibres", "solver",
                "method", "np", "status", "candidates", "active", "iterations", "time_s", "ms/iter",
                "peak_MB");
    for (const ScalePoint& p : study.points)
      std::printf("%7d %-9s %-12s %3d %-14s %10ld %9ld %10ld %10.3f %10.4f %10.1f\n", p.fibres,
                  p.solver.c_str(), p.method.c_str(), p.processes, p.status.c_str(), p.candidates,
                  p.active, p.iterations, p.time_s, p.ms_per_iteration(), p.peak_memory_mb);
    for (const ScaleExponent& e : study.exponents)
      std::printf("  %s %s: time ~ fibres^%.2f, peak memory ~ fibres^%.2f (%d sizes)\n",
                  e.solver.c_str(), e.method.c_str(), e.time, e.memory, e.sizes);
    std::cout << "study written to " << args.out << "\n";
  }
  return kExitConverged;
}

}  // namespace

int run_study(const StudyArguments& args) {
  if (args.study == "scale") return run_scale(args);
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
  CLI::App* scale = study->add_subcommand(
      "scale",
      "Time, iterations and peak memory against the number of fibres on generated tows: each "
      "rule, the reference (under mpiexec) and Siconos on the reference's problem");
  scale->add_option("--out", args.out, "Folder of the study's data")->required();
  scale->add_option("--fibres", args.fibres, "Tow sizes for the iterative rules (default 100,1000)")
      ->delimiter(',');
  scale->add_option("--seed-c", args.seed_c, "The seed rule's step c in N/mm")
      ->check(CLI::PositiveNumber);
  scale->add_option("--slices", args.tow_slices, "Slices of the generated tows (default 100)")
      ->check(CLI::Range(1, 100000));
  scale->add_option("--seed", args.tow_seed, "Seed of the generated tows (default 3)");
  scale
      ->add_option("--rules", args.rules,
                   "Iterative rules (default auto,accelerated; seed needs --seed-c)")
      ->delimiter(',')
      ->check(CLI::IsMember(update_rule_names()));
  scale
      ->add_option("--reference-fibres", args.reference_fibres,
                   "Sizes the reference runs at (default 100; none: --reference-fibres 0)")
      ->delimiter(',')
      ->expected(0, -1);
  scale->add_option("--processes", args.processes, "MPI processes of the reference (default 2)")
      ->check(CLI::Range(1, 1024));
  scale
      ->add_option("--peer-fibres", args.peer_fibres,
                   "Sizes whose reference problem Siconos solves again (default 100; none: 0)")
      ->delimiter(',')
      ->expected(0, -1);
  scale
      ->add_option("--peer-solvers", args.peer_solvers,
                   "Siconos solvers of the frictionless problem: lemke (the default), pgs, newton")
      ->delimiter(',')
      ->check(CLI::IsMember({"lemke", "pgs", "newton"}));
  scale->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  scale->callback([&args, scale] { args.study = scale->get_name(); });
  return study;
}

}  // namespace fibrecheck
