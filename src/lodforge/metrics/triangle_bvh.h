#pragma once
/// A bounding volume hierarchy over a mesh's triangles answering exact
/// closest-point queries: which point of the surface is nearest to p, on which
/// triangle, at which barycentric coordinates.
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/metrics/closest_point_on_triangle.h"

namespace lodforge {

/// How the hierarchy is built (the queries are the same).
enum class BvhBuild {
  /// Binned surface-area heuristic: tight boxes, the fewest nodes visited per
  /// query; for many queries.
  kSah,
  /// Triangles in Morton order of their centroids, each node split where the
  /// highest bit in which its triangles' codes differ changes (Lauterbach et
  /// al. 2009, "Fast BVH Construction on GPUs": LBVH). Several times faster
  /// to build, somewhat more nodes visited per query; for a few queries.
  kMorton
};

struct BvhOptions {
  int leaf_size = 4;           ///< at most this many triangles per leaf (1..32)
  int bins = 16;               ///< SAH bins along the split axis (2..64)
  bool vertex_normals = true;  ///< normal_at interpolates the mesh's vertex normals if it has any
  BvhBuild build = BvhBuild::kSah;
};

/// The answer to a closest-point query.
struct ClosestPoint {
  static constexpr std::uint32_t kNone = lodforge::kNone;
  Vec3 point;                          ///< the nearest surface point
  std::uint32_t triangle = kNone;      ///< index into mesh.triangles
  std::array<float, 3> barycentric{};  ///< of `point` in that triangle
  float distance_squared = std::numeric_limits<float>::infinity();

  bool found() const { return triangle != kNone; }
};

/// The answer to a first-hit query.
struct RayHit {
  float distance = std::numeric_limits<float>::infinity();  ///< t along the unit direction
  std::uint32_t triangle = kNone;                           ///< index into mesh.triangles
  bool hit() const { return triangle != kNone; }
};

/// Built once per mesh, then queried from any number of threads at once
/// (queries are const and allocate nothing). The mesh is referenced, not
/// copied: it must outlive the hierarchy and stay unchanged.
///
/// Construction: binned surface-area heuristic on triangle centroids (or
/// Morton order, BvhOptions::build), nodes in one flat array in depth-first
/// order. Queries: stack traversal, nearer child
/// first, subtrees pruned when their box is farther than the best distance so
/// far; with a hint, from the hint's leaf up through the other children of its
/// ancestors (so a query that may stop early stops near the hint). Degenerate triangles take part
/// as the segments or points they are.
class TriangleBvh {
 public:
  /// Preconditions: triangle indices < #V (assert). A mesh without triangles
  /// gives an empty hierarchy whose queries find nothing.
  explicit TriangleBvh(const TriangleMesh& mesh, const BvhOptions& options = {});

  /// Exact closest point of the surface to `p`; not found() only when the mesh
  /// has no triangles. `hint`, a triangle likely to be close (e.g. the answer
  /// for the previous of a run of nearby queries), is tested first so that the
  /// traversal starts with a tight bound; it never changes the distance found.
  ClosestPoint closest_point(const Vec3& p, std::uint32_t hint = ClosestPoint::kNone) const;

  /// As closest_point(p, hint), but the search ends at the first triangle
  /// whose squared distance is <= `stop_squared`: the answer is exact when
  /// the surface is farther than that, else it is some triangle within it.
  /// For maxima of distances (Hausdorff), where a point nearer than the
  /// largest distance known does not matter and most queries end at the hint.
  ClosestPoint closest_point_unless_within(const Vec3& p, float stop_squared,
                                           std::uint32_t hint = ClosestPoint::kNone) const;

  /// As closest_point(p), but among triangles at the same distance (within a
  /// relative 1e-5 of the squared distance plus float rounding noise, e.g. at
  /// a shared edge or vertex) takes the one whose surface normal there
  /// (normal_at) makes the smallest angle with `normal`: the tie rule of the
  /// normal deviation measure. distance_squared is still the exact minimum;
  /// point, triangle and barycentric are those of the chosen triangle.
  ClosestPoint closest_point(const Vec3& p, const Vec3& normal,
                             std::uint32_t hint = ClosestPoint::kNone) const;

  /// As closest_point(p, hint), but among triangles at exactly the same
  /// squared distance (e.g. a point whose nearest surface point is a vertex
  /// they share) the lowest index wins. The answer then depends neither on
  /// `hint` nor on the hierarchy's shape, so callers whose hints follow how
  /// work is split among threads get the same triangle for any thread count.
  ClosestPoint closest_point_lowest_index(const Vec3& p,
                                          std::uint32_t hint = ClosestPoint::kNone) const;

  /// The first triangle the ray origin + t * direction meets, 0 <= t <=
  /// max_distance, t along the unit direction (the direction's length is
  /// ignored), from either side (metrics/ray.h); among triangles at exactly
  /// the same t, the lowest index of those the traversal reaches (a tied
  /// triangle in a box whose entry rounds beyond t may be missed: the
  /// distance is exact, the triangle one of the tied ones, the same for a
  /// given hierarchy). Not hit() when there is none, or when the
  /// direction is zero. Preconditions: origin and direction finite. Nodes
  /// nearer the origin first, skipping those entered beyond the nearest hit
  /// so far.
  RayHit first_hit(const Vec3& origin, const Vec3& direction,
                   float max_distance = std::numeric_limits<float>::infinity()) const;

  /// Unit surface normal at a found point: the mesh's per-vertex normals
  /// interpolated with the barycentric coordinates when it has them (and
  /// options.vertex_normals), else the face normal. Zero for a degenerate triangle without vertex
  /// normals.
  Vec3 normal_at(const ClosestPoint& at) const;

  bool empty() const { return nodes_.empty(); }
  std::size_t node_count() const { return nodes_.size(); }
  int depth() const { return depth_; }

 private:
  struct Node {
    Vec3 lo, hi;
    std::uint32_t index;  // interior: right child (left is this + 1); leaf: first triangle
    std::uint32_t count;  // 0 for interior nodes, else triangles in the leaf
  };

  // How a query chooses among triangles at the same distance: the first one
  // found, the lowest index (exact ties), or the best normal (near ties).
  enum class Tie { kFirst, kLowestIndex, kNormal };
  template <Tie kRule>
  ClosestPoint query(const Vec3& p, const Vec3& normal, std::uint32_t hint,
                     float stop_squared = -1) const;
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, int depth,
                      std::vector<Vec3>& centroid, std::vector<Vec3>& lo, std::vector<Vec3>& hi);
  void build_morton(const std::vector<Vec3>& centroid, const std::vector<Vec3>& lo,
                    const std::vector<Vec3>& hi);
  std::uint32_t build_morton(std::uint32_t begin, std::uint32_t end, int depth,
                             const std::vector<std::uint64_t>& keyed, const std::vector<Vec3>& lo,
                             const std::vector<Vec3>& hi);

  const TriangleMesh* mesh_;
  BvhOptions options_;
  std::vector<Node> nodes_;
  std::vector<PreparedTriangle> corners_;  // triangles in leaf order
  std::vector<std::uint32_t> order_;       // leaf order -> mesh triangle index
  std::vector<std::uint32_t> slot_;        // mesh triangle index -> leaf order
  std::vector<std::uint32_t> parent_;      // node -> its parent (the root: 0)
  std::vector<std::uint32_t> leaf_of_;     // leaf order -> the leaf holding it
  std::vector<Vec3> face_normals_;         // per mesh triangle, unit or zero
  float tie_floor_ = 0;                    // absolute tie tolerance on squared distances
  int depth_ = 0;
};

}  // namespace lodforge
