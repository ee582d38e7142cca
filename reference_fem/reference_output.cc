// output_results: the final state, every number from the finite elements.

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "contact_results.h"
#include "deformed_test.h"
#include "process_sums.h"
#include "reference_solver_class.h"

namespace fibrecheck {

// output_results: the beams solved once more under the final contact forces; from that solution
// the displacements and moments at the samples, each contact's overlap and slip, the contacts'
// and walls' forces, and the energies.
void ReferenceSolver::output_results(Result& r) {
  dealii::TimerOutput::Scope scope(timer_, "output_results");
  gather_forces();
  const FinalFields fields = final_fields();
  r.finite_elements.emplace();
  std::vector<Eigen::Vector3d> u_a, u_b;
  measure_contacts(fields.stations, r, u_a, u_b);
  const std::size_t samples = sample_s_.size();
  for (std::size_t f = 0; f < fibres_.size(); ++f) {
    FibreResult fr;
    fr.id = fibres_[f].id;
    for (std::size_t j = 0; j < samples; ++j) {
      const std::size_t at = f * samples + j;
      fr.displacement.emplace_back(fields.displacement[3 * at], fields.displacement[3 * at + 1],
                                   fields.displacement[3 * at + 2]);
      fr.moment.emplace_back(fields.moment[2 * at], fields.moment[2 * at + 1]);
    }
    r.fibres.push_back(std::move(fr));
  }
  r.contacts = contact_results(contacts_, fibres_, scene_.walls, force_on_a_, u_a, u_b, mu_);
  if (mu_ > 0.0) {
    r.friction = friction_figures(contacts_, mu_, FrictionModel::coulomb);
    r.friction->fixed_point_updates = tresca_updates_;
    end_state_ = SlipOrigins(contacts_, u_a, u_b, r);
  }
  r.walls = wall_results(contacts_, fibres_, scene_.walls);
  r.geometry = to_string(scene_.contact.geometry);
  r.geometric_updates = geometric_updates_;
  // The seed's test on the final state; a crossing found off the deformed closest points is
  // measured there, moved by the change of the fibres' displacements at the detection grid,
  // interpolated.
  const std::vector<double>& grid = detector_.grid();
  r.deformed_test = deformed_test(
      detector_, contacts_, u_a, u_b,
      [&](int f, const std::vector<double>& s, std::vector<Eigen::Vector3d>& u) {
        u.resize(s.size());
        const int m = static_cast<int>(grid.size()) - 1;
        for (std::size_t i = 0; i < s.size(); ++i) {
          const int j = std::min(std::max(static_cast<int>(std::floor(s[i] * m)), 0), m - 1);
          const double w = s[i] * m - j;
          u[i] = (1.0 - w) * grid_u_[f][j] + w * grid_u_[f][j + 1];
        }
      });
  warn_where_the_seeds_test_fails(scene_.overlap_tolerance(), r);
  add_energies(r);
}

// The beams under the scene's loads and the final contact forces, and their displacements at
// every contact station and sample and their moments at the samples, summed over the processes.
// A non-finite number left here becomes a zero and the status `diverged` in solve_reference
// (replace_non_finite), as for the iterative solver.
ReferenceSolver::FinalFields ReferenceSolver::final_fields() {
  const std::size_t samples = sample_s_.size();
  FinalFields fields;
  fields.stations.assign(3 * offset_.back(), 0.0);
  fields.displacement.assign(3 * samples * fibres_.size(), 0.0);
  fields.moment.assign(2 * samples * fibres_.size(), 0.0);
  if (model_) {
    model_->run(nodal_forces(), true);
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      for (std::size_t i = 0; i < stations_[f].size(); ++i) {
        const Eigen::Vector3d x = model_->displacement(static_cast<int>(f), stations_[f][i]);
        for (int d = 0; d < 3; ++d) fields.stations[3 * (offset_[f] + i) + d] = x[d];
      }
      for (std::size_t j = 0; j < samples; ++j) {
        const Eigen::Vector3d x = model_->displacement(static_cast<int>(f), sample_s_[j]);
        for (int d = 0; d < 3; ++d) fields.displacement[3 * (f * samples + j) + d] = x[d];
        const Eigen::Vector2d M = model_->moment(static_cast<int>(f), sample_s_[j]);
        for (int d = 0; d < 2; ++d) fields.moment[2 * (f * samples + j) + d] = M[d];
      }
    }
    if (!options_.vtu.empty()) write_vtu();
  }
  sum_over_processes(fields.stations, comm_);
  sum_over_processes(fields.displacement, comm_);
  sum_over_processes(fields.moment, comm_);
  return fields;
}

