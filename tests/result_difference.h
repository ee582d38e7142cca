#pragma once

// How far apart two results of one scene are, for tests that hold two solvers against each other.

#include <algorithm>

#include "result.h"

namespace fibrecheck::testing {

/// The largest difference of the sampled displacements of `x` and `y` (fibres in the same
/// order), relative to the largest displacement of `x` (0 where both are equal, unloaded ones too).
inline double displacement_difference(const Result& x, const Result& y) {
  double largest = 0.0, difference = 0.0;
  for (std::size_t f = 0; f < x.fibres.size(); ++f)
    for (std::size_t j = 0; j < x.fibres[f].displacement.size(); ++j) {
      largest = std::max(largest, x.fibres[f].displacement[j].norm());
      difference =
          std::max(difference, (x.fibres[f].displacement[j] - y.fibres[f].displacement[j]).norm());
    }
  return difference == 0.0 ? 0.0 : difference / largest;
}

}  // namespace fibrecheck::testing
