#pragma once
/// The face rules of vertex_clustering (see vertex_clustering.h for the
/// contract): remapping a level's triangles and lines onto the cells of the
/// next, dropping doublets, collapsed triangles and repeated lines, and the
/// vertices nothing uses. Internal to simplify/.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/detail/clustering_cut.h"

namespace lodforge::detail::clustering {

/// Open-addressing set of line segments ({lo, hi}); insert() says whether
/// the segment was new.
class SegmentSet {
 public:
  /// Empties the set, sized for `expected` segments (keeps its memory).
  void reset(std::size_t expected) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, {kNone, kNone});
    mask_ = cap - 1;
  }
  bool insert(const Segment& key) {
    std::uint64_t h = 0;
    for (std::uint32_t k : key) h = (h ^ k) * 0x9e3779b97f4a7c15ull;
    std::size_t i = (h ^ (h >> 29)) & mask_;
    while (true) {
      auto& s = slots_[i];
      if (s[0] == kNone) {
        s = key;
        return true;
      }
      if (s == key) return false;
      i = (i + 1) & mask_;
    }
  }

 private:
  Buffer<Segment> slots_;
  std::size_t mask_ = 0;
};

/// The buffers of remap_faces, kept over the levels of one call: allocating
/// them afresh per level costs page faults (freed large blocks go back to
/// the system) more than the work in them.
struct RemapScratch {
  struct Entry {
    std::uint32_t k1, k2, index;  // the canonical rotation's last corners; position in the run
  };
  Buffer<Entry> run;
  Buffer<Triangle> run_tris;
  Buffer<std::uint32_t> run_origin;
  Buffer<std::uint32_t> run_start;   // vertex -> its run of kept triangles (when there are lines)
  Buffer<std::uint32_t> off, upper;  // vertex -> the larger ends of the third edges at it
  Buffer<Segment> not_edges;
  SegmentSet seen_lines;
  Buffer<std::uint32_t> keep;  ///< the result: new vertex -> kept index or kNone
};

/// The last two corners of triangle t's rotation that starts at its corner
/// `vertex` (orientation kept), as one 64-bit key (compared
/// lexicographically); selects, not branches: which corner is `vertex` is
/// data.
inline std::uint64_t rotation_key(const Triangle& t, std::uint32_t vertex) {
  const bool first = t[0] == vertex, second = t[1] == vertex;
  const std::uint32_t k1 = first ? t[1] : second ? t[2] : t[0];
  const std::uint32_t k2 = first ? t[2] : second ? t[0] : t[1];
  return std::uint64_t(k1) << 32 | k2;
}

/// dedupe_run (below) for any n: out of line, for the runs of more than
/// three triangles and those with doublets.
[[gnu::noinline]] std::size_t dedupe_long_run(Triangle* tris, std::uint32_t* origin, std::size_t n,
                                              std::uint32_t vertex, RemapScratch& scratch);

/// Sorts the run [tris, tris + n) of triangles whose smallest corner is
/// `vertex` (and their origins) by canonical rotation (`vertex` first,
/// orientation kept; ties in run order) and squeezes out the doublets (equal
/// rotations: the first stays); returns how many are left, at the front.
/// Runs of two and three (nine in ten) are inlined into the callers.
inline std::size_t dedupe_run(Triangle* tris, std::uint32_t* origin, std::size_t n,
                              std::uint32_t vertex, RemapScratch& scratch) {
  auto key = [&](const Triangle& t) { return rotation_key(t, vertex); };
  if (n < 2) return n;
  if (n == 2) {  // the commonest run: its order by stores to computed slots, not a branch
    const std::uint64_t k0 = key(tris[0]), k1 = key(tris[1]);
    if (k0 == k1) return 1;
    const std::size_t second = k1 < k0;  // where the first goes
    const Triangle t0 = tris[0], t1 = tris[1];
    const std::uint32_t o0 = origin[0], o1 = origin[1];
    tris[second] = t0;
    tris[1 - second] = t1;
    origin[second] = o0;
    origin[1 - second] = o1;
    return 2;
  }
  if (n == 3) {  // each to its rank among the keys
    const std::uint64_t k0 = key(tris[0]), k1 = key(tris[1]), k2 = key(tris[2]);
    if (k0 != k1 && k0 != k2 && k1 != k2) {
      const std::size_t r0 = (k1 < k0) + (k2 < k0), r1 = (k0 < k1) + (k2 < k1),
                        r2 = (k0 < k2) + (k1 < k2);
      const Triangle t0 = tris[0], t1 = tris[1], t2 = tris[2];
      const std::uint32_t o0 = origin[0], o1 = origin[1], o2 = origin[2];
      tris[r0] = t0;
      tris[r1] = t1;
      tris[r2] = t2;
      origin[r0] = o0;
      origin[r1] = o1;
      origin[r2] = o2;
      return 3;
    }
  }
  return dedupe_long_run(tris, origin, n, vertex, scratch);
}

