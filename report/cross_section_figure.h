#pragma once

#include <string>

#include "report_page.h"
#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// A cross-section of a tow like the seed's Figure 4.14, as figure `name` of `page`: the fibres
/// along the tow axis cut by the slice at mid-length, as circles of their radius (mm) at their
/// deformed centres, the rim coloured by the bending moment |M| (N·mm) there; the walls seen
/// edge-on; and the contact forces of that slice as lines from each contact point (normal forces
/// scaled so that the largest is one radius long, friction forces on their own such scale).
/// `what` opens the caption. Nothing is drawn for fewer than three fibres along the axis.
void draw_cross_section(ReportPage& page, const std::string& name, const std::string& what,
                        const Scene& scene, const Result& result);

}  // namespace fibrecheck
