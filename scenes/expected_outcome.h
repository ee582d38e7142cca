#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "result.h"

namespace fibrecheck {

/// What a scene must give, for scenes that know it (the catalogue in scenes/extreme/): the status
/// of each solver and closed-form numbers (DESIGN §7), each with the tolerance it is known to.
/// The solvers never read it; the tests and the stability study judge their results by it.
///
///   "expected": {
///     "closed_form": "P = δ/(C_A + C_B), C = a²b²/(3EIL)",
///     "status": {"iterative": "converged", "reference": "converged"},
///     "message": {"iterative": "c < "},        substring of the result's message (optional)
///     "warning": "outside small-deflection",   substring of a warning, both solvers (optional)
///     "forces": [{"fibres": ["A", "B"], "total_force": 1.5e-6, "relative_tolerance": 1e-6}],
///     "deflections": [{"fibre": "A", "position": 0.5, "displacement": [0, 0, -1e-4],
///                      "relative_tolerance": 1e-6}]
///   }
///
/// A status is one of the result's statuses: `beyond_reach` where the solver would need more
/// memory than a machine has (exit code 3 with what it would need) — the reference's dense
/// influence matrices and compliance matrix at 100 000 slices, say. A pair's force is the sum of `total_force` over its contacts (0 when it
/// has none); an expected force of 0 takes the tolerance in newtons. A deflection is read at the
/// result's sample at `position`, which must be one.
struct ExpectedOutcome {
  struct Force {
    std::array<std::string, 2> fibres;
    double total_force = 0.0;  ///< N
    double relative_tolerance = 1e-6;
  };
  struct Deflection {
    std::string fibre;
    double position = 0.5;                                   ///< fraction of the fibre's length
    Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  ///< mm
    double relative_tolerance = 1e-6;
  };
  std::string closed_form;
  std::map<std::string, std::string> status;   ///< "iterative" | "reference" → status
  std::map<std::string, std::string> message;  ///< "iterative" | "reference" → substring
  std::string warning;
  std::vector<Force> forces;
  std::vector<Deflection> deflections;
};

/// Reads the `expected` object of a scene file (InputError naming the field on anything wrong).
ExpectedOutcome read_expected_outcome(const nlohmann::json& object, const std::string& source);
nlohmann::json to_json(const ExpectedOutcome& expected);

/// How a result measures up to the expectation for one solver ("iterative" or "reference").
struct OutcomeCheck {
  std::vector<std::string> failures;  ///< empty: as expected
  /// The worst relative error over the expected forces and deflections; NaN when none is listed
  /// or the status differs.
  double error = NAN;
  bool passed() const { return failures.empty(); }
};

OutcomeCheck check_outcome(const ExpectedOutcome& expected, const Result& result,
                           const std::string& solver);

/// The status a solver is expected to end with ("converged" when the scene does not say).
std::string expected_status(const ExpectedOutcome& expected, const std::string& solver);

}  // namespace fibrecheck
