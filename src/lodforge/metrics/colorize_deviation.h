#pragma once
/// Per-vertex colours showing where a deviation is large, on the colour scale
/// of seed 000 (Figure 5.16): blue = 0, green = half the maximum, red = the
/// maximum, linear in between.
#include <span>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// Colours for `mesh`'s vertices from one value per vertex (e.g.
/// CompareResult::vertex_deviation). Values are clamped to [0, max]; with
/// max <= 0 (or not finite) every vertex is blue, and NaN values are blue.
/// Returns #V RGB colours in [0,1], ready for mesh.colors.
/// Precondition: values.size() == mesh.vertex_count() (assert).
std::vector<Vec3> colorize_deviation(const TriangleMesh& mesh, std::span<const float> values,
                                     float max);

}  // namespace lodforge
