#include "reference_solver.h"

#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>

#include "beam_model.h"
#include "contact_detection.h"
#include "contact_results.h"
#include "fibre.h"
#include "fibre_mesh.h"
#include "superposition.h"

namespace fibrecheck {

namespace {

/// The contact problem P ≥ 0, d = d0 − W·P ≤ 0, P·d = 0 is the quadratic programme
/// min ½PᵀWP − Pᵀd0 over P ≥ 0. Solved exactly by an active-set method in the manner of
/// Lawson–Hanson's non-negative least squares: add the contact with the largest remaining overlap
/// to the set of pushing contacts, solve W_SS·P_S = d0_S, step back to feasibility when a force
/// would turn negative, and repeat until no overlap above `tolerance` is left. It terminates in a
/// finite number of steps for positive definite W (no cycling, unlike the plain primal–dual
/// active set on a dense W).
bool active_set_solve(const Eigen::MatrixXd& W, const Eigen::VectorXd& d0, double tolerance,
                      int max_iterations, Eigen::VectorXd& P, int& iterations) {
  const Eigen::Index n = d0.size();
  P = Eigen::VectorXd::Zero(n);
  iterations = 0;
  if (n == 0) return true;
  std::vector<char> pushing(n, 0);
  auto solve_on_set = [&](Eigen::VectorXd& z) {
    std::vector<Eigen::Index> index;
    for (Eigen::Index k = 0; k < n; ++k)
      if (pushing[k]) index.push_back(k);
    z = Eigen::VectorXd::Zero(n);
    const Eigen::Index m = static_cast<Eigen::Index>(index.size());
    if (m == 0) return;
    Eigen::MatrixXd Wss(m, m);
    Eigen::VectorXd ds(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      ds[i] = d0[index[i]];
      for (Eigen::Index j = 0; j < m; ++j) Wss(i, j) = W(index[i], index[j]);
    }
    const Eigen::VectorXd zs = Wss.ldlt().solve(ds);
    for (Eigen::Index i = 0; i < m; ++i) z[index[i]] = zs[i];
  };
  Eigen::VectorXd z;
  for (iterations = 1; iterations <= max_iterations; ++iterations) {
    const Eigen::VectorXd d = d0 - W * P;
    Eigen::Index j = -1;
    double worst = tolerance;
    for (Eigen::Index k = 0; k < n; ++k)
      if (!pushing[k] && d[k] > worst) worst = d[k], j = k;
    if (j < 0) return true;
    pushing[j] = 1;
    solve_on_set(z);
    for (int inner = 0; inner < n + 1; ++inner) {
      double alpha = 1.0;
      bool blocked = false;
      for (Eigen::Index k = 0; k < n; ++k)
        if (pushing[k] && z[k] <= 0.0) {
          blocked = true;
          alpha = std::min(alpha, P[k] / (P[k] - z[k]));
        }
      if (!blocked) break;
      P += alpha * (z - P);
      for (Eigen::Index k = 0; k < n; ++k)
        if (pushing[k] && P[k] <= 1e-300) pushing[k] = 0, P[k] = 0.0;
      solve_on_set(z);
    }
    P = z.cwiseMax(0.0);
  }
  return false;
}

std::string temporary_mesh_path() {
  return (std::filesystem::temp_directory_path() /
          ("fibrecheck_reference_" + std::to_string(getpid()) + ".msh"))
      .string();
}

}  // namespace

Result solve_reference(const Scene& scene, const ReferenceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Fibre> fibres;
  double smallest_radius = INFINITY;
  for (const FibreSpec& spec : scene.fibres) {
    fibres.push_back(make_fibre(spec, scene.contact.axis, scene.contact.parallel_angle_deg));
    smallest_radius = std::min(smallest_radius, spec.radius);
  }
  const double tolerance = scene.overlap_tolerance();
  Superposition superposition(fibres, scene);  // contact geometry of the deformed fibres only
  ContactDetector detector(fibres, scene, 0.1 * smallest_radius);
  const int samples = scene.output.samples;
  std::vector<double> sample_s(samples);
  for (int j = 0; j < samples; ++j) sample_s[j] = static_cast<double>(j) / (samples - 1);

  std::vector<Contact> contacts;
  std::vector<Eigen::Vector3d> force_on_a, u_a, u_b;
  auto gather = [&] {
    force_on_a.resize(contacts.size());
    for (std::size_t k = 0; k < contacts.size(); ++k) force_on_a[k] = contacts[k].force_on_a();
  };
  // Candidates on the fibres deformed by the current forces; pushing contacts keep their state.
  auto detect = [&] {
    superposition.attach(contacts);
    gather();
    std::vector<std::vector<Eigen::Vector3d>> grid(fibres.size());
    for (std::size_t f = 0; f < fibres.size(); ++f)
      superposition.fibre_field(static_cast<int>(f), contacts, force_on_a, true, detector.grid(),
                                grid[f]);
    std::vector<Contact> found = detector.detect(grid);
    std::map<std::uint64_t, const Contact*> previous;
    for (const Contact& c : contacts) previous[c.key()] = &c;
    for (Contact& c : found) {
      auto it = previous.find(c.key());
      if (it == previous.end()) continue;
      c.force = it->second->force;
      previous.erase(it);
    }
    for (const auto& [key, c] : previous)
      if (c->force > 0.0) found.push_back(*c);
    contacts = std::move(found);
  };

  Result r;
  r.scene = scene.name;
  r.solver = "fem";
  r.rule = "active_set";
  r.status = "max_iterations";
  r.criterion = "max_iterations";
  detect();
  std::set<std::pair<std::uint64_t, long long>> last_state;
  int outer = 0, active_set_iterations = 0;
  const std::string mesh = temporary_mesh_path();
  std::unique_ptr<BeamModel> model;
  for (outer = 1; outer <= options.max_outer_iterations; ++outer) {
    // make_grid: nodes at every contact and sample position.
    MeshOptions mesh_options;
    mesh_options.contact_stations.assign(fibres.size(), {});
    mesh_options.sample_stations.assign(fibres.size(), sample_s);
    for (const Contact& c : contacts) {
      mesh_options.contact_stations[c.a].push_back(c.s_a);
      if (c.kind != ContactKind::wall) mesh_options.contact_stations[c.b].push_back(c.s_b);
    }
    write_mesh(scene, mesh_options, mesh);
    model = std::make_unique<BeamModel>(scene, mesh);

    // The overlaps under the external loads alone, along each contact's normal.
    model->run({}, true);
    const Eigen::Index n = static_cast<Eigen::Index>(contacts.size());
    Eigen::VectorXd d0(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const Contact& c = contacts[k];
      const Eigen::Vector3d no_displacement = Eigen::Vector3d::Zero();
      d0[k] = detector.overlap_along_normal(
          c, model->displacement(c.a, c.s_a),
          c.kind == ContactKind::wall ? no_displacement : model->displacement(c.b, c.s_b));
    }

    // W column by column: the overlap each unit force pair removes at every contact.
    Eigen::MatrixXd W(n, n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const Contact& c = contacts[k];
      std::vector<NodalForce> pair = {
          {c.a, c.s_a, (c.kind == ContactKind::wall ? 1.0 : -1.0) * c.normal}};
      if (c.kind != ContactKind::wall) pair.push_back({c.b, c.s_b, c.normal});
      model->run(pair, false);
      for (Eigen::Index j = 0; j < n; ++j) {
        const Contact& cj = contacts[j];
        const Eigen::Vector3d ua = model->displacement(cj.a, cj.s_a);
        W(j, k) = cj.kind == ContactKind::wall
                      ? cj.normal.dot(ua)
                      : cj.normal.dot(model->displacement(cj.b, cj.s_b) - ua);
      }
    }
    Eigen::VectorXd P;
    int iterations = 0;
    const bool solved =
        active_set_solve(W, d0, 1e-6 * tolerance, options.max_active_set_iterations, P, iterations);
    active_set_iterations += iterations;
    for (Eigen::Index k = 0; k < n; ++k) contacts[k].force = P[k];
    if (!solved) break;

    // update_active_set: re-detect on the deformed fibres; stop when nothing moved.
    std::set<std::pair<std::uint64_t, long long>> state;
    for (const Contact& c : contacts)
      if (c.force > 0.0) state.insert({c.key(), std::llround(c.s_a * 1e9)});
    if (state == last_state) {
      r.status = "converged";
      r.criterion = "active_set";
      break;
    }
    last_state = state;
    detect();
  }
  std::filesystem::remove(mesh);

  // output_results: the final state from the finite elements.
  gather();
  std::vector<NodalForce> forces;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (!(c.force > 0.0)) continue;
    forces.push_back({c.a, c.s_a, force_on_a[k]});
    if (c.kind != ContactKind::wall) forces.push_back({c.b, c.s_b, -force_on_a[k]});
  }
  if (model) model->run(forces, true);
  u_a.assign(contacts.size(), Eigen::Vector3d::Zero());
  u_b.assign(contacts.size(), Eigen::Vector3d::Zero());
  r.max_overlap = contacts.empty() ? 0.0 : -INFINITY;
  for (std::size_t k = 0; k < contacts.size() && model; ++k) {
    Contact& c = contacts[k];
    u_a[k] = model->displacement(c.a, c.s_a);
    if (c.kind != ContactKind::wall) u_b[k] = model->displacement(c.b, c.s_b);
    const double d = detector.overlap_along_normal(c, u_a[k], u_b[k]);
    c.overlap = d;
    r.max_overlap = std::max(r.max_overlap, d);
    if (c.force > 0.0) r.gap_force_residual = std::max(r.gap_force_residual, -d);
  }
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    FibreResult fr;
    fr.id = fibres[f].id;
    for (double s : sample_s)
      fr.displacement.push_back(model ? model->displacement(static_cast<int>(f), s)
                                      : Eigen::Vector3d::Zero());
    r.fibres.push_back(std::move(fr));
  }
  r.contacts = contact_results(contacts, fibres, detector, force_on_a, u_a, u_b);
  r.walls = wall_results(contacts, fibres, detector.wall_specs());
  // Energies of the same loads by the beam formulas, which the elements reproduce at the nodes.
  superposition.attach(contacts);
  std::vector<Eigen::Vector3d> ua, ub;
  superposition.contact_displacements(contacts, force_on_a, true, ua, ub, &r.strain_energy_exact);
  r.strain_energy = superposition.trapezium_energy(contacts, force_on_a, scene.contact.slices);
  r.iterations = std::min(outer, options.max_outer_iterations);
  r.stages = {"gmsh_mesh", "fem_beams", "active_set"};
  if (detector.point_search()) r.stages.push_back("point_contacts");
  if (detector.slicing()) r.stages.push_back("slices");
  if (detector.walls()) r.stages.push_back("walls");
  if (scene.contact.friction > 0.0) {
    r.stages.push_back("friction_not_modelled");
    r.warnings.push_back("the reference model is frictionless; contact.friction was ignored");
  }
  if (r.status == "converged" && r.max_overlap > tolerance)
    r.warnings.push_back("overlap above the tolerance remains");
  r.message = "active-set iterations: " + std::to_string(active_set_iterations) +
              "; unknowns: " + std::to_string(model ? model->unknowns() : 0);
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace fibrecheck
