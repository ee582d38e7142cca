#pragma once

#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace fibrecheck {

/// PETSc calls report failure by their return code: turned into an exception naming the call.
inline void check(PetscErrorCode code, const char* call) {
  if (code != 0)
    throw std::runtime_error(std::string("PETSc: ") + call + " failed (error " +
                             std::to_string(code) + ")");
}

}  // namespace fibrecheck
