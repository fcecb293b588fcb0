#pragma once
/// The indexed triangle mesh every algorithm works on.
///
/// Shapes: positions #V, triangles #F (indices into positions, counter-clockwise
/// seen from the front). The optional attributes are either empty or exactly as
/// long as what they attach to: normals, texcoords and colors per vertex (#V),
/// material per triangle (#F). Line segments (#L, from IndexedLineSets or faces
/// that collapsed to lines) are kept beside the triangles.
#include <array>
#include <cstdint>
#include <vector>

#include "lodforge/core/math.h"

namespace lodforge {

using Triangle = std::array<std::uint32_t, 3>;
using Segment = std::array<std::uint32_t, 2>;

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<Vec3> normals;             ///< empty or #V, unit length
  std::vector<Vec2> texcoords;           ///< empty or #V
  std::vector<Vec3> colors;              ///< empty or #V, RGB in [0,1]
  std::vector<std::uint32_t> materials;  ///< empty or #F, index into the caller's material list
  std::vector<Segment> lines;            ///< line segments, indices into positions

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_texcoords() const { return !texcoords.empty(); }
  bool has_colors() const { return !colors.empty(); }
  bool has_materials() const { return !materials.empty(); }
  Box3 bounds() const {
    Box3 b;
    for (const auto& p : positions) b.add(p);
    return b;
  }
};

}  // namespace lodforge