/// Builds the faces of `to` (which holds the new vertices, new_count of them)
/// from the previous level's faces: `mapped[i]` is its i-th triangle with
/// its corners already mapped to new vertices, and the triangles with three
/// distinct corners must come sorted by their smallest corner (they do: the
/// previous level's triangles are sorted by smallest vertex and the map to
/// cells is monotone); `origin[i]` is its input triangle. Applies the face
/// rules; reads nothing of `to` but its faces, so that it can run beside the
/// choice of the new vertices (number_used_vertices and compact_vertices
/// then drop those nothing uses). `line_candidates` holds the lines found
/// before (they come first); the previous level's `lines`, mapped by
/// `vertex_map`, follow.
///
/// | remapped triangle          | becomes                                    |
/// |----------------------------|--------------------------------------------|
/// | 3 distinct vertices        | kept, unless an equal rotation was kept    |
/// | 2 distinct vertices        | a line (dropped if no_lines)               |
/// | 1 vertex                   | dropped                                    |
/// | remapped line, 2 vertices  | a line                                     |
/// | line, 1 vertex             | dropped                                    |
/// | line equal to a kept line or to an edge of a kept triangle | dropped    |
///
/// A doublet has the same smallest corner, so it lies in the same run of
/// consecutive triangles: each run is sorted by its canonical rotation (the
/// smallest corner first, orientation kept) and the first of equal keys kept.
/// The output stays sorted by smallest vertex, so that neighbours in memory
/// are neighbours in space for the levels to come.
void remap_faces(std::span<const Triangle> mapped, std::span<const std::uint32_t> origin,
                 std::span<const Segment> lines, std::span<const std::uint32_t> vertex_map,
                 std::size_t new_count, bool no_lines, Buffer<Segment>& line_candidates, Cut& to,
                 RemapScratch& scratch);

/// The second half of remap_faces, once `to.tris` holds the kept triangles:
/// appends the previous level's lines, mapped, to `line_candidates` and
/// keeps in `to.lines` those that are neither an edge of a kept triangle nor
/// a line seen before.
void finish_faces(std::span<const Segment> lines, std::span<const std::uint32_t> vertex_map,
                  std::size_t new_count, Buffer<Segment>& line_candidates, Cut& to,
                  RemapScratch& scratch);

/// Dropping the vertices no triangle or line uses, keeping the order, in two
/// steps: once `to` has its faces (remap_faces), of new_count vertices,
/// number_used_vertices leaves the map (new vertex -> kept index or kNone) in
/// `scratch.keep`, renumbers the faces and returns how many are kept (it reads
/// nothing but the faces, so it can run beside the choice of the vertices);
/// once the vertices are there too, compact_vertices drops the others.
std::size_t number_used_vertices(std::size_t new_count, Cut& to, RemapScratch& scratch);
void compact_vertices(std::size_t new_count, std::size_t kept, Cut& to,
                      const RemapScratch& scratch);

}  // namespace lodforge::detail::clustering
