#include "shared_compliance.h"

#include <numeric>

#include "process_sums.h"
#include "subset_solve.h"

namespace fibrecheck {

Eigen::VectorXd SharedCompliance::times(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd mine = AssembledCompliance(part_).times(x);
  std::vector<double> y(mine.data(), mine.data() + mine.size());
  sum_over_processes(y, comm_);
  return Eigen::Map<Eigen::VectorXd>(y.data(), x.size());
}

Eigen::VectorXd SharedCompliance::diagonal() const {
  std::vector<double> d(static_cast<std::size_t>(part_.rows()), 0.0);
  for (Eigen::Index k = 0; k < part_.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(part_, k); it; ++it)
      if (it.row() == k) d[k] += it.value();
  sum_over_processes(d, comm_);
  return Eigen::Map<Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
}

// The set's entries of this process's part, in the set's numbering, then those of every process in
// the order of the processes: every process builds the same W_SS, summing the parts alike.
bool SharedCompliance::solve_on_subset(const std::vector<Eigen::Index>& index,
                                       const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const int m = static_cast<int>(index.size());
  std::vector<int> position(static_cast<std::size_t>(part_.rows()), -1);
  for (int i = 0; i < m; ++i) position[static_cast<std::size_t>(index[i])] = i;
  std::vector<int> rows, columns;
  std::vector<double> values;
  for (int c = 0; c < m; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(part_, index[c]); it; ++it) {
      const int row = position[static_cast<std::size_t>(it.row())];
      if (row < 0) continue;
      rows.push_back(row);
      columns.push_back(c);
      values.push_back(it.value());
    }
  int processes = 1;
  MPI_Comm_size(comm_, &processes);
  std::vector<int> count(static_cast<std::size_t>(processes)), first(count.size(), 0);
  const int mine = static_cast<int>(values.size());
  MPI_Allgather(&mine, 1, MPI_INT, count.data(), 1, MPI_INT, comm_);
  std::partial_sum(count.begin(), count.end() - 1, first.begin() + 1);
  const std::size_t all = static_cast<std::size_t>(first.back() + count.back());
  std::vector<int> all_rows(all), all_columns(all);
  std::vector<double> all_values(all);
  MPI_Allgatherv(rows.data(), mine, MPI_INT, all_rows.data(), count.data(), first.data(), MPI_INT,
                 comm_);
  MPI_Allgatherv(columns.data(), mine, MPI_INT, all_columns.data(), count.data(), first.data(),
                 MPI_INT, comm_);
  MPI_Allgatherv(values.data(), mine, MPI_DOUBLE, all_values.data(), count.data(), first.data(),
                 MPI_DOUBLE, comm_);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(all);
  for (std::size_t e = 0; e < all; ++e)
    entries.emplace_back(all_rows[e], all_columns[e], all_values[e]);
  Eigen::SparseMatrix<double> Wss(m, m);
  Wss.setFromTriplets(entries.begin(), entries.end());
  std::vector<Eigen::Index> every(static_cast<std::size_t>(m));
  std::iota(every.begin(), every.end(), Eigen::Index(0));
  return fibrecheck::solve_on_subset(Wss, every, b, x);
}

}  // namespace fibrecheck
