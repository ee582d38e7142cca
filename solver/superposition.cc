#include "superposition.h"

#include <algorithm>
#include <cmath>

#include "beam.h"

namespace fibrecheck {

namespace {

/// Running sums of both bending planes (beam.h).
struct PlaneSums {
  BeamSums s[2];

  void add_right(const Eigen::Vector2d& p, double b) {
    for (int k = 0; k < 2; ++k) {
      s[k].Sb += p[k] * b;
      s[k].Sb3 += p[k] * b * b * b;
    }
  }
  /// Moves a load from the "a ≥ x" sums to the "a < x" sums.
  void move_left(const Eigen::Vector2d& p, double a, double b) {
    for (int k = 0; k < 2; ++k) {
      s[k].Sb -= p[k] * b;
      s[k].Sb3 -= p[k] * b * b * b;
      s[k].Sa += p[k] * a;
      s[k].Sa3 += p[k] * a * a * a;
    }
  }
};

}  // namespace

Superposition::Superposition(const std::vector<Fibre>& fibres, const Scene& scene)
    : fibres_(fibres),
      point_loads_(fibres.size()),
      distributed_(fibres.size(), Eigen::Vector2d::Zero()),
      external_axial_(fibres.size(), 0.0),
      slots_(fibres.size()) {
  for (const LoadSpec& load : scene.loads) {
    const int i = scene.fibre_index(load.fibre);
    const Fibre& f = fibres_[i];
    const Eigen::Vector2d p(load.force.dot(f.e1), load.force.dot(f.e2));
    if (load.kind == LoadKind::point) {
      point_loads_[i].push_back({load.position * f.length, p});
      external_axial_[i] += std::fabs(load.force.dot(f.t));
    } else {
      distributed_[i] += p;
      external_axial_[i] += std::fabs(load.force.dot(f.t)) * f.length;
    }
  }
  for (std::size_t i = 0; i < fibres_.size(); ++i) {
    for (std::size_t k = 0; k < point_loads_[i].size(); ++k)
      slots_[i].push_back({point_loads_[i][k].a, -1 - static_cast<int>(k), 0});
    std::stable_sort(slots_[i].begin(), slots_[i].end(),
                     [](const Slot& x, const Slot& y) { return x.a < y.a; });
  }
}

void Superposition::attach(const std::vector<Contact>& contacts) {
  for (std::size_t i = 0; i < fibres_.size(); ++i) {
    slots_[i].clear();
    for (std::size_t k = 0; k < point_loads_[i].size(); ++k)
      slots_[i].push_back({point_loads_[i][k].a, -1 - static_cast<int>(k), 0});
  }
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& k = contacts[c];
    slots_[k.a].push_back({k.s_a * fibres_[k.a].length, static_cast<int>(c), +1});
    if (k.kind != ContactKind::wall)
      slots_[k.b].push_back({k.s_b * fibres_[k.b].length, static_cast<int>(c), -1});
  }
  for (auto& list : slots_)
    std::sort(list.begin(), list.end(), [](const Slot& x, const Slot& y) {
      return x.a < y.a || (x.a == y.a && x.contact < y.contact);
    });
}

void Superposition::resort(const std::vector<Contact>& contacts) {
  for (std::size_t i = 0; i < fibres_.size(); ++i) {
    auto& list = slots_[i];
    for (Slot& slot : list) {
      if (slot.contact < 0) continue;
      const Contact& k = contacts[slot.contact];
      slot.a = (slot.sign > 0 ? k.s_a : k.s_b) * fibres_[i].length;
    }
    // Nearly sorted already: insertion sort is O(k) here.
    for (std::size_t j = 1; j < list.size(); ++j)
      for (std::size_t m = j; m > 0 && list[m].a < list[m - 1].a; --m) std::swap(list[m], list[m - 1]);
  }
}

Eigen::Vector2d Superposition::slot_force(int fibre, const Slot& slot,
                                          const std::vector<Contact>& /*contacts*/,
                                          const std::vector<Eigen::Vector3d>& force_on_a) const {
  const Fibre& f = fibres_[fibre];
  const Eigen::Vector3d force = slot.sign * force_on_a[slot.contact];
  return {force.dot(f.e1), force.dot(f.e2)};
}

