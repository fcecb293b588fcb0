#pragma once
/// Run-time extraction of a level of detail from a marching-cube octree
/// (Kim, ch. 6): the reverse walk of the LOD array.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lodforge/mcoctree/mc_octree.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// Which level to extract: exactly one of the three may be set; all unset
/// means the full resolution.
struct McExtractOptions {
  std::int64_t priority = -1;   ///< expand the nodes of priority 1..N (clamped to 0..#LOD array)
  std::int64_t triangles = -1;  ///< triangle budget: the priority whose count is nearest
  double percent = -1;          ///< percent of the full-resolution triangle count (0..100)
};

struct McExtractResult {
  TriangleMesh mesh;            ///< shared vertices, unit normals, colours if the model has them
  std::uint32_t priority = 0;   ///< the N extracted
  std::uint64_t requested = 0;  ///< the triangle count asked for (budget or percent)
  bool clamped = false;         ///< the request was outside 0..maximum and was clamped
  std::size_t centroid_vertices = 0;  ///< loop centroids added (see cell_polygonize.cpp)
};

/// The priority whose accumulated triangle count is nearest `triangles` (ties:
/// the smaller priority). O(#LOD array), integer work.
std::uint32_t priority_for_triangles(const McOctree& tree, std::uint64_t triangles);

/// Extracts one level; the triangle count is tree.accumulated[priority].
/// Throws std::invalid_argument when more than one target is set or a
/// percent is not finite. Budgets beyond the range are clamped (result.clamped).
///
/// The walk visits the LOD array from N down to 1 and triangulates each
/// visited node's children that are not themselves expanded (priority > N),
/// reading which of their faces and edges a neighbour splits from precomputed
/// priorities: integer and array work only, except the centroid of a loop that
/// no diagonal may cut (rare; counted in centroid_vertices).
McExtractResult extract_mc_mesh(const McOctree& tree, const McExtractOptions& options = {});

/// The extraction with its scratch arrays kept between calls (for repeated
/// extraction, e.g. every frame).
class McExtractor {
 public:
  explicit McExtractor(const McOctree& tree);
  /// Extracts priority N (clamped) into `out` (its arrays reused).
  std::size_t extract(std::uint32_t priority, TriangleMesh& out);
  std::size_t centroid_vertices() const { return centroids_; }

 private:
  const McOctree& tree_;
  std::vector<std::uint32_t> stamp_, remap_;
  std::uint32_t epoch_ = 0;
  std::size_t centroids_ = 0;
};

}  // namespace lodforge
