// fibrecheck-siconos: an outside solver for the reference's contact problems.
//
//   fibrecheck fem scenes/two_fibres_crossing.json --export-contact-problem crossing.problem.json
//   fibrecheck-siconos crossing.problem.json --out crossing.siconos.json
//
// Reads a problem written by `fibrecheck fem --export-contact-problem` (compliance W with its
// tangential blocks, free overlaps and slips q, μ, and the reference's answer), solves it with
// Siconos' numerics library — Lemke, projected Gauss–Seidel and Newton for the frictionless LCP;
// nonsmooth Gauss–Seidel and the Alart–Curnier Newton method for Coulomb friction in 2-D and 3-D —
// and compares each answer with the reference's where the answer is unique. Siconos is handed the
// problem scaled to order one (--unscaled: as exported). An answer counts as converged only when
// its own residual says it solves the problem (--residual-tolerance), whatever Siconos' return code
// says; both are reported. It is its own small program: Siconos links the sequential MUMPS, the
// reference the parallel one through PETSc.
//
// Exit codes: 0 every answer solves the problem (and agreed, with --agreement), 2 bad input,
// 3 an answer does not solve it or disagreed.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.h"
#include "blas_threads.h"
#include "contact_problem.h"
#include "contact_problem_check.h"
#include "input_error.h"
#include "siconos_solvers.h"

