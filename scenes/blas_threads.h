#pragma once

#include <dlfcn.h>

namespace fibrecheck {

// Debian's OpenBLAS (the system BLAS once installed, which deal.II, PETSc, MUMPS and Siconos call)
// starts as many threads as the machine has cores in every process. Under mpirun, with one
// process per core, that oversubscribes the cores. These look the library up at run time, so the
// program works with any BLAS.

/// OpenBLAS's thread count in this process, −1 when the BLAS is not OpenBLAS.
inline int blas_threads() {
  using Get = int (*)();
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : -1;
}

/// Sets OpenBLAS's thread count (nothing with another BLAS).
inline void set_blas_threads(int threads) {
  using Set = void (*)(int);
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set) set(threads);
}

}  // namespace fibrecheck
