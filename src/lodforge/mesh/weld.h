#pragma once
/// Merging of coincident vertices ("welding"), the cure for the doublets of
/// real files (coordinates are de-duplicated, as in the LODCreator) and for STL's triangle
/// soup.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct WeldOptions {
  /// 0: merge only vertices with exactly equal positions (+0 == -0).
  /// > 0: also merge a vertex into an earlier kept vertex closer than this
  /// (object-space units, Euclidean). Greedy in vertex order, so a chain of
  /// close vertices is not merged transitively beyond one epsilon.
  float epsilon = 0;
  /// true: merge only if normals, texcoords and colours are equal as well
  /// (keeps attribute seams). false: the first vertex's attributes win.
  bool match_attributes = false;
  /// Drop triangles that now use a vertex twice (and lines of zero length).
  bool remove_degenerate = true;
  /// Drop triangles equal to an earlier one up to rotation (same orientation),
  /// and lines equal to an earlier one in either direction.
  bool remove_duplicates = false;
};

struct WeldResult {
  TriangleMesh mesh;                       ///< welded mesh; triangles keep their order
  std::vector<std::uint32_t> remap;        ///< #V of the input: old vertex -> new vertex
  std::vector<std::uint32_t> face_origin;  ///< #F of the output: new triangle -> old triangle
  std::size_t merged_vertices = 0;         ///< input vertices merged into another
  std::size_t removed_degenerate = 0;      ///< triangles dropped as degenerate
  std::size_t removed_duplicates = 0;      ///< triangles dropped as duplicates
  std::size_t removed_lines = 0;           ///< line segments dropped (degenerate or duplicate)
};

/// Welds `mesh`. Kept vertices keep their relative order (each new vertex is
/// the first old vertex of its group). Expected O(V + F) (hashing). Never
/// throws except std::bad_alloc. Precondition: indices < #V (asserted).
WeldResult weld(const TriangleMesh& mesh, const WeldOptions& options = {});

}  // namespace lodforge
