#pragma once

// The scale study. Question: how do the iterative solver's rules, the reference and an outside
// peer (Siconos, on the reference's exported problem) grow with the tow — time, iterations, time
// per iteration and peak memory against the number of fibres — and with what exponents?
//
// Each size is a generated tow (`generate tow --fibres N --slices S --seed X`). Every run is its
// own process — `fibrecheck solve`, `mpiexec -np P fibrecheck fem`, `fibrecheck-siconos` — so that
// its peak memory is its own and a crash or a cap ends one point, not the study. Points are kept
// as they finish (a study run again computes only what is missing).
//
// Sample run:
//   fibrecheck study scale --fibres 100,1000,3000 --reference-fibres 100,300 --peer-fibres 100
//     (continued:) --out study/scale

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scale_study_record.h"

namespace fibrecheck {

/// What a finished program run tells: its exit code, wall time and peak memory (of the process, or
/// of the largest of its processes under mpiexec), resident and proportional.
struct ProgramRun {
  int exit_code = -1;
  double wall_time_s = 0.0;
  double peak_memory_mb = 0.0;
  /// The proportional set size: each page shared with other processes (the libraries' code)
  /// counted as its share, so that the processes' figures add up to what the machine holds.
  double peak_proportional_memory_mb = 0.0;
  std::string error;  ///< standard error's last lines, when it failed
};
/// Runs a program (arguments[0] its path) to its end.
using ProgramRunner = std::function<ProgramRun(const std::vector<std::string>& arguments)>;

struct ScaleStudyOptions {
  std::vector<int> fibres{100, 1000};
  int slices = 100;
  std::uint64_t seed = 3;
  std::vector<std::string> rules{"auto", "accelerated"};
  /// The seed rule's step c (N/mm), needed when `rules` has it: the seed's method has no c of its
  /// own (its stable limit depends on the tow; see the stability study).
  double seed_c = 0.0;
  /// Sizes the reference runs at (a subset of `fibres`, or sizes of their own), on `processes`.
  std::vector<int> reference_fibres{100};
  int processes = 2;
  /// Sizes whose reference problem the outside peer solves again (they need the reference).
  std::vector<int> peer_fibres{100};
  /// Lemke only by default: the dense projected Gauss–Seidel and Newton methods of Siconos took
  /// minutes on a 100-fibre tow (5 856 contacts) where Lemke took 36 s.
  std::vector<std::string> peer_solvers{"lemke"};
  /// The programs: fibrecheck, fibrecheck-siconos (empty: no peer), mpiexec (empty: one process).
  std::string program, peer_program, mpiexec;
  bool quiet = false;
};

/// Runs the study into `folder`: scenes/, results/, problems/, scale.csv and scale_study.json.
/// Throws InputError for impossible options (no sizes, a peer size without the reference).
ScaleStudy run_scale_study(const ScaleStudyOptions& options, const ProgramRunner& run,
                           const std::string& folder);

}  // namespace fibrecheck
