#pragma once
/// The representative choice of vertex_clustering (see vertex_clustering.h
/// for the heuristics): the triangles around each cell, the plane quadrics
/// of Garland and Heckbert, "Surface Simplification Using Quadric Error
/// Metrics" (SIGGRAPH 1997), summed per cell as in P. Lindstrom, "Out-of-core
/// simplification of large polygonal models" (SIGGRAPH 2000), and the
/// choice of one representative per cell. Internal to simplify/.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "lodforge/core/quadric.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/detail/clustering_cut.h"

namespace lodforge::detail::clustering {

/// The weights of the four heuristics (area, volume, weighted mean, quadric).
struct Weights {
  double area = 0, volume = 0, mean = 0, quadric = 0;
};

/// The triangles of a level around each cell of the next: for cell j, the
/// entries [start[j], start[j + 1]) of `entry`, each 4 x triangle + the index
/// of its one corner inside the cell (0, 1, 2), or + 3 when two or three
/// corners are inside (it collapses). One pass over the triangles, in
/// triangle order, so each cell's list is sorted.
struct CellFaces {
  Buffer<std::uint32_t> start;
  Buffer<std::uint32_t> entry;

  /// `mapped`: the triangles with their corners replaced by their cells.
  /// Lists only the cells with `wanted[cell]` (the others get empty lists).
  void build(std::span<const Triangle> mapped, std::span<const char> wanted) {
    count(mapped, wanted);
    fill(mapped, wanted);
  }

  /// build in two passes over the triangles, which may run on different
  /// threads, one after the other: count into start[cell + 1]; then turn
  /// the counts into starts, fill with start[cell]++ (which leaves the
  /// starts shifted down by one cell) and shift them back.
  void count(std::span<const Triangle> mapped, std::span<const char> wanted);
  void fill(std::span<const Triangle> mapped, std::span<const char> wanted);

 private:
  /// Whether each corner starts an entry: its cell is wanted and no earlier
  /// corner of the triangle is in it (0 or 1, for adding). Branch-free:
  /// whether corners share a cell is data the branch predictor cannot learn
  /// (about half the triangles collapse at a level), so each corner adds 0
  /// or 1 (an entry only at a cell's first corner).
  static std::array<std::uint32_t, 3> adds(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                           std::span<const char> wanted) {
    const std::uint32_t ab = a != b, ac = a != c, bc = b != c;
    return {std::uint32_t(wanted[a]), ab & std::uint32_t(wanted[b]),
            ac & bc & std::uint32_t(wanted[c])};
  }
};

/// Adds the area-weighted plane quadric of each triangle of `tris` (over
/// `pos`) to the quadrics of the cells its corners map to (`mapped`, in
/// triangle order): area x the squared distance to the triangle's plane;
/// nothing for a degenerate triangle.
void add_plane_quadrics(std::span<const Vec3> pos, std::span<const Triangle> tris,
                        std::span<const Triangle> mapped, Buffer<Quadric>& quadric);

/// The cells of a cut at `depth`: cell j holds the previous level's
/// vertices [begin[j], begin[j + 1]) (runs in octree order); `of[i]` is the
/// cell of vertex i.
struct Cells {
  Buffer<std::uint32_t> begin;
  Buffer<std::uint32_t> of;
  int depth = 0;

  std::size_t count() const { return begin.size() - 1; }
};

/// Chooses the representatives of a level's cells, keeping per-thread
/// scratch memory over the levels of one call.
class RepresentativePicker {
 public:
  RepresentativePicker();
  ~RepresentativePicker();
  RepresentativePicker(const RepresentativePicker&) = delete;
  RepresentativePicker& operator=(const RepresentativePicker&) = delete;

  /// Fills next.pos, weight, orig and code of every cell of `cells` over
  /// `prev`, and next.quadric when `weights.quadric > 0` (each cell's the
  /// sum of its vertices'; already summed from the triangles, by
  /// add_plane_quadrics, when prev has none). A cell of one vertex keeps it;
  /// a cell of several takes the winner of the heuristics of
  /// vertex_clustering.h among its vertices and Lindstrom's point. `faces`:
  /// the triangles around the cells (null when neither area nor volume is
  /// weighted or prev has no triangle); `corner`: which vertices of prev are
  /// corners of a triangle (empty: all). Cells in parallel (TBB).
  void pick(const Cut& prev, const Cells& cells, const CellFaces* faces, const Weights& weights,
            std::span<const char> corner, const Octree& octree, Cut& next);

 private:
  struct PerThread;
  std::unique_ptr<PerThread> per_thread_;
};

}  // namespace lodforge::detail::clustering
