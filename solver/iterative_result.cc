#include "iterative_result.h"

#include "contact_results.h"
#include "deformed_test.h"
#include "validity.h"

namespace fibrecheck {

namespace {

std::vector<std::string> stages(const Scene& scene, const SolverOptions& options,
                                const ContactDetector& detector) {
  std::vector<std::string> list = {"superposition"};
  if (detector.broad_phase()) list.push_back("broad_phase");
  if (detector.point_search()) list.push_back("point_contacts");
  if (detector.slicing()) list.push_back("slices");
  if (detector.walls()) list.push_back("walls");
  if (scene.contact.friction > 0.0)
    list.push_back(std::string("friction_") + to_string(scene.contact.friction_model));
  if (options.energy_tolerance > 0.0) list.push_back("energy_criterion");
  list.push_back(std::string("update_") + to_string(options.rule));
  return list;
}

}  // namespace

Result iterative_result(const Scene& scene, const SolverOptions& options,
                        const std::vector<Fibre>& fibres, const Superposition& superposition,
                        const ContactDetector& detector, IterationState& state,
                        const IterationRecord& record) {
  Result r;
  r.scene = scene.name;
  r.solver = "iterative";
  r.rule = to_string(options.rule);
  state.gather_forces();
  r.strain_energy = superposition.trapezium_energy(state.force_on_a, scene.contact.slices);
  superposition.contact_displacements(state.contacts, state.force_on_a, true, state.u_a, state.u_b,
                                      &r.strain_energy_exact);
  r.max_overlap = record.residuals.max_overlap;
  r.gap_force_residual = record.residuals.gap_force;
  r.c = record.step;
  r.c_stable_limit = record.lambda_max > 0.0 ? 2.0 / record.lambda_max : 0.0;
  r.axial_load_dropped = superposition.axial_load_dropped(state.contacts, state.force_on_a);
  r.candidates = static_cast<long>(state.contacts.size());
  r.warnings = record.warnings;
  const double mu = scene.contact.friction;
  if (mu > 0.0) {
    detector.geometry().measure(state.contacts, state.u_a, state.u_b, true);
    r.friction = friction_figures(state.contacts, mu, scene.contact.friction_model);
    r.friction->fixed_point_updates = record.tresca_updates;
  }
  r.stages = stages(scene, options, detector);

  const int samples = scene.output.samples;
  std::vector<double> s(samples);
  for (int j = 0; j < samples; ++j) s[j] = static_cast<double>(j) / (samples - 1);
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    FibreResult fr;
    fr.id = fibres[f].id;
    superposition.fibre_field(static_cast<int>(f), state.force_on_a, true, s, fr.displacement,
                              &fr.moment);
    r.fibres.push_back(std::move(fr));
  }
  r.contacts = contact_results(state.contacts, fibres, scene.walls, state.force_on_a, state.u_a,
                               state.u_b, mu);
  r.walls = wall_results(state.contacts, fibres, scene.walls);
  r.history = record.history;
  r.geometry = to_string(scene.contact.geometry);
  r.geometric_updates = record.geometric_updates;
  r.exact_answers = record.exact_answers;
  r.deformed_test =
      deformed_test(detector, state.contacts, state.u_a, state.u_b,
                    [&](int f, const std::vector<double>& s, std::vector<Eigen::Vector3d>& u) {
                      superposition.fibre_field(f, state.force_on_a, true, s, u);
                    });
  assess_validity(r, fibres);
  r.status = record.termination.status;
  r.criterion = record.termination.criterion;
  r.message = record.termination.message;
  r.iterations = record.iterations;
  warn_where_the_seeds_test_fails(scene.overlap_tolerance(), r);
  return r;
}

}  // namespace fibrecheck
