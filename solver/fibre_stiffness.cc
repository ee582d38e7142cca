#include "fibre_stiffness.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace fibrecheck {

FibreStiffness::FibreStiffness(const std::vector<Fibre>& fibres) : fibres_(fibres) {}

void FibreStiffness::attach(const std::vector<Contact>& contacts) {
  lines_.clear();
  std::map<std::tuple<int, int, int>, int> line_of;  // (kind, A, B or wall) of slices and walls
  auto plane = [&](int f, const Eigen::Vector3d& n) {
    return Eigen::Array2d(n.dot(fibres_[f].e1), n.dot(fibres_[f].e2));
  };
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& k = contacts[c];
    const int id = static_cast<int>(c);
    const bool wall = k.kind == ContactKind::wall;
    int line = static_cast<int>(lines_.size());
    if (k.kind != ContactKind::point) {
      const auto found = line_of.emplace(std::make_tuple(static_cast<int>(k.kind), k.a, k.b), line);
      line = found.first->second;
    }
    if (line == static_cast<int>(lines_.size())) lines_.push_back({{k.a, wall ? -1 : k.b}, {}});
    Line& l = lines_[line];
    if (wall) {
      l.side[0].push_back({k.s_a * fibres_[k.a].length, id, plane(k.a, k.normal)});
      continue;
    }
    // W·x at a contact is n·(u_B − u_A) under the forces −x·n on A and +x·n on B.
    const double EIa = fibres_[k.a].EI, EIb = fibres_[k.b].EI;
    const double D = std::sqrt(EIa * EIb) / (EIa + EIb);
    l.side[0].push_back({k.s_a * fibres_[k.a].length, id, -D * plane(k.a, k.normal)});
    l.side[1].push_back({k.s_b * fibres_[k.b].length, id, D * plane(k.b, k.normal)});
  }
  for (Line& l : lines_)
    for (auto& list : l.side)
      std::sort(list.begin(), list.end(), [](const Slot& x, const Slot& y) {
        return x.a < y.a || (x.a == y.a && x.contact < y.contact);
      });
  side_a_.assign(contacts.size(), 0.0);
  side_b_.assign(contacts.size(), 0.0);
}

void FibreStiffness::beam_stiffness(double L, double EI, const std::vector<double>& x,
                                    std::vector<Eigen::Array2d>& v) {
  const std::size_t m = x.size();
  if (m == 0) return;
  thread_local std::vector<double> h, diagonal;
  thread_local std::vector<Eigen::Array2d> s;
  h.resize(m + 1);
  diagonal.resize(m);
  s.resize(m);
  for (std::size_t j = 0; j <= m; ++j) h[j] = (j == m ? L : x[j]) - (j == 0 ? 0.0 : x[j - 1]);
  // The second difference A of a station vector that is zero at both supports.
  auto second_difference = [&](const std::vector<Eigen::Array2d>& w, std::size_t j) {
    Eigen::Array2d result = -w[j] * (1.0 / h[j + 1] + 1.0 / h[j]);
    if (j > 0) result += w[j - 1] / h[j];
    if (j + 1 < m) result += w[j + 1] / h[j + 1];
    return result;
  };
  for (std::size_t j = 0; j < m; ++j) s[j] = second_difference(v, j);
  // B·M' = A·w by the Thomas algorithm (B is symmetric and diagonally dominant).
  for (std::size_t j = 0; j < m; ++j) {
    diagonal[j] = (h[j] + h[j + 1]) / 3.0;
    if (j > 0) {
      const double l = (h[j] / 6.0) / diagonal[j - 1];
      diagonal[j] -= l * h[j] / 6.0;
      s[j] -= l * s[j - 1];
    }
  }
  for (std::size_t j = m; j-- > 0;) {
    if (j + 1 < m) s[j] -= (h[j + 1] / 6.0) * s[j + 1];
    s[j] /= diagonal[j];
  }
  for (std::size_t j = 0; j < m; ++j) v[j] = EI * second_difference(s, j);
}

void FibreStiffness::apply_side(int fibre, const std::vector<Slot>& side, const Eigen::VectorXd& r,
                                const std::vector<unsigned char>& free, double* out) const {
  const double L = fibres_[fibre].length;
  // Stations closer than this are one; loads at a support move nothing.
  const double merge = 1e-9 * L;
  thread_local std::vector<double> x;
  thread_local std::vector<Eigen::Array2d> v;
  thread_local std::vector<int> station;  // of each slot, −1 at a support or not free
  x.clear();
  v.clear();
  station.assign(side.size(), -1);
  for (std::size_t j = 0; j < side.size(); ++j) {
    const Slot& s = side[j];
    if (!free[s.contact] || s.a <= merge || s.a >= L - merge) continue;
    if (x.empty() || s.a - x.back() > merge) {
      x.push_back(s.a);
      v.push_back(Eigen::Array2d::Zero());
    }
    station[j] = static_cast<int>(x.size()) - 1;
    v.back() += s.direction * r[s.contact];
  }
  beam_stiffness(L, fibres_[fibre].EI, x, v);
  for (std::size_t j = 0; j < side.size(); ++j)
    out[side[j].contact] = station[j] < 0 ? 0.0 : (side[j].direction * v[station[j]]).sum();
}

void FibreStiffness::apply(const Eigen::VectorXd& r, const std::vector<unsigned char>& free,
                           Eigen::VectorXd& z) const {
  const int n_lines = static_cast<int>(lines_.size());
  double* const out[2] = {side_a_.data(), side_b_.data()};
#pragma omp parallel for schedule(dynamic, 16) if (n_lines > 64)
  for (int l = 0; l < n_lines; ++l)
    for (int side = 0; side < 2; ++side)
      if (lines_[l].fibre[side] >= 0)
        apply_side(lines_[l].fibre[side], lines_[l].side[side], r, free, out[side]);
  const Eigen::Index n = static_cast<Eigen::Index>(free.size());
  z.resize(n);
#pragma omp parallel for schedule(static) if (n > 4096)
  for (Eigen::Index k = 0; k < n; ++k) z[k] = free[k] ? side_a_[k] + side_b_[k] : 0.0;
}

}  // namespace fibrecheck
