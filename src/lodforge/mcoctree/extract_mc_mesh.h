#pragma once
/// Run-time extraction of a level of detail from a marching-cube octree
/// (Kim, ch. 6): the reverse walk of the LOD array, done on the compiled
/// run-time model (mc_lod_model.h).
///
/// Two outputs: an index buffer into the model's static vertex table
/// (extract_mc_indices: what a renderer needs per level, integer copies
/// only), and a standalone mesh with only the vertices used (extract_mc_mesh,
/// McExtractor::extract).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "lodforge/mcoctree/mc_lod_model.h"
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
  std::size_t centroid_vertices = 0;  ///< loop centroids used (see cell_polygonize.cpp)
};

/// The priority whose accumulated triangle count is nearest `triangles` (ties:
/// the smaller priority). O(#LOD array), integer work.
std::uint32_t priority_for_triangles(const std::vector<std::uint64_t>& accumulated,
                                     std::uint64_t triangles);
inline std::uint32_t priority_for_triangles(const McOctree& tree, std::uint64_t triangles) {
  return priority_for_triangles(tree.accumulated, triangles);
}
inline std::uint32_t priority_for_triangles(const McLodModel& model, std::uint64_t triangles) {
  return priority_for_triangles(model.accumulated, triangles);
}

/// The index buffer of priority N (clamped to the model's priorities):
/// out = model.accumulated[N] triangles, indices into model.positions.
/// Returns the triangle count.
///
/// The walk visits the cells whose parent has priority <= N (a prefix of the
/// cell array), skips those expanded themselves (until <= N), picks each
/// other cell's interval by comparing its starts with N and copies its
/// triangles: no floating point, no per-vertex work. `out` is reused (grown,
/// never shrunk in capacity).
std::size_t extract_mc_indices(const McLodModel& model, std::uint32_t priority,
                               std::vector<Triangle>& out);

/// Extracts one level as a standalone mesh (the used vertices, in order of
/// first use, with decoded normals and colours in [0,1]); the triangle count
/// is accumulated[priority]. Throws DataError when more than one
/// target is set or a percent is not finite. Budgets beyond the range are
/// clamped (result.clamped).
McExtractResult extract_mc_mesh(const McLodModel& model, const McExtractOptions& options = {});
/// The same from the build-time tree: compiles the run-time model first
/// (compile_mc_lod; for repeated extraction keep the model or an McExtractor).
McExtractResult extract_mc_mesh(const McOctree& tree, const McExtractOptions& options = {});

/// Extraction with its scratch arrays kept between calls (for repeated
/// extraction, e.g. every frame). Not copyable.
class McExtractor {
 public:
  /// Compiles and owns the run-time model of `tree`.
  explicit McExtractor(const McOctree& tree);
  /// Refers to `model`, which must outlive the extractor.
  explicit McExtractor(const McLodModel& model);
  McExtractor(const McExtractor&) = delete;
  McExtractor& operator=(const McExtractor&) = delete;

  /// Priority N (clamped) as a standalone mesh into `out` (its arrays
  /// reused). Returns the triangle count.
  std::size_t extract(std::uint32_t priority, TriangleMesh& out);
  /// The standalone mesh of an index buffer into model().positions (any cut
  /// of the model, e.g. a view-dependent one) into `out`: the used vertices
  /// in table order with decoded normals and colours. Returns the triangle
  /// count.
  std::size_t mesh_of(const std::vector<Triangle>& indices, TriangleMesh& out);
  /// Priority N (clamped) as an index buffer into model().positions.
  const std::vector<Triangle>& indices(std::uint32_t priority) {
    extract_mc_indices(*model_, priority, indices_);
    return indices_;
  }
  const McLodModel& model() const { return *model_; }
  /// Loop centroids among the vertices of the last extract().
  std::size_t centroid_vertices() const { return centroids_; }

 private:
  std::unique_ptr<const McLodModel> owned_;
  const McLodModel* model_;
  std::vector<Triangle> indices_;
  struct Seen {
    std::uint32_t epoch, index;  ///< index in the output when epoch is the current one
  };
  std::vector<Seen> seen_;
  std::uint32_t epoch_ = 0;
  std::size_t centroids_ = 0;
};

}  // namespace lodforge
