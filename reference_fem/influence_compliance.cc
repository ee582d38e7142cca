#include "influence_compliance.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <numeric>
#include <utility>

#include "process_sums.h"
#include "subset_solve.h"

namespace fibrecheck {

namespace {

Eigen::VectorXd summed_over_processes(std::vector<double>& y, MPI_Comm comm) {
  sum_over_processes(y, comm);
  return Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
}

/// Every process's (row, column, value) entries, in the order of the processes, on every process.
std::vector<Eigen::Triplet<double>> gathered(const std::vector<int>& rows,
                                             const std::vector<int>& columns,
                                             const std::vector<double>& values, MPI_Comm comm) {
  int processes = 1;
  MPI_Comm_size(comm, &processes);
  std::vector<int> count(static_cast<std::size_t>(processes)), first(count.size(), 0);
  const int mine = static_cast<int>(values.size());
  MPI_Allgather(&mine, 1, MPI_INT, count.data(), 1, MPI_INT, comm);
  std::partial_sum(count.begin(), count.end() - 1, first.begin() + 1);
  const std::size_t all = static_cast<std::size_t>(first.back() + count.back());
  std::vector<int> all_rows(all), all_columns(all);
  std::vector<double> all_values(all);
  MPI_Allgatherv(rows.data(), mine, MPI_INT, all_rows.data(), count.data(), first.data(), MPI_INT,
                 comm);
  MPI_Allgatherv(columns.data(), mine, MPI_INT, all_columns.data(), count.data(), first.data(),
                 MPI_INT, comm);
  MPI_Allgatherv(values.data(), mine, MPI_DOUBLE, all_values.data(), count.data(), first.data(),
                 MPI_DOUBLE, comm);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(all);
  for (std::size_t e = 0; e < all; ++e)
    entries.emplace_back(all_rows[e], all_columns[e], all_values[e]);
  return entries;
}

}  // namespace

InfluenceCompliance::InfluenceCompliance(std::vector<Fibre> fibres, Eigen::Index rows,
                                         MPI_Comm communicator)
    : fibres_(std::move(fibres)), rows_(rows), comm_(communicator) {
  first_.assign(static_cast<std::size_t>(rows_) + 1, 0);
  for (const Fibre& f : fibres_)
    for (const Side& side : f.sides) ++first_[static_cast<std::size_t>(side.row) + 1];
  std::partial_sum(first_.begin(), first_.end(), first_.begin());
  held_.resize(first_.back());
  std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
  for (std::size_t f = 0; f < fibres_.size(); ++f)
    for (std::size_t i = 0; i < fibres_[f].sides.size(); ++i)
      held_[next[static_cast<std::size_t>(fibres_[f].sides[i].row)]++] = {static_cast<int>(f),
                                                                          static_cast<int>(i)};
}

// Per fibre: the forces x puts on its stations (few: x is mostly zero), then the displacement
// across the fibre they give at each side's station, along its φ.
Eigen::VectorXd InfluenceCompliance::times(const Eigen::VectorXd& x) const {
  std::vector<double> y(static_cast<std::size_t>(rows_), 0.0);
  std::vector<std::pair<int, Eigen::Vector3d>> loaded;
  for (const Fibre& f : fibres_) {
    loaded.clear();
    for (const Side& side : f.sides)
      if (x[side.row] != 0.0) loaded.emplace_back(side.station, x[side.row] * side.direction);
    if (loaded.empty()) continue;
    for (const Side& side : f.sides) {
      const double* column = f.G + static_cast<std::ptrdiff_t>(side.station) * f.stations;
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      for (const auto& [station, force] : loaded) u += column[station] * force;
      y[static_cast<std::size_t>(side.row)] += side.direction.dot(u);
    }
  }
  return summed_over_processes(y, comm_);
}

Eigen::VectorXd InfluenceCompliance::diagonal() const {
  std::vector<double> d(static_cast<std::size_t>(rows_), 0.0);
  for (const Fibre& f : fibres_)
    for (const Side& side : f.sides)
      d[static_cast<std::size_t>(side.row)] +=
          f.G[static_cast<std::ptrdiff_t>(side.station) * (f.stations + 1)] *
          side.direction.squaredNorm();
  return summed_over_processes(d, comm_);
}

// The set's entries of this process's fibres, in the set's numbering (found from the set's own
// rows, fibre by fibre), then those of every process in the order of the processes: every process
// sums the same entries alike into the same W_SS.
Eigen::SparseMatrix<double> InfluenceCompliance::on_subset(
    const std::vector<Eigen::Index>& index) const {
  const int m = static_cast<int>(index.size());
  struct InSet {
    int fibre, side, position;
  };
  std::vector<InSet> in_set;
  for (int i = 0; i < m; ++i) {
    const std::size_t k = static_cast<std::size_t>(index[i]);
    for (std::size_t h = first_[k]; h < first_[k + 1]; ++h)
      in_set.push_back({held_[h].fibre, held_[h].side, i});
  }
  std::sort(in_set.begin(), in_set.end(), [](const InSet& p, const InSet& q) {
    return p.fibre != q.fibre ? p.fibre < q.fibre : p.side < q.side;
  });
  std::vector<int> rows, columns;
  std::vector<double> values;
  for (std::size_t begin = 0, end = 0; begin < in_set.size(); begin = end) {
    const Fibre& f = fibres_[static_cast<std::size_t>(in_set[begin].fibre)];
    while (end < in_set.size() && in_set[end].fibre == in_set[begin].fibre) ++end;
    for (std::size_t j = begin; j < end; ++j) {
      const Side& sj = f.sides[static_cast<std::size_t>(in_set[j].side)];
      const double* column = f.G + static_cast<std::ptrdiff_t>(sj.station) * f.stations;
      for (std::size_t k = begin; k < end; ++k) {
        const Side& sk = f.sides[static_cast<std::size_t>(in_set[k].side)];
        rows.push_back(in_set[k].position);
        columns.push_back(in_set[j].position);
        values.push_back(column[sk.station] * sk.direction.dot(sj.direction));
      }
    }
  }
  const std::vector<Eigen::Triplet<double>> entries = gathered(rows, columns, values, comm_);
  Eigen::SparseMatrix<double> Wss(m, m);
  Wss.setFromTriplets(entries.begin(), entries.end());
  return Wss;
}

bool InfluenceCompliance::solve_on_subset(const std::vector<Eigen::Index>& index,
                                          const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  std::vector<Eigen::Index> every(index.size());
  std::iota(every.begin(), every.end(), Eigen::Index(0));
  return fibrecheck::solve_on_subset(on_subset(index), every, b, x);
}

}  // namespace fibrecheck
