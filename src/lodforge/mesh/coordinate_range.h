#pragma once
/// The range of coordinates the algorithms work in. They compute in single
/// precision with tolerances relative to the model's size, and products of
/// up to four lengths (squared areas) must stay finite and above the
/// denormals: that holds for models at most kMaxCoordinate from the origin
/// and at least kMinExtent across.
#include <span>
#include <string>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

inline constexpr float kMaxCoordinate = 1e9f;
inline constexpr float kMinExtent = 1e-7f;

/// Throws DataError naming `name` and the supported range when a position of
/// `mesh` is not finite or farther than kMaxCoordinate on an axis, or when
/// the positions are not all at one point and their bounding box is less
/// than kMinExtent across on every axis.
void check_coordinate_range(const TriangleMesh& mesh, const std::string& name);
/// The same for any set of points.
void check_coordinate_range(std::span<const Vec3> points, const std::string& name);

}  // namespace lodforge
