#pragma once
/// Corner signs of the marching-cube octree's lattice from a triangle mesh:
/// signed distances by the exact closest point and the angle-weighted
/// pseudo-normal, a band measured by scanning the triangles, the rest by
/// flood fill (detail of build_mc_octree).
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "lodforge/core/progress.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/sign_lattice.h"
#include "lodforge/mesh/adjacency.h"
#include "lodforge/metrics/triangle_bvh.h"

namespace lodforge::detail {

/// Signed distance to a mesh: the exact closest point, and the side by the
/// angle-weighted pseudo-normal there (Baerentzen & Aanaes 2005, "Signed
/// distance computation using the angle weighted pseudonormal": face, edge or
/// vertex normal by where on the triangle the closest point lies). Queries
/// are const and may run from any number of threads.
class SignedDistance {
 public:
  /// Takes the mesh as the distances' surface: welded (shared vertices, for
  /// the pseudo-normals), wound outwards, triangle indices < #V. Missing
  /// vertex normals are filled with the angle-weighted ones.
  explicit SignedDistance(TriangleMesh mesh);

  struct Sample {
    float distance;  ///< signed: negative inside
    ClosestPoint at;
    /// Nearest an open rim: the side is unknown (distance >= 0). Nearest a
    /// fold (a vertex or edge whose faces turn back onto each other, so that
    /// its pseudo-normal cancels) the side is outside: the fold encloses no
    /// volume, and a point inside the solid next to it is nearer a face.
    bool open;
  };
  /// The signed distance of p (an exact closest-point query; `hint` as in
  /// TriangleBvh, it never changes the answer).
  Sample operator()(const Vec3& p, std::uint32_t hint = kNone) const;
  /// The signed distance of p whose closest surface point is cp.
  Sample sample(const Vec3& p, const ClosestPoint& cp) const;
  /// The pseudo-normal at a closest point and whether its feature (face,
  /// edge or vertex) is on an open rim (a fold is not).
  std::pair<Vec3, bool> feature(const ClosestPoint& cp) const;
  bool has_rims() const { return !adjacency_.boundary_edges.empty(); }
  const TriangleMesh& mesh() const { return mesh_; }
  /// The closest-point hierarchy, built on the first call (thread-safe; a
  /// closed mesh's band and edge points come from the triangle scan alone and
  /// never need it). Among equally near triangles its queries take the lowest
  /// index, so that answers do not depend on hints or threads.
  const TriangleBvh& bvh() const;
  /// The point of triangle t nearest to p, as a closest-point answer.
  ClosestPoint on_triangle(const Vec3& p, std::uint32_t t) const;
  /// The unit normal at a closest point (vertex normals interpolated; the
  /// face normal where they cancel).
  Vec3 normal_at(const ClosestPoint& cp) const;

 private:
  // Kinds of feature (bits): on an open rim, on a fold.
  static constexpr std::uint8_t kRimFeature = 1, kFoldFeature = 2;
  std::pair<Vec3, std::uint8_t> feature_kind(const ClosestPoint& cp) const;

  TriangleMesh mesh_;
  MeshAdjacency adjacency_;
  std::vector<Vec3> face_normal_, vertex_normal_, edge_normal_;
  std::vector<std::uint8_t> open_vertex_, open_edge_;
  mutable std::unique_ptr<TriangleBvh> bvh_;
  mutable std::once_flag bvh_once_;
};

/// The sign lattice of sd's mesh at `resolution` (empty_lattice): exact
/// signed distances in a band one cell wide around the triangles, found by
/// scanning each triangle over the lattice points near it; the root cube's
/// boundary outside; every other point, and the band points nearest an open
/// rim, by a breadth-first flood fill from those; then every flooded point
/// whose sign disagrees with a neighbour's gets an exact one (repeated until
/// no sign changes); a closed mesh's inside regions of one part are then
/// joined by bridges (bridge_mesh_parts). Fills stats' band_points,
/// flooded_points, sign_repairs and part_bridges; reports "signs" (slabs of the lattice) to
/// `progress`. The result depends neither on the threads nor on how work is split. Throws DataError
/// when the mesh's vertices are all at one point.
Lattice make_mesh_lattice(const SignedDistance& sd, int resolution, McBuildStats& stats,
                          const ProgressCallback& progress);

/// The resolution at which the full-resolution model of `m` has about as
/// many triangles as `m` (2..1000).
int mesh_resolution(const TriangleMesh& m);

}  // namespace lodforge::detail
