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
  /// The input's parts whose bounds, grown by `near`, meet no model part's
  /// bounds (a part thinner than about a cell that left no surface), in the
  /// input's order, at most `most`; empty when the counts are equal or
  /// `near` is 0.
  std::vector<McPart> vanished;
  bool kept() const { return input_parts == model_parts; }
};

/// Compares the parts of `input` with those of `full` (extract_mc_mesh of
/// the model at full resolution); `near`: how far a model part may lie from
/// an input part it stands for (a cell; 0: vanished parts are not looked
/// for). O(V + F + input parts x model parts) expected. Never throws beyond
/// allocation.
McPartsCheck check_mc_parts(const TriangleMesh& input, const TriangleMesh& full,
                            std::size_t most = 3, float near = 0);

/// The resolution (cells across the longest side of `box`, the input's
/// bounds) at which `part` is about two cells across its thinnest side, so
/// that the lattice has points inside it; above 1000 (the largest allowed)
/// when it is that thin.
int resolution_to_keep(const McPart& part, const Box3& box);

}  // namespace lodforge
