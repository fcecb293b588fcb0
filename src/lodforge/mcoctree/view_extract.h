#pragma once
/// View-dependent extraction from the marching-cube octree's run-time model
/// (mc_lod_model.h; what Kim's ch. 8 leaves as future work, "simplify only
/// the viewing area", with ch. 7's O(log n) per node through the octree,
/// Table 7.1 "view dependency"): every region is refined until its error,
/// projected on the screen, is under a pixel budget; regions outside the view
/// frustum stay coarse. The result is crack-free on the same terms as uniform
/// extraction (extract_mc_mesh.h).
///
/// The cut. Node x is refined while it is in the view frustum (its cube, grown
/// by its error and a quarter of its size, against the near plane and the four
/// side planes; there is no far plane: distant nodes project small) and
///
///     error(x) * pixels / (2 * depth(x) * tan(fov / 2)) > pixel_error
///
/// where depth(x) is the smallest depth of x's cube along the view direction
/// (a cube reaching the camera plane is refined). error(x) bounds the distance
/// from the full-resolution surface under x to any of x's triangulations: the
/// largest distance of the full-resolution vertices under x to x's triangles
/// (of each interval) plus, per finest cell, its longest triangle edge /
/// sqrt(3) (a point of a finest triangle is within that of one of its
/// vertices); infinite when x has no triangles (it hides the surface under
/// it, whose distance to the neighbours' triangles nothing bounds: such a node
/// in view is always refined); 0 for a finest cell. The result's error is
/// therefore measured one way, from the full-resolution surface to the cut.
///
/// Cracks. The model stores each cell's triangles for the split states of
/// uniform extraction, where the expanded nodes are those of priority 1..N.
/// A view-dependent cut keeps these rules, forcing expansions until they hold
/// (integer and array work: neighbour tables made once, priority compares):
///
///   rule                                     | forces
///   -----------------------------------------+---------------------------------
///   the numbering's neighbour rule: no cell  | the coarser cell's expansion
///   touching an expanded node is coarser     |
///   than it                                  |
///   a cell's expanded face/edge neighbours   | the cell's own expansion when a
///   are a prefix of them in priority order  | neighbour of higher priority is
///   (so its split state is one of uniform    | expanded; the lower-priority
///   extraction's, at N = the largest of     | neighbours' expansion otherwise
///   their priorities)                        |
///
/// so each emitted cell copies the triangles of its interval at that N, as
/// uniform extraction does, and neighbours agree on every shared face and edge.
///
/// Open models (McHoles::kOpen): a node none of whose finest cells has
/// triangles (all of it over a hole of the input) cannot be placed from the
/// model; it is never refined (it is emitted with its first interval when its
/// parent is, as it shows nothing at full resolution) and takes no part in
/// the crack rules of its neighbours, whose border there is open anyway.
///
/// Cost: preparation (McViewExtractor's constructor) is O(cells) hash
/// look-ups for the neighbour tables (18 same-level neighbours and the few
/// coarser cells the neighbour rule needs, 4 bytes each per cell) plus
/// O(triangles x depth) for the error bounds, on all threads; an extraction
/// is O(1) table reads per visited node (a few tens) plus O(output) copies.
/// Deterministic.
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/mc_lod_model.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// A perspective camera. Units are the model's.
struct McCamera {
  Vec3 position{0, 0, 1};
  Vec3 look_at{0, 0, 0};              ///< must differ from position
  Vec3 up{0, 1, 0};                   ///< must not be parallel to the view direction
  double fov = std::numbers::pi / 4;  ///< vertical field of view, radians, in (0, pi)
  double pixels = 1080;               ///< screen height in pixels, > 0
  double aspect = 16.0 / 9.0;         ///< width / height, > 0 (the side planes)
};

struct McViewOptions {
  McCamera camera;
  /// Largest projected error of an emitted node in view, in pixels, > 0.
  double pixel_error = 1;
};

struct McViewResult {
  TriangleMesh mesh;  ///< as extract_mc_mesh's: shared vertices, unit normals, colours
  /// Largest projected error bound over the emitted cells in view (pixels):
  /// <= pixel_error unless finest cells project larger (they cannot be
  /// refined); 0 when nothing in view has an error.
  double pixel_error = 0;
  std::size_t expanded = 0;  ///< nodes expanded
  std::size_t forced = 0;    ///< of which for the crack rules alone
  std::size_t culled = 0;    ///< emitted cells outside the frustum that have an error
};

/// Prepared view-dependent extraction of one model (the per-node cubes,
/// parents, error bounds and the same-level neighbour table), kept between
/// calls with its scratch arrays, e.g. for one extraction per frame. Refers to
/// `model`, which must outlive it. Not copyable.
class McViewExtractor {
 public:
  /// Throws DataError when the model is a prefix of a file (nodes whose
  /// children it does not hold), deeper than kMaxDepth levels, or its cells do
  /// not nest (a corrupted model).
  explicit McViewExtractor(const McLodModel& model);
  McViewExtractor(const McViewExtractor&) = delete;
  McViewExtractor& operator=(const McViewExtractor&) = delete;

  static constexpr int kMaxDepth = 19;

  /// The cut for `options` as a standalone mesh. Throws DataError for a
  /// degenerate camera (look_at = position, up parallel to the view, a field
  /// of view outside (0, pi), non-finite numbers) or pixels / pixel_error /
  /// aspect not > 0.
  McViewResult extract(const McViewOptions& options);

  /// The error bound of each cell (model units, see the header comment).
  const std::vector<float>& cell_errors() const { return error_; }
  const McLodModel& model() const { return model_; }

 private:
  struct Frame;
  void prepare_tree();
  void prepare_errors();
  std::uint32_t find(int level, std::int64_t x, std::int64_t y, std::int64_t z) const;
  void prepare_neighbours();
  /// The same-level neighbour of cell c at offset j (face or edge, 0..17).
  std::uint32_t neighbour(std::uint32_t c, int j) const { return near_[18 * std::size_t{c} + j]; }
  bool located(std::uint32_t c) const { return coords_[c][0] != McNode::kNone; }
  void expand(std::uint32_t c, bool forced);
  double on_screen(std::uint32_t c, const Frame& frame) const;
  void check(std::uint32_t c, const Frame& frame, double pixel_error);
  std::uint32_t split_priority(std::uint32_t c) const;
  void emit(const Frame& frame, McViewResult& result);

  const McLodModel& model_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint8_t> level_;
  std::vector<std::array<std::uint32_t, 3>> coords_;
  std::vector<float> error_;
  std::unordered_map<std::uint64_t, std::uint32_t>
      index_;                                       // (level, coords) -> cell, while preparing
  std::vector<std::uint32_t> near_;                 // 18 per cell
  std::vector<std::uint32_t> needs_begin_, needs_;  // per cell: coarser cells needed
  // Per extraction.
  std::vector<std::uint8_t> expanded_;
  std::vector<std::uint32_t> expanded_list_, queue_;
  std::vector<Triangle> indices_;
  McViewResult* stats_ = nullptr;
  McExtractor compactor_;
};

/// One view-dependent extraction (prepares an McViewExtractor and discards
/// it; keep one for repeated extraction).
McViewResult extract_mc_view(const McLodModel& model, const McViewOptions& options);

}  // namespace lodforge