namespace {

using fibrecheck::ContactProblem;
using fibrecheck::PeerAnswer;
using nlohmann::json;

json answer_json(const ContactProblem& p, const PeerAnswer& a) {
  json j = {
      {"solver", a.solver},
      {"siconos_solver", a.siconos_solver},
      {"dimension", a.dimension},
      {"scaled", a.scaled},
      {"converged", a.converged},
      {"info", a.info},
      {"siconos_says_converged", a.info == 0},
      {"iterations", a.iterations},
      {"error", a.error},
      {"time_s", a.time_s},
      {"residual",
       {{"overlap_mm", a.residual.overlap_mm},
        {"slip_mm", a.residual.slip_mm},
        {"excluded_N", a.residual.excluded_N},
        {"relative", a.relative_residual}}},
      {"reaction", std::vector<double>(a.reaction.data(), a.reaction.data() + a.reaction.size())}};
  if (p.reaction.size() == a.reaction.size()) {
    const fibrecheck::ProblemAgreement g = fibrecheck::compare_answers(p, p.reaction, a.reaction);
    j["against_reference"] = {{"normal_N", g.normal_N},
                              {"friction_N", g.friction_N},
                              {"w_mm", g.w_mm},
                              {"normal_scale_N", g.normal_scale_N},
                              {"w_scale_mm", g.w_scale_mm},
                              {"relative", g.relative()},
                              {"contacts", g.contacts},
                              {"frictions_compared", g.frictions_compared},
                              {"frictions_not_unique", g.frictions_not_unique}};
  }
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fibrecheck-siconos: a contact problem of the reference, solved by Siconos"};
  std::string problem_file, out;
  std::vector<std::string> solvers;
  fibrecheck::PeerSettings settings;
  double agreement = 0.0;
  int threads = 0;
  bool quiet = false, unscaled = false;
  app.add_option("problem", problem_file, "Problem file (fibrecheck fem --export-contact-problem)")
      ->required();
  app.add_option("--out", out, "Answers (JSON): each solver's reaction, figures and agreement");
  app.add_option("--solvers", solvers,
                 "Solvers to run (default: every one that takes the problem): lemke, pgs, newton "
                 "for mu = 0; nsgs, newton (and lemke in 2-D) with friction")
      ->delimiter(',');
  app.add_option("--tolerance", settings.tolerance,
                 "Siconos' own relative error to reach (default 1e-12)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-iterations", settings.max_iterations,
                 "Iterations per solver (default 100000)")
      ->check(CLI::PositiveNumber);
  app.add_option("--residual-tolerance", settings.residual_tolerance,
                 "An answer converged when its residual (overlap and slip left by the natural "
                 "map, mm) is within this of the largest |q| (default 1e-9)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--unscaled", unscaled,
               "Hand Siconos the problem as exported instead of scaled to order one");
  app.add_option("--agreement", agreement,
                 "Fail (exit 3) unless every answer agrees with the reference's within this, "
                 "relative (forces to the largest normal force, overlaps and slips to the largest "
                 "|q|)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--blas-threads", threads, "OpenBLAS threads (default: OpenBLAS' own choice)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--quiet,-q", quiet, "Print nothing but errors");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (threads > 0) fibrecheck::set_blas_threads(threads);
  settings.scaled = !unscaled;
  try {
    const ContactProblem p = fibrecheck::read_contact_problem(problem_file);
    if (solvers.empty()) solvers = fibrecheck::applicable_solvers(p);
    const std::vector<std::string> known = fibrecheck::applicable_solvers(p);
    for (const std::string& s : solvers) {
      if (std::find(known.begin(), known.end(), s) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        throw fibrecheck::InputError("command line", "--solvers",
                                     "\"" + s + "\" does not take this problem (" +
                                         (p.mu > 0.0 ? "friction" : "mu = 0") + "): use " + list);
      }
    }
    if (!out.empty()) fibrecheck::create_parent_folder(out);
    std::size_t excluded = 0;
    for (const auto& c : p.contacts) excluded += c.excluded ? 1 : 0;
    if (!quiet)
      std::cout << "problem " << problem_file << ": scene " << p.scene << ", step " << p.step
                << ", " << p.contacts.size() << " contacts (" << excluded << " excluded), "
                << p.offset.back() << " unknowns, mu = " << p.mu << ", OpenBLAS threads "
                << fibrecheck::blas_threads() << "; " << (settings.scaled ? "scaled" : "unscaled")
                << ", an answer converges when its residual is within "
                << settings.residual_tolerance << " of max|q| = "
                << fibrecheck::residual_scale(p) << " mm\n";
    json answers = json::array();
    bool all_good = true;
    for (const std::string& s : solvers) {
      const PeerAnswer a = fibrecheck::solve_with_siconos(p, s, settings);
      json j = answer_json(p, a);
      const bool agrees = !(agreement > 0.0) || !j.contains("against_reference") ||
                          j["against_reference"]["relative"].get<double>() <= agreement;
      all_good &= a.converged && agrees;
      if (!quiet) {
        std::ostringstream line;
        line << std::setprecision(3) << "  " << std::left << std::setw(7) << s << " "
             << std::setw(30) << a.siconos_solver
             << (a.converged ? "converged" : "NOT converged") << ", residual "
             << a.residual.overlap_mm << " mm overlap, " << a.residual.slip_mm << " mm slip ("
             << a.relative_residual << " of max|q|), Siconos info " << a.info
             << (a.info == 0 ? " (it says converged)" : " (it says not converged)") << ", "
             << a.iterations << " iterations, error " << a.error << ", " << a.time_s << " s";
        if (j.contains("against_reference"))
          line << "; against the reference " << j["against_reference"]["relative"].get<double>()
               << (agrees ? "" : " (above --agreement)");
        std::cout << line.str() << "\n";
      }
      answers.push_back(std::move(j));
    }
    if (!out.empty()) {
      json j = {{"problem", problem_file},
                {"scene", p.scene},
                {"step", p.step},
                {"mu", p.mu},
                {"contacts", p.contacts.size()},
                {"unknowns", p.offset.back()},
                {"scaled", settings.scaled},
                {"residual_tolerance", settings.residual_tolerance},
                {"residual_scale_mm", fibrecheck::residual_scale(p)},
                {"blas_threads", fibrecheck::blas_threads()},
                {"answers", answers}};
      fibrecheck::write_file_atomically(out, j.dump(1) + "\n");
    }
    return all_good ? 0 : 3;
  } catch (const fibrecheck::InputError& e) {
    std::cerr << "fibrecheck-siconos: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fibrecheck-siconos: error: " << e.what() << "\n";
    return 1;
  }
}
