#pragma once

#include <deal.II/base/mpi.h>

namespace fibrecheck {

/// MPI (and PETSc) for the length of one command, started and ended the way deal.II does it.
/// The command's own arguments belong to CLI11, so MPI sees only the program's name.
class MpiSession {
 public:
  MpiSession() : argv_{name_, nullptr}, arguments_(argv_), mpi_(argc_, arguments_, 1) {}
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

 private:
  int argc_ = 1;
  char name_[11] = "fibrecheck";
  char* argv_[2];
  char** arguments_;
  dealii::Utilities::MPI::MPI_InitFinalize mpi_;
};

}  // namespace fibrecheck
