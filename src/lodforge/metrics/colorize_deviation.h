#pragma once
/// Per-vertex colours showing where a deviation is large, on the colour scale
/// of the LODCreator thesis (Figure 5.16): blue = 0, green = half the maximum, red = the
/// maximum, linear in between.
#include <array>
#include <span>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// The scale's colours at 0, max / 2 and max (linear in between): blue,
/// green, red. A colour bar drawn with these stops reads the colours back.
inline constexpr std::array<Vec3, 3> kDeviationScale = {Vec3{0, 0, 1}, Vec3{0, 1, 0},
                                                        Vec3{1, 0, 0}};

/// Colours for `mesh`'s vertices from one value per vertex (e.g.
/// CompareResult::vertex_deviation). Values are clamped to [0, max]; with
/// max <= 0 (or not finite) every vertex is blue, and NaN values are blue.
/// Returns #V RGB colours in [0,1], ready for mesh.colors.
/// Precondition: values.size() == mesh.vertex_count() (assert).
std::vector<Vec3> colorize_deviation(const TriangleMesh& mesh, std::span<const float> values,
                                     float max);

}  // namespace lodforge
