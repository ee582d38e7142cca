#pragma once

#include <string>

#include "result.h"

namespace fibrecheck {

/// How a run of the iteration ended (seed §4.3.6): its status, the criterion that ended it and a
/// message for the user.
struct Termination {
  Status status = Status::max_iterations;
  Criterion criterion = Criterion::max_iterations;
  std::string message;
};

}  // namespace fibrecheck
