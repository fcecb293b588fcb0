#pragma once
/// Triangulation of one polygon given by its corners in 3D.
///
/// The polygon may be concave and non-planar: it is projected onto the plane
/// of its Newell normal and triangulated there by ear clipping. Quadrilaterals
/// follow the quad rule of the original LODCreator. The output triangles are corner numbers
/// (0..n-1, not vertex indices), so that a caller with per-corner attributes
/// (OBJ v/vt/vn, VRML indexed bindings) can map them back itself.
#include <cstdint>
#include <span>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct TriangulateOptions {
  /// A convex quad bent by more than this angle (radians) between the two
  /// triangles of either diagonal is split; default 10 degrees.
  float quad_split_angle = 0.174533f;
  /// false (`--no-quads`): never report a quad as kept.
  bool keep_quads = true;
};

struct TriangulateResult {
  /// n-2 triangles of corner numbers for n >= 3 corners (empty for n < 3),
  /// wound like the polygon (counter-clockwise around `normal`).
  std::vector<Triangle> triangles;
  /// Unit Newell normal of the polygon; zero if the polygon has no area.
  Vec3 normal;
  /// n == 4 only: the quad is convex and flat enough to stay a quad. The two
  /// triangles above are still filled in (along the better diagonal).
  bool keep_as_quad = false;
  /// The polygon has (almost) no area: all corners collinear or coincident,
  /// or some output triangle has zero area. The triangles are still a valid
  /// index set (a fan when nothing better exists).
  bool degenerate = false;
  /// The polygon is not simple (self-intersecting, or numerically so): ear
  /// clipping had to clip a corner that is not an ear.
  bool not_simple = false;
  bool has_warning() const { return degenerate || not_simple; }
};

/// Triangulates a polygon with corners `points` (in order, either winding).
/// Never throws. Up to 256 corners the best-shaped ear is clipped each time
/// (O(n^2)); beyond, a convex polygon takes O(n), and any other about O(n)
/// ear tests of a cost that grows with the non-convex corners in each ear's
/// box (100 000 corners: a star 0.4 s, random radii 0.6 s; a comb of 25 000
/// teeth on one straight edge of collinear corners, the quadratic worst
/// case: 11 s).
TriangulateResult triangulate_polygon(std::span<const Vec3> points,
                                      const TriangulateOptions& options = {});

/// Same for a polygon given as indices into `positions` (each index must be
/// < positions.size(): asserted). The result still holds corner numbers
/// 0..n-1; map them through `indices` to get vertex indices.
TriangulateResult triangulate_polygon(std::span<const Vec3> positions,
                                      std::span<const std::uint32_t> indices,
                                      const TriangulateOptions& options = {});

/// Whether triangulate_polygon flags the triangle (a, b, c) as degenerate,
/// without building a result: for readers that pass triangles through.
bool triangle_is_degenerate(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace lodforge
