#include "influence_compliance.h"

#include <Eigen/SparseCore>
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

// Per fibre: the forces x puts on its stations (few: x is mostly zero), then the displacement
// across the fibre they give at each side's station, along its φ.
Eigen::VectorXd InfluenceCompliance::times(const Eigen::VectorXd& x) const {
  std::vector<double> y(static_cast<std::size_t>(contacts_), 0.0);
  std::vector<std::pair<int, Eigen::Vector3d>> loaded;
  for (const Fibre& f : fibres_) {
    loaded.clear();
    for (const Side& side : f.sides)
      if (x[side.contact] != 0.0)
        loaded.emplace_back(side.station, x[side.contact] * side.direction);
    if (loaded.empty()) continue;
    for (const Side& side : f.sides) {
      const double* column = f.G + static_cast<std::ptrdiff_t>(side.station) * f.stations;
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      for (const auto& [station, force] : loaded) u += column[station] * force;
      y[static_cast<std::size_t>(side.contact)] += side.direction.dot(u);
    }
  }
  return summed_over_processes(y, comm_);
}

Eigen::VectorXd InfluenceCompliance::diagonal() const {
  std::vector<double> d(static_cast<std::size_t>(contacts_), 0.0);
  for (const Fibre& f : fibres_)
    for (const Side& side : f.sides)
      d[static_cast<std::size_t>(side.contact)] +=
          f.G[static_cast<std::ptrdiff_t>(side.station) * (f.stations + 1)] *
          side.direction.squaredNorm();
  return summed_over_processes(d, comm_);
}

// The set's entries of this process's fibres, in the set's numbering, then those of every process
// in the order of the processes: every process sums the same entries alike into the same W_SS.
bool InfluenceCompliance::solve_on_subset(const std::vector<Eigen::Index>& index,
                                          const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const int m = static_cast<int>(index.size());
  std::vector<int> position(static_cast<std::size_t>(contacts_), -1);
  for (int i = 0; i < m; ++i) position[static_cast<std::size_t>(index[i])] = i;
  std::vector<int> rows, columns;
  std::vector<double> values;
  std::vector<const Side*> in_set;
  for (const Fibre& f : fibres_) {
    in_set.clear();
    for (const Side& side : f.sides)
      if (position[static_cast<std::size_t>(side.contact)] >= 0) in_set.push_back(&side);
    for (const Side* j : in_set) {
      const double* column = f.G + static_cast<std::ptrdiff_t>(j->station) * f.stations;
      for (const Side* k : in_set) {
        rows.push_back(position[static_cast<std::size_t>(k->contact)]);
        columns.push_back(position[static_cast<std::size_t>(j->contact)]);
        values.push_back(column[k->station] * k->direction.dot(j->direction));
      }
    }
  }
  const std::vector<Eigen::Triplet<double>> entries = gathered(rows, columns, values, comm_);
  Eigen::SparseMatrix<double> Wss(m, m);
  Wss.setFromTriplets(entries.begin(), entries.end());
  std::vector<Eigen::Index> every(static_cast<std::size_t>(m));
  std::iota(every.begin(), every.end(), Eigen::Index(0));
  return fibrecheck::solve_on_subset(Wss, every, b, x);
}

}  // namespace fibrecheck
