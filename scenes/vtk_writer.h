#pragma once

#include <string>

#include "result.h"
#include "scene.h"

namespace fibrecheck {

/// Writes a result as VTK XML PolyData (.vtp) for ParaView: each fibre's deformed centreline as a
/// polyline with point data `radius` (mm) and `displacement` (mm), and every contact point as a
/// vertex with point data `force` (N, on the first fibre of the pair). Written atomically.
void write_vtk(const std::string& path, const Scene& scene, const Result& result);

}  // namespace fibrecheck
