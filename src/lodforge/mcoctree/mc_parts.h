#pragma once
/// Whether a model keeps the input's parts: the connected parts of the input
/// mesh against those of the model's surface at full resolution. A part
/// thinner than about a cell comes apart into pieces or vanishes (the
/// lattice cannot hold both of its sides), a gap narrower than a cell may
/// join two parts; the counts say which happened, the smallest parts of the
/// model say where.
#include <cstddef>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct McPart {
  std::size_t triangles = 0;
  Box3 bounds;
};

struct McPartsCheck {
  std::size_t input_parts = 0;  ///< connected parts of the input (triangle_parts)
  std::size_t model_parts = 0;  ///< of the model's full-resolution mesh
  /// The model's smallest parts, fewest triangles first (ties: first found),
  /// at most `most` of them; empty when the counts are equal.
  std::vector<McPart> smallest;
  bool kept() const { return input_parts == model_parts; }
};

/// Compares the parts of `input` with those of `full` (extract_mc_mesh of
/// the model at full resolution). O(V + F) expected. Never throws beyond
/// allocation.
McPartsCheck check_mc_parts(const TriangleMesh& input, const TriangleMesh& full,
                            std::size_t most = 3);

}  // namespace lodforge
