#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "contact.h"
#include "contact_detection.h"
#include "result.h"

namespace fibrecheck {

/// A fibre's displacements (mm) at sorted fractions of its length, from a solver's own beams.
using FibreDisplacements =
    std::function<void(int fibre, const std::vector<double>& s, std::vector<Eigen::Vector3d>& u)>;

/// The seed's own test of a final state in the deformed configuration (Eq. 4.15, §4.3.6), whatever
/// contact model produced it: every candidate's gap between displaced centres — a slice's in its
/// cross-section plane, a crossing's at the closest points of the deformed fibres near where it
/// acts (one step of ContactDetector::follow_crossing, displaced by `u_a`, `u_b` plus their
/// change along each fibre that `displacements` gives) — the largest |gap| where the contact
/// pushes and the largest overlap where it does not. `u_a`, `u_b` are the displacements of each
/// contact's two sides where it acts.
DeformedTest deformed_test(const ContactDetector& detector, const std::vector<Contact>& contacts,
                           const std::vector<Eigen::Vector3d>& u_a,
                           const std::vector<Eigen::Vector3d>& u_b,
                           const FibreDisplacements& displacements);

/// Under the deformed contact a converged answer passes the seed's test to t_d. Where the
/// result's test is above `overlap_tolerance` (a crossing its solver left off the closest points
/// of the deformed fibres), the converged result gets a warning saying by how much; the
/// linearised contact is not judged by this test. Call it once the status is set.
void warn_where_the_seeds_test_fails(double overlap_tolerance, Result& r);

}  // namespace fibrecheck
