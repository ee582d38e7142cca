#include "study_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>

#include "exit_codes.h"
#include "input_error.h"
#include "program_runner.h"
#include "scene.h"
#include "solvers.h"
#ifdef FIBRECHECK_WITH_FEM
#include "mpi_session.h"
#endif

namespace fibrecheck {

namespace {

const std::string kStudyNames =
    "the studies are slices, tolerance, stability, compaction, scale and friction";

using SceneStudy = std::function<void(const std::vector<Scene>&, const Solvers&)>;

/// How often a study's iterative runs say where they stand (s): never when quiet.
double progress_every(const StudyArguments& args) {
  return args.quiet ? 0.0 : args.progress_every_s;
}

/// A study on scene files: the scenes read, `check` on the options, the reference there (a study
/// measures against it), then `study` with the solvers.
int run_scene_study(const StudyArguments& args, const std::function<void()>& check,
                    const SceneStudy& study) {
  if (args.scenes.empty()) throw InputError("command line", "", "no scene file given (see --help)");
  const std::vector<Scene> scenes = read_scenes(args.scenes);
  check();
  if (!have_reference())
    throw InputError("command line", "",
                     "a study measures against the reference: it needs the build with "
                     "-DFIBRECHECK_WITH_FEM=ON");
#ifdef FIBRECHECK_WITH_FEM
  const MpiSession mpi;
#endif
  study(scenes, make_solvers(true, progress_every(args)));
  if (!args.quiet) std::cout << "study written to " << args.out << "\n";
  return kExitConverged;
}

void print(const SliceStudyScene& s) {
  std::printf("%s (rule %s, t_d %g mm; ground truth's line force within %.1e):\n", s.scene.c_str(),
              s.rule.c_str(), s.tolerance, s.truth_error_estimate);
  std::printf("  %8s %12s %12s %12s %10s\n", "slices", "deflection", "force", "energy", "time_s");
  for (const SliceStudyPoint& p : s.points)
    std::printf("  %8d %12.3e %12.3e %12.3e %10.4f\n", p.slices, p.errors.deflection,
                p.errors.force, p.errors.energy, p.time_s);
  std::printf("  observed order: deflection %.2f, force %.2f, energy %.2f\n", s.order.deflection,
              s.order.force, s.order.energy);
}

int run_slices(const StudyArguments& args) {
  SliceStudyOptions o = args.slices;
  o.quiet = args.quiet;
  auto check = [&] {
    for (int n : o.slices)
      if (n < 1)
        throw InputError("command line", "--slices", "every slice count must be at least 1");
  };
  return run_scene_study(args, check, [&](const std::vector<Scene>& scenes, const Solvers& s) {
    for (const SliceStudyScene& study : run_slice_study(scenes, o, s, args.out))
      if (!args.quiet) print(study);
  });
}

void print(const ToleranceStudyScene& s) {
  for (const SpeedUp& u : s.speedups) {
    if (std::isnan(u.iterative_time_s) || std::isnan(u.reference_time_s)) {
      std::printf("%s: at error %.0e no converged run of the %s reaches it: no speed-up\n",
                  s.scene.c_str(), u.error_level,
                  std::isnan(u.iterative_time_s) ? "iterative method" : "reference");
      continue;
    }
    std::printf(
        "%s: at error %.0e the iterative method (%s) takes %.4g s, the reference "
        "%.4g s: speed-up %.3g\n",
        s.scene.c_str(), u.error_level, u.iterative_method.c_str(), u.iterative_time_s,
        u.reference_time_s, u.speedup());
  }
}

int run_tolerance(const StudyArguments& args) {
  ToleranceStudyOptions o = args.tolerance;
  o.quiet = args.quiet;
  return run_scene_study(
      args, [] {},
      [&](const std::vector<Scene>& scenes, const Solvers& s) {
        for (const ToleranceStudyScene& study : run_tolerance_study(scenes, o, s, args.out))
          if (!args.quiet) print(study);
      });
}

void print(const StabilityStudyScene& s) {
  for (const CataloguePoint& p : s.catalogue)
    std::printf("%-28s %-9s %-13s expected %-13s %s\n", s.scene.c_str(), p.solver.c_str(),
                p.status.c_str(), p.expected_status.c_str(),
                p.failures.empty() ? "as expected" : p.failures.c_str());
  if (!s.catalogue.empty()) return;
  std::printf("%s: rule seed, c_crit = %.4g N/mm\n", s.scene.c_str(), s.c_crit);
  for (const StepPoint& p : s.steps)
    std::printf("  c = %5.2f c_crit: %-15s (%s) after %ld iterations\n", p.fraction,
                p.status.c_str(), p.criterion.c_str(), p.iterations);
}

int run_stability(const StudyArguments& args) {
  StabilityStudyOptions o = args.stability;
  o.quiet = args.quiet;
  return run_scene_study(
      args, [] {},
      [&](const std::vector<Scene>& scenes, const Solvers& s) {
        for (const StabilityStudyScene& study : run_stability_study(scenes, o, s, args.out))
          if (!args.quiet) print(study);
      });
}

void print(const CompactionStudyScene& s) {
  std::printf("%s:\n", s.scene.c_str());
  for (const CompactionRun& r : s.runs) {
    // The last step that converged: a step that did not has no pressure to read.
    const CompactionPoint* last = nullptr;
    int converged = 0;
    for (const CompactionPoint& p : r.points)
      if (p.status == "converged") last = &p, ++converged;
    std::printf(
        "  %-9s mu %-4g %-8s %-10s %-14s %d of %zu steps converged, the last at Vf %.3f p %.4g "
        "MPa; van Wyk k %.3g Vf0 %.3f R2 %.3f; Toll k %.3g n %.2f Vf0 %.3f R2 %.3f\n",
        r.solver.c_str(), r.mu, r.friction_model.c_str(), r.geometry.c_str(), r.status.c_str(),
        converged, r.points.size(), last ? last->fibre_volume_fraction : NAN,
        last ? last->pressure : NAN, r.van_wyk.k, r.van_wyk.vf0, r.van_wyk.r2, r.toll.k, r.toll.n,
        r.toll.vf0, r.toll.r2);
  }
  for (const CompactionAgreement& a : s.agreement)
    std::printf(
        "  iterative (mu %g, %s) against the reference (%s): pressure %.2e, energy "
        "%.2e over %d steps\n",
        a.mu, a.friction_model.c_str(), a.against.c_str(), a.pressure_error, a.energy_error,
        a.steps);
}

int run_compaction(const StudyArguments& args) {
  CompactionStudyOptions o = args.compaction;
  o.quiet = args.quiet;
  return run_scene_study(
      args, [] {},
      [&](const std::vector<Scene>& scenes, const Solvers& s) {
        for (const CompactionStudyScene& study : run_compaction_study(scenes, o, s, args.out))
          if (!args.quiet) print(study);
      });
}

void print(const ScaleStudy& study) {
  std::printf("%7s %-9s %-12s %3s %-14s %10s %9s %10s %10s %10s %10s\n", "fibres", "solver",
              "method", "np", "status", "candidates", "active", "iterations", "time_s", "ms/iter",
              "peak_MB");
  for (const ScalePoint& p : study.points)
    std::printf("%7d %-9s %-12s %3d %-14s %10ld %9ld %10ld %10.3f %10.4f %10.1f\n", p.fibres,
                p.solver.c_str(), p.method.c_str(), p.processes, p.status.c_str(), p.candidates,
                p.active, p.iterations, p.time_s, p.ms_per_iteration(), p.peak_memory_mb);
  for (const ScaleExponent& e : study.exponents)
    std::printf("  %s %s, %d process%s: time ~ fibres^%.2f, peak memory ~ fibres^%.2f (%d sizes)\n",
                e.solver.c_str(), e.method.c_str(), e.processes, e.processes == 1 ? "" : "es",
                e.time, e.memory, e.sizes);
}

/// The scale study runs `fibrecheck solve`, `fibrecheck fem` (under mpiexec) and
/// `fibrecheck-siconos` as processes of their own: this program, and the programs found.
int run_scale(const StudyArguments& args) {
  ScaleStudyOptions o = args.scale;
  // An empty list on the command line ('' or 0) means none.
  auto sizes = [](std::vector<int> list) {
    list.erase(std::remove(list.begin(), list.end(), 0), list.end());
    return list;
  };
  o.reference_fibres = sizes(o.reference_fibres);
  o.peer_fibres = sizes(o.peer_fibres);
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
    print(study);
    std::cout << "study written to " << args.out << "\n";
  }
  return kExitConverged;
}

void print(const std::vector<FrictionPoint>& points) {
  std::printf("%7s %5s %6s %4s %-8s %-15s %-13s %10s %8s %10s %10s\n", "fibres", "F", "Vf", "mu",
              "friction", "status", "criterion", "iterations", "time_s", "stick_mm", "p_MPa");
  for (const FrictionPoint& p : points)
    std::printf("%7d %5.2f %6.3f %4.2f %-8s %-15s %-13s %10ld %8.2f %10.2e %10.3e\n", p.fibres,
                p.compaction, p.fibre_volume_fraction, p.mu, p.model.c_str(), p.status.c_str(),
                p.criterion.c_str(), p.iterations, p.time_s, p.stick_residual, p.pressure);
}

/// The friction study generates its tows and needs the iterative solver alone.
int run_friction(const StudyArguments& args) {
  FrictionStudyOptions o = args.friction;
  o.quiet = args.quiet;
  const std::vector<FrictionPoint> points =
      run_friction_study(o, make_solvers(true, progress_every(args)).iterative, args.out);
  if (!args.quiet) {
    print(points);
    std::cout << "study written to " << args.out << "\n";
  }
  return kExitConverged;
}

const std::map<std::string, std::function<int(const StudyArguments&)>>& studies() {
  static const std::map<std::string, std::function<int(const StudyArguments&)>> all = {
      {"slices", run_slices},         {"tolerance", run_tolerance}, {"stability", run_stability},
      {"compaction", run_compaction}, {"scale", run_scale},         {"friction", run_friction}};
  return all;
}

/// --quiet, and how often a long iterative run prints where it stands.
void add_quiet_and_progress(CLI::App* s, StudyArguments& args) {
  s->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  s->add_option("--progress", args.progress_every_s,
                "Seconds between the lines a long iterative run prints (its step, iteration and "
                "residuals; 0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

/// The options every study on scene files has (and the cap on its iterative runs, where it has
/// one); the sub-command names the study it runs.
void add_common_options(CLI::App* s, StudyArguments& args, long* max_iterations = nullptr) {
  s->add_option("scenes", args.scenes, "Scene files (JSON)")->required();
  s->add_option("--out", args.out, "Folder of the study's data")->required();
  if (max_iterations)
    s->add_option("--max-iterations", *max_iterations, "Cap on each iterative run")
        ->check(CLI::PositiveNumber);
  add_quiet_and_progress(s, args);
  s->callback([&args, s] { args.study = s->get_name(); });
}

void add_slices(CLI::App& study, StudyArguments& args) {
  CLI::App* slices = study.add_subcommand(
      "slices", "Error of the iterative method against the continuous reference per slice count");
  add_common_options(slices, args);
  slices->add_option("--slices", args.slices.slices, "Slice counts, e.g. 2,4,8,16")->delimiter(',');
}

void add_tolerance(CLI::App& study, StudyArguments& args) {
  ToleranceStudyOptions& o = args.tolerance;
  CLI::App* tolerance = study.add_subcommand(
      "tolerance",
      "Error against run time for every rule and the reference; speed-up at equal error");
  add_common_options(tolerance, args, &o.max_iterations);
  tolerance
      ->add_option("--tolerances", o.tolerances,
                   "Overlap tolerances t_d as multiples of the smallest radius")
      ->delimiter(',');
  tolerance
      ->add_option("--force-tolerances", o.force_tolerances,
                   "Runs of the default rule stopped by their force estimate at these relative "
                   "force tolerances (empty: none)")
      ->delimiter(',');
  tolerance
      ->add_option("--seed-fractions", o.seed_fractions,
                   "The seed rule's c as fractions of its stable limit")
      ->delimiter(',');
  tolerance->add_option("--refinements", o.refinements, "The reference's refinements K")
      ->delimiter(',');
  tolerance->add_flag("--against-slices", o.against_slices,
                      "Measure against the reference on the scene's own slices (the solution "
                      "method alone; for tows whose continuous reference is out of reach)");
}

void add_stability(CLI::App& study, StudyArguments& args) {
  StabilityStudyOptions& o = args.stability;
  CLI::App* stability = study.add_subcommand(
      "stability", "The seed rule's step c against its stable limit; stiffness contrasts");
  add_common_options(stability, args, &o.max_iterations);
  stability->add_option("--fractions", o.fractions, "c as fractions of the stable limit")
      ->delimiter(',');
  stability
      ->add_option("--stiffness-ratios", o.stiffness_ratios,
                   "Young's modulus of every second fibre times these")
      ->delimiter(',');
}

void add_compaction(CLI::App& study, StudyArguments& args) {
  CompactionStudyOptions& o = args.compaction;
  CLI::App* compaction = study.add_subcommand(
      "compaction",
      "Pressure against fibre volume fraction along each scene's load path, both solvers, with "
      "and without friction; van Wyk and Toll fits");
  add_common_options(compaction, args);
  compaction
      ->add_option("--steps", o.steps,
                   "For scenes without steps: this many compaction steps (0: such scenes are "
                   "refused)")
      ->check(CLI::NonNegativeNumber);
  compaction
      ->add_option("--final-compaction", o.final_compaction,
                   "The last step's compaction factor F for --steps")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  compaction
      ->add_option("--sections", o.sections,
                   "Steps whose state is kept for cross-section pictures (the last always is)")
      ->delimiter(',');
  compaction
      ->add_option("--reference-fibres", o.reference_fibres,
                   "The reference only on scenes of at most this many fibres (0: on every scene)")
      ->check(CLI::NonNegativeNumber);
  compaction
      ->add_option("--frictional-reference-fibres", o.frictional_reference_fibres,
                   "The reference with friction only on scenes of at most this many fibres (0: "
                   "on every scene)")
      ->check(CLI::NonNegativeNumber);
}

void add_scale(CLI::App& study, StudyArguments& args) {
  ScaleStudyOptions& o = args.scale;
  CLI::App* scale = study.add_subcommand(
      "scale",
      "Time, iterations and peak memory against the number of fibres on generated tows: each "
      "rule, the reference (under mpiexec) and Siconos on the reference's problem");
  scale->add_option("--out", args.out, "Folder of the study's data")->required();
  scale->add_option("--fibres", o.fibres, "Tow sizes for the iterative rules (default 100,1000)")
      ->delimiter(',');
  scale->add_option("--seed-c", o.seed_c, "The seed rule's step c in N/mm")
      ->check(CLI::PositiveNumber);
  scale->add_option("--slices", o.slices, "Slices of the generated tows (default 100)")
      ->check(CLI::Range(1, 100000));
  scale->add_option("--seed", o.seed, "Seed of the generated tows (default 3)");
  scale
      ->add_option("--rules", o.rules,
                   "Iterative rules (default auto,accelerated; seed needs --seed-c)")
      ->delimiter(',')
      ->check(CLI::IsMember(update_rule_names()));
  scale
      ->add_option("--reference-fibres", o.reference_fibres,
                   "Sizes the reference runs at (default 100; none: --reference-fibres 0)")
      ->delimiter(',')
      ->expected(0, -1);
  scale->add_option("--processes", o.processes, "MPI processes of the reference (default 2)")
      ->check(CLI::Range(1, 1024));
  scale
      ->add_option("--peer-fibres", o.peer_fibres,
                   "Sizes whose reference problem Siconos solves again (default 100; none: 0)")
      ->delimiter(',')
      ->expected(0, -1);
  scale
      ->add_option("--peer-solvers", o.peer_solvers,
                   "Siconos solvers of the frictionless problem: lemke (the default), pgs, newton")
      ->delimiter(',')
      ->check(CLI::IsMember({"lemke", "pgs", "newton"}));
  scale->add_flag("--quiet,-q", args.quiet, "Print nothing but errors");
  scale->callback([&args, scale] { args.study = scale->get_name(); });
}

void add_friction(CLI::App& study, StudyArguments& args) {
  FrictionStudyOptions& o = args.friction;
  CLI::App* friction = study.add_subcommand(
      "friction",
      "Where the seed's friction rule converges and where it stalls, against Coulomb friction: "
      "generated tows compacted in one step, over mu and the compaction factor");
  friction->add_option("--out", args.out, "Folder of the study's data")->required();
  friction->add_option("--fibres", o.fibres, "Tow sizes (default 19,100)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1000000));
  friction->add_option("--mu", o.mu, "Friction coefficients (default 0.1,0.2,0.4)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  friction
      ->add_option("--compactions", o.compactions,
                   "Compaction factors F of the cross-section (default 0.9,0.8,0.7)")
      ->delimiter(',')
      ->check(CLI::Range(1e-6, 1.0));
  friction->add_option("--slices", o.slices, "Slices of the generated tows (default 100)")
      ->check(CLI::Range(1, 100000));
  friction->add_option("--seed", o.seed, "Seed of the generated tows (default 2)");
  friction
      ->add_option("--volume-fraction", o.volume_fraction,
                   "Fibre volume fraction before compaction (default 0.35)")
      ->check(CLI::Range(1e-3, 0.9));
  friction->add_option("--max-iterations", o.max_iterations, "Cap on each run (default 100000)")
      ->check(CLI::PositiveNumber);
  add_quiet_and_progress(friction, args);
  friction->callback([&args, friction] { args.study = friction->get_name(); });
}

}  // namespace

int run_study(const StudyArguments& args) {
  const auto study = studies().find(args.study);
  if (study == studies().end())
    throw InputError("command line", "study", "no study '" + args.study + "': " + kStudyNames);
  return study->second(args);
}

CLI::App* add_study_command(CLI::App& app, StudyArguments& args) {
  CLI::App* study = app.add_subcommand("study", "Studies of accuracy, cost and stability");
  study->require_subcommand(0, 1);
  study->callback([study] {
    const std::vector<std::string> words = study->remaining();
    if (!study->get_subcommands().empty()) {
      if (!words.empty()) throw CLI::ExtrasError(words);
      return;
    }
    if (words.empty()) throw CLI::RequiredError("A subcommand");
    throw CLI::ValidationError("study", "no study '" + words.front() + "': " + kStudyNames);
  });
  add_slices(*study, args);
  add_tolerance(*study, args);
  add_stability(*study, args);
  add_compaction(*study, args);
  add_scale(*study, args);
  add_friction(*study, args);
  // A word that names no study is kept, not refused as a stray argument, so that the refusal can
  // name it. Set after the studies are added: they keep refusing what they do not know.
  study->allow_extras();
  return study;
}

}  // namespace fibrecheck