void Superposition::contact_displacements(const std::vector<Contact>& contacts,
                                          const std::vector<Eigen::Vector3d>& force_on_a,
                                          bool external, std::vector<Eigen::Vector3d>& u_a,
                                          std::vector<Eigen::Vector3d>& u_b,
                                          double* exact_energy) const {
  u_a.resize(contacts.size());
  u_b.resize(contacts.size());
  double energy = 0.0;
  const int n_fibres = static_cast<int>(fibres_.size());
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : energy) if (n_fibres > 64)
  for (int i = 0; i < n_fibres; ++i) {
    const auto& list = slots_[i];
    const Fibre& f = fibres_[i];
    const Eigen::Vector2d q = external ? distributed_[i] : Eigen::Vector2d::Zero();
    if (list.empty() && q.isZero()) continue;
    thread_local std::vector<Eigen::Vector2d> p;
    p.resize(list.size());
    const double L = f.length;
    PlaneSums sums;
    for (std::size_t j = 0; j < list.size(); ++j) {
      const Slot& slot = list[j];
      if (slot.contact >= 0)
        p[j] = slot_force(i, slot, contacts, force_on_a);
      else
        p[j] = external ? point_loads_[i][-1 - slot.contact].p : Eigen::Vector2d::Zero();
      sums.add_right(p[j], L - slot.a);
    }
    double fibre_energy = 0.0;
    Eigen::Vector2d unit_q_work = Eigen::Vector2d::Zero();  // Σ p·v_{q=1}(a) (Maxwell–Betti)
    const double inverse = 1.0 / (6.0 * f.EI * L);
    const bool distributed = !q.isZero();
    std::size_t moved = 0;
    Eigen::Vector2d v = Eigen::Vector2d::Zero();
    double vq = 0.0;
    for (std::size_t j = 0; j < list.size(); ++j) {
      const double x = list[j].a;
      // Slices put several contacts of a fibre at one station: evaluate each station once.
      if (j == 0 || x != list[j - 1].a) {
        for (; moved < list.size() && list[moved].a < x; ++moved)
          sums.move_left(p[moved], list[moved].a, L - list[moved].a);
        v = {scaled_deflection_from_sums(sums.s[0], x, L) * inverse,
             scaled_deflection_from_sums(sums.s[1], x, L) * inverse};
        if (distributed) {
          vq = uniform_load_deflection(1.0, x, L, f.EI);
          v += q * vq;
        }
      }
      if (exact_energy) fibre_energy += 0.5 * p[j].dot(v);
      if (distributed) unit_q_work += p[j] * vq;
      if (list[j].contact >= 0) {
        const Eigen::Vector3d u = v[0] * f.e1 + v[1] * f.e2;
        (list[j].sign > 0 ? u_a : u_b)[list[j].contact] = u;
      }
    }
    // ½∫q·v dx = ½ q·(q L⁵/120EI + Σ p·v_{q=1}(a)).
    const double integral = uniform_load_deflection_integral(1.0, L, f.EI);
    fibre_energy += 0.5 * (q[0] * (q[0] * integral + unit_q_work[0]) +
                           q[1] * (q[1] * integral + unit_q_work[1]));
    energy += fibre_energy;
  }
  if (exact_energy) *exact_energy = energy;
}

void Superposition::fibre_field(int fibre, const std::vector<Contact>& contacts,
                                const std::vector<Eigen::Vector3d>& force_on_a, bool external,
                                const std::vector<double>& s, std::vector<Eigen::Vector3d>& u,
                                std::vector<Eigen::Vector2d>* moment) const {
  const auto& list = slots_[fibre];
  const Fibre& f = fibres_[fibre];
  const double L = f.length;
  const Eigen::Vector2d q = external ? distributed_[fibre] : Eigen::Vector2d::Zero();
  thread_local std::vector<Eigen::Vector2d> p;
  p.resize(list.size());
  PlaneSums sums;
  for (std::size_t j = 0; j < list.size(); ++j) {
    const Slot& slot = list[j];
    if (slot.contact >= 0)
      p[j] = slot_force(fibre, slot, contacts, force_on_a);
    else
      p[j] = external ? point_loads_[fibre][-1 - slot.contact].p : Eigen::Vector2d::Zero();
    sums.add_right(p[j], L - slot.a);
  }
  u.resize(s.size());
  if (moment) moment->resize(s.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double x = s[i] * L;
    for (; moved < list.size() && list[moved].a < x; ++moved)
      sums.move_left(p[moved], list[moved].a, L - list[moved].a);
    const double vq = uniform_load_deflection(1.0, x, L, f.EI);
    const double v1 = deflection_from_sums(sums.s[0], x, L, f.EI) + q[0] * vq;
    const double v2 = deflection_from_sums(sums.s[1], x, L, f.EI) + q[1] * vq;
    u[i] = v1 * f.e1 + v2 * f.e2;
    if (moment) {
      const double mq = uniform_load_moment(1.0, x, L);
      (*moment)[i] = {moment_from_sums(sums.s[0], x, L) + q[0] * mq,
                      moment_from_sums(sums.s[1], x, L) + q[1] * mq};
    }
  }
}

double Superposition::trapezium_energy(const std::vector<Contact>& contacts,
                                       const std::vector<Eigen::Vector3d>& force_on_a,
                                       int intervals) const {
  std::vector<double> s(intervals + 1);
  for (int j = 0; j <= intervals; ++j) s[j] = static_cast<double>(j) / intervals;
  double energy = 0.0;
  const int n_fibres = static_cast<int>(fibres_.size());
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : energy) if (n_fibres > 64)
  for (int i = 0; i < n_fibres; ++i) {
    thread_local std::vector<Eigen::Vector3d> u;
    thread_local std::vector<Eigen::Vector2d> m;
    fibre_field(i, contacts, force_on_a, true, s, u, &m);
    const double h = fibres_[i].length / intervals;
    double sum = 0.0;
    for (int j = 0; j <= intervals; ++j) {
      const double weight = (j == 0 || j == intervals) ? 0.5 : 1.0;
      sum += weight * m[j].squaredNorm();
    }
    energy += sum * h / (2.0 * fibres_[i].EI);  // Eq. 4.34, trapezium rule
  }
  return energy;
}

double Superposition::axial_load_dropped(const std::vector<Contact>& contacts,
                                         const std::vector<Eigen::Vector3d>& force_on_a) const {
  double total = 0.0;
  for (double x : external_axial_) total += x;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    total += std::fabs(force_on_a[c].dot(fibres_[contacts[c].a].t));
    if (contacts[c].kind != ContactKind::wall)
      total += std::fabs(force_on_a[c].dot(fibres_[contacts[c].b].t));
  }
  return total;
}

}  // namespace fibrecheck
