#pragma once

#include <vector>

#include "fibre.h"
#include "result.h"

namespace fibrecheck {

/// Small-deflection Euler–Bernoulli beams (seed §4.3.1) hold while slopes stay small: beyond
/// kMaxSlope (rad) the linearised curvature w'' differs from the true w''/(1 + w'²)^{3/2} by more
/// than 1.5 %, and the chord the loads act along has shortened by w'²/2 = 0.5 % of the length.
constexpr double kMaxSlope = 0.1;

/// Shear deformation, which Euler–Bernoulli beams leave out, adds 12EI/(κGAL²) = 8.8 (r/L)² to a
/// pinned fibre's deflection under a mid-span load (solid circle: κ = 0.886, G = E/2.6 for
/// ν = 0.3); more than this fraction is flagged, that is L/r below 30.
constexpr double kMaxShearShare = 0.01;

/// Sets the result's `max_deflection_over_radius` and `max_slope` from its displacement samples
/// (transverse parts; slopes by differences between neighbouring samples), and adds a warning
/// when the answer lies outside small-deflection theory or a fibre is too stubby for it. The
/// status is left alone: the answer is still the exact one of the model, which both solvers must
/// agree on; the warning says the model no longer describes the fibres.
void assess_validity(Result& result, const std::vector<Fibre>& fibres);

}  // namespace fibrecheck