// The beams' solution as a ParaView file: with several processes one piece per process, and a
// record that collects them (written by the first).
void ReferenceSolver::write_vtu() const {
  if (processes_ == 1) {
    model_->write_vtu(options_.vtu);
    return;
  }
  const std::filesystem::path path(options_.vtu);
  const auto piece = [&](unsigned int p) {
    return path.stem().string() + "." + std::to_string(p) + ".vtu";
  };
  std::vector<std::string> pieces;
  for (unsigned int p = 0; p < processes_ && p < fibres_.size(); ++p) pieces.push_back(piece(p));
  const std::string record =
      rank_ == 0 ? (path.parent_path() / (path.stem().string() + ".pvtu")).string() : "";
  model_->write_vtu((path.parent_path() / piece(rank_)).string(), record, pieces);
}

// Each contact's overlap (and with friction its slip) in the final state, from the displacements
// `u` at the stations; the sides' displacements go to `u_a`, `u_b`. Sets the largest overlap, the
// largest gap that carries a force and the complementarity residual max |P·d|.
void ReferenceSolver::measure_contacts(const std::vector<double>& u, Result& r,
                                       std::vector<Eigen::Vector3d>& u_a,
                                       std::vector<Eigen::Vector3d>& u_b) {
  FiniteElementFigures& figures = *r.finite_elements;
  u_a.assign(contacts_.size(), Eigen::Vector3d::Zero());
  u_b.assign(contacts_.size(), Eigen::Vector3d::Zero());
  r.max_overlap = contacts_.empty() ? 0.0 : -INFINITY;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    Contact& c = contacts_[k];
    u_a[k] = packed(u, c.a, station_a_[k]);
    if (c.kind != ContactKind::wall) u_b[k] = packed(u, c.b, station_b_[k]);
    c.overlap = detector_.geometry().overlap(c, u_a[k], u_b[k]);
    if (mu_ > 0.0) c.slip = c.tangential(c.relative(u_a[k], u_b[k]) - c.origin);
    r.max_overlap = std::max(r.max_overlap, c.overlap);
    if (c.force > 0.0) r.gap_force_residual = std::max(r.gap_force_residual, -c.overlap);
    figures.complementarity_residual =
        std::max(figures.complementarity_residual, std::fabs(c.force * c.overlap));
  }
}

// The energies and the dropped axial load, from this process's elements, summed: Eq. 4.34 by the
// trapezium rule on the finite-element moments at the slice spacing (as the iterative solver),
// ½ΣP·v from the finite-element displacements, and ∫M²/2EI over the elements (N·mm; N).
void ReferenceSolver::add_energies(Result& r) {
  std::vector<double> sums(4, 0.0);
  if (model_) {
    const int n = scene_.contact.slices;
    for (std::size_t f = 0; f < fibres_.size(); ++f) {
      if (!owned_[f]) continue;
      double sum = 0.0;
      for (int j = 0; j <= n; ++j) {
        const double weight = (j == 0 || j == n) ? 0.5 : 1.0;
        sum +=
            weight * model_->moment(static_cast<int>(f), static_cast<double>(j) / n).squaredNorm();
      }
      sums[0] += sum * (fibres_[f].length / n) / (2.0 * fibres_[f].EI);
    }
    sums[1] = model_->load_work();
    sums[2] = model_->strain_energy();
    sums[3] = model_->axial_load_dropped();
  }
  sum_over_processes(sums, comm_);
  r.strain_energy = sums[0];
  r.strain_energy_exact = sums[1];
  r.finite_elements->strain_energy_elements = sums[2];
  r.axial_load_dropped = sums[3];
  r.candidates = static_cast<long>(contacts_.size());
}

}  // namespace fibrecheck
