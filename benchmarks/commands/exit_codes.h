#pragma once

namespace fibrecheck {

/// Exit codes of the fibrecheck program, so scripts can tell outcomes apart.
enum ExitCode : int {
  kExitConverged = 0,  ///< every run converged
  kExitFailure = 1,    ///< an unexpected internal error
  kExitBadInput = 2,   ///< bad scene, option or path: nothing was written
  kExitUnsolved = 3,   ///< valid input that did not converge: result written with its status
};

}  // namespace fibrecheck
