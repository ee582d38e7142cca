#include "superposition.h"

#include <algorithm>
#include <cmath>

#include "beam.h"
#include "parallel_work.h"

namespace fibrecheck {

/// Lane k of each array is the bending plane of e_{k+1}: one SIMD operation updates both planes.
struct Superposition::PlaneSums : RunningSums<Eigen::Array2d> {};

namespace {

/// (F·e1, F·e2) for one fibre: the rows of [e1 e2] held as arrays, so a force is resolved into both
/// planes at once. Summed in the order of Eigen's dot, (F₀e₀ + F₁e₁) + F₂e₂.
struct PlaneProjection {
  Eigen::Array2d r0, r1, r2;

  explicit PlaneProjection(const Fibre& f)
      : r0(f.e1[0], f.e2[0]), r1(f.e1[1], f.e2[1]), r2(f.e1[2], f.e2[2]) {}
  Eigen::Array2d operator()(const Eigen::Vector3d& F) const {
    return F[0] * r0 + F[1] * r1 + F[2] * r2;
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
  total_slots_ = 0;
  for (auto& list : slots_) {
    std::sort(list.begin(), list.end(), [](const Slot& x, const Slot& y) {
      return x.a < y.a || (x.a == y.a && x.contact < y.contact);
    });
    total_slots_ += static_cast<long>(list.size());
  }
}

void Superposition::move_points(const std::vector<Contact>& contacts,
                                const std::vector<int>& fibres) {
  for (int f : fibres) {
    std::vector<Slot>& list = slots_[f];
    for (Slot& slot : list) {
      if (slot.contact < 0) continue;
      const Contact& k = contacts[slot.contact];
      slot.a = (slot.sign > 0 ? k.s_a : k.s_b) * fibres_[f].length;
    }
    std::sort(list.begin(), list.end(), [](const Slot& x, const Slot& y) {
      return x.a < y.a || (x.a == y.a && x.contact < y.contact);
    });
  }
}

// Inline: it is the first half of the inner loop of every evaluation.
inline void Superposition::load_components(int fibre,
                                           const std::vector<Eigen::Vector3d>& force_on_a,
                                           bool external, std::vector<Eigen::Array2d>& p,
                                           PlaneSums& sums) const {
  const std::size_t n = slots_[fibre].size();
  const Slot* const slot = slots_[fibre].data();
  const Eigen::Vector3d* const force = force_on_a.data();
  const double L = fibres_[fibre].length;
  const PlaneProjection project(fibres_[fibre]);
  if (p.size() < n) p.resize(n);
  Eigen::Array2d* const load = p.data();
  for (std::size_t j = 0; j < n; ++j) {
    // The forces are gathered in slice order, far apart: fetch a few slots ahead.
    if (j + 8 < n && slot[j + 8].contact >= 0) __builtin_prefetch(&force[slot[j + 8].contact]);
    Eigen::Array2d pj;
    if (slot[j].contact >= 0)  // sign ±1: exact, the same as resolving ±F
      pj = static_cast<double>(slot[j].sign) * project(force[slot[j].contact]);
    else
      pj = external ? Eigen::Array2d(point_loads_[fibre][-1 - slot[j].contact].p)
                    : Eigen::Array2d::Zero();
    load[j] = pj;
    sums.add_right(pj, L - slot[j].a);
  }
}

void Superposition::contact_displacements(const std::vector<Contact>& contacts,
                                          const std::vector<Eigen::Vector3d>& force_on_a,
                                          bool external, std::vector<Eigen::Vector3d>& u_a,
                                          std::vector<Eigen::Vector3d>& u_b,
                                          double* exact_energy) const {
  u_a.resize(contacts.size());
  u_b.resize(contacts.size());
  // Each fibre's energy kept apart and added in fibre order: the same total on any number of
  // threads.
  const int n_fibres = static_cast<int>(fibres_.size());
  std::vector<double> fibre_energies(exact_energy ? fibres_.size() : 0, 0.0);
#pragma omp parallel if (total_slots_ > kParallelContacts)
  {
    thread_local std::vector<Eigen::Array2d> p;  // the loads of one fibre, reused between calls
    // Plain pointers, private to the thread: the compiler need not reload them after each store.
    Eigen::Vector3d* const out_a = u_a.data();
    Eigen::Vector3d* const out_b = u_b.data();
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < n_fibres; ++i) {
      const std::size_t n = slots_[i].size();
      const Fibre& f = fibres_[i];
      const Eigen::Array2d q = external ? Eigen::Array2d(distributed_[i]) : Eigen::Array2d::Zero();
      const bool distributed = !q.isZero();
      if (n == 0 && !distributed) continue;
      PlaneSums sums;
      load_components(i, force_on_a, external, p, sums);
      const Slot* const slot = slots_[i].data();
      const Eigen::Array2d* const load = p.data();
      const double L = f.length;
      const double inverse = 1.0 / (6.0 * f.EI * L);
      double fibre_energy = 0.0;
      Eigen::Array2d unit_q_work = Eigen::Array2d::Zero();  // Σ p·v_{q=1}(a) (Maxwell–Betti)
      // Second pass, station by station. Slices put several contacts of a fibre at one station:
      // each station is evaluated once, then its loads move to the "a < x" sums.
      for (std::size_t j = 0; j < n;) {
        const double x = slot[j].a;
        Eigen::Array2d v = sums.scaled_deflection(x, L) * inverse;
        double vq = 0.0;
        if (distributed) {
          vq = uniform_load_deflection(1.0, x, L, f.EI);
          v += q * vq;
        }
        const Eigen::Vector3d u = v[0] * f.e1 + v[1] * f.e2;
        do {
          if (exact_energy) fibre_energy += 0.5 * (load[j] * v).sum();
          if (distributed) unit_q_work += load[j] * vq;
          if (slot[j].contact >= 0) (slot[j].sign > 0 ? out_a : out_b)[slot[j].contact] = u;
          sums.move_left(load[j], x, L - x);
        } while (++j < n && slot[j].a == x);
      }
      // ½∫q·v dx = ½ q·(q L⁵/120EI + Σ p·v_{q=1}(a)).
      const double integral = uniform_load_deflection_integral(1.0, L, f.EI);
      fibre_energy += 0.5 * (q[0] * (q[0] * integral + unit_q_work[0]) +
                             q[1] * (q[1] * integral + unit_q_work[1]));
      if (exact_energy) fibre_energies[i] = fibre_energy;
    }
  }
  if (exact_energy) {
    double energy = 0.0;
    for (double e : fibre_energies) energy += e;
    *exact_energy = energy;
  }
}

void Superposition::fibre_field(int fibre, const std::vector<Eigen::Vector3d>& force_on_a,
                                bool external, const std::vector<double>& s,
                                std::vector<Eigen::Vector3d>& u,
                                std::vector<Eigen::Vector2d>* moment) const {
  const auto& list = slots_[fibre];
  const Fibre& f = fibres_[fibre];
  const double L = f.length;
  const Eigen::Array2d q = external ? Eigen::Array2d(distributed_[fibre]) : Eigen::Array2d::Zero();
  thread_local std::vector<Eigen::Array2d> p;
  PlaneSums sums;
  load_components(fibre, force_on_a, external, p, sums);
  u.resize(s.size());
  if (moment) moment->resize(s.size());
  const double scale = 6.0 * f.EI * L;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double x = s[i] * L;
    for (; moved < list.size() && list[moved].a < x; ++moved)
      sums.move_left(p[moved], list[moved].a, L - list[moved].a);
    const double vq = uniform_load_deflection(1.0, x, L, f.EI);
    const Eigen::Array2d v = sums.scaled_deflection(x, L) / scale + q * vq;
    u[i] = v[0] * f.e1 + v[1] * f.e2;
    if (moment) (*moment)[i] = sums.moment(x, L) + q * uniform_load_moment(1.0, x, L);
  }
}

double Superposition::trapezium_energy(const std::vector<Eigen::Vector3d>& force_on_a,
                                       int intervals) const {
  std::vector<double> s(intervals + 1);
  for (int j = 0; j <= intervals; ++j) s[j] = static_cast<double>(j) / intervals;
  const int n_fibres = static_cast<int>(fibres_.size());
  std::vector<double> fibre_energies(fibres_.size(), 0.0);  // added in fibre order, below
#pragma omp parallel for schedule(dynamic, 16) if (n_fibres > 64)
  for (int i = 0; i < n_fibres; ++i) {
    // Only the moments: the deflections (and their cubic sums) are not needed here.
    const auto& list = slots_[i];
    const double L = fibres_[i].length;
    const Eigen::Array2d q = distributed_[i];
    thread_local std::vector<Eigen::Array2d> p;
    PlaneSums sums;
    load_components(i, force_on_a, true, p, sums);
    std::size_t moved = 0;
    double sum = 0.0;
    for (int j = 0; j <= intervals; ++j) {
      const double x = s[j] * L;
      for (; moved < list.size() && list[moved].a < x; ++moved)
        sums.move_left_moment(p[moved], list[moved].a, L - list[moved].a);
      const Eigen::Array2d m = sums.moment(x, L) + q * uniform_load_moment(1.0, x, L);
      const double weight = (j == 0 || j == intervals) ? 0.5 : 1.0;
      sum += weight * m.square().sum();
    }
    fibre_energies[i] = sum * (L / intervals) / (2.0 * fibres_[i].EI);  // Eq. 4.34, trapezium
  }
  double energy = 0.0;
  for (double e : fibre_energies) energy += e;
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
