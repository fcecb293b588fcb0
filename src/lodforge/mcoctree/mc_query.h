#pragma once
/// Geometric queries against one level of a marching-cube octree model
/// (mc_lod_model.h) through the octree itself: the first hit of a ray, the
/// closest surface point with the signed distance, and whether a point is
/// inside (Kim, Table 7.1: collision detection through the octree).
///
/// The level's triangles are those of extract_mc_mesh at the same options;
/// the octree's cells (the root, the children of the nodes expanded at that
/// level, down to the emitted cells) are the search structure: each emitted
/// cell holds its own triangles, each node the bounding box of the triangles
/// below it. No second hierarchy is built.
///
/// Sign: inside is negative. The side of a point is that of the angle-weighted
/// pseudo-normal at its closest surface point (Baerentzen & Aanaes 2005: the
/// face normal inside a triangle, the sum of the two face normals on an edge,
/// the angle-weighted sum around a vertex), the rule the octree's own corner
/// signs were built with (mesh_signs.h). It is exact for a closed, consistently
/// wound (outwards) surface, which every level of a model built from a closed
/// mesh, or with McHoles::kCapped, is. The run-time model keeps no corner
/// signs, so they cannot be read back. Near an open border of the level
/// (McHoles::kOpen over the input's holes) the side is unknown: the result
/// says so (McClosest::open) and the point counts as outside.
///
/// Units are the model's (those of the mesh it was built from). Queries are
/// const and may run from any number of threads at once. Answers are
/// deterministic: the same model, level and query give the same answer. Among
/// triangles at exactly the same distance the lowest index found wins (for
/// closest points every such triangle is found; for rays, one in a cell the
/// float rounding of a box entry puts beyond the hit may be missed).
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/mc_lod_model.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/metrics/closest_point_on_triangle.h"

namespace lodforge {
namespace detail {
class SignedDistance;
}

/// The first intersection of a ray with the surface.
struct McRayHit {
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  float distance = kInf;  ///< along the ray from its origin (the direction's length is ignored)
  Vec3 point;             ///< origin + distance * unit direction
  Vec3 normal;            ///< unit face normal of the triangle hit (winding: outwards)
  std::uint32_t triangle = kNone;  ///< index into McQuery::mesh().triangles
  bool hit() const { return triangle != kNone; }
};

/// The closest surface point of a query point.
struct McClosest {
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  Vec3 point;                      ///< the nearest surface point
  std::uint32_t triangle = kNone;  ///< index into McQuery::mesh().triangles
  /// Signed distance: |distance| = |p - point|, negative inside; >= 0 when
  /// `open`. Infinite when the level has no triangles.
  float distance = kInf;
  /// The closest point lies on (or nearest to) an open border: side unknown.
  bool open = false;
  bool found() const { return triangle != kNone; }
  bool inside() const { return distance < 0; }
};

/// Queries against one level of a model: built once (O(cells + triangles) of
/// the level, plus the adjacency for the pseudo-normals), then queried.
/// Holds copies of what it needs; the model may be dropped afterwards.
/// Movable (a moved-from query may only be assigned to or destroyed), not
/// copyable.
class McQuery {
 public:
  /// The level as in extract_mc_mesh: McExtractOptions{} is the full
  /// resolution, .priority / .triangles / .percent a coarser one (clamped).
  /// Throws DataError as extract_mc_mesh does for contradictory options, and
  /// when the tree is deeper than kMaxDepth levels (no model from
  /// build_mc_octree is).
  explicit McQuery(const McLodModel& model, const McExtractOptions& level = {});
  McQuery(McQuery&&) noexcept;
  McQuery& operator=(McQuery&&) noexcept;
  ~McQuery();

  static constexpr int kMaxDepth = 30;

  /// First hit of the ray origin + t * direction, 0 <= t <= max_distance
  /// (t in units of length along the ray). Both sides of a triangle count. No
  /// hit: hit() is false. Throws DataError when the origin is not finite or
  /// the direction is zero or not finite.
  ///
  /// Cost: the cells whose boxes the ray enters, front to back, stopping at
  /// the first cell whose entry is beyond the nearest hit so far: O(log n)
  /// nodes for n triangles when the ray crosses the surface at a few places;
  /// a ray grazing a large flat region visits the cells along it.
  McRayHit ray(const Vec3& origin, const Vec3& direction,
               float max_distance = McRayHit::kInf) const;

  /// The closest surface point to `p` and the signed distance (header
  /// comment). found() is false only when the level has no triangles. Throws
  /// DataError when p is not finite.
  ///
  /// Cost: depth first over the cells, the nearest box first, skipping
  /// cells whose boxes are farther than the nearest point found so far (the
  /// radius shrinks with each closer triangle): O(log n) nodes for a point
  /// within a few cells of the surface; a point at distance D visits the
  /// cells whose boxes are nearer than D, more as D grows against the cell
  /// size (the centre of a sphere: every cell). Allocates nothing.
  McClosest closest(const Vec3& p) const;

  /// Whether p is inside the closed surface: closest(p).inside().
  bool inside(const Vec3& p) const { return closest(p).inside(); }

  std::uint32_t priority() const { return priority_; }
  /// The level's mesh (extract_mc_mesh's): the triangle indices of the
  /// answers refer to it.
  const TriangleMesh& mesh() const;
  /// Nodes of the search tree (octree nodes with triangles below them).
  std::size_t node_count() const { return nodes_.size(); }

 private:
  struct Node {
    Vec3 lo, hi;          // bounds of the triangles below (slightly grown)
    std::uint32_t first;  // leaf: first triangle; inner: first child node
    std::uint32_t count;  // leaf: triangles; inner: children
    bool leaf;
  };
  McQuery(const McLodModel& model, McExtractResult level);
  void build_tree(const McLodModel& model);

  std::uint32_t priority_ = 0;
  std::unique_ptr<const detail::SignedDistance> signs_;  // the level's mesh and pseudo-normals
  std::vector<Node> nodes_;                 // [0] = the root; a node's children are contiguous
  std::vector<PreparedTriangle> prepared_;  // by triangle index of mesh()
};

}  // namespace lodforge
