#pragma once
/// Smooth vertex normals computed from a mesh's geometry.
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// Angle-weighted vertex normals (Thuermer & Wuethrich 1998: each face counts
/// with its corner angle, so the result does not depend on how a face is
/// split into triangles), accumulated over all vertices at the same position:
/// seams of UV spheres and triangle soups (STL) are smooth too. One unit
/// normal per vertex; a vertex of degenerate triangles only gets a zero
/// normal. O(V + F).
std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh);

}  // namespace lodforge
