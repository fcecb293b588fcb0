#pragma once
/// What every simplifier returns: the simplified mesh, where its parts came
/// from, the error it reached and why it stopped. Stopping short of the target
/// is a result, not a failure (meshoptimizer's contract).
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// Why a simplifier stopped.
enum class StopReason {
  kTargetReached,       ///< the triangle target (count or ratio) was met
  kErrorBudgetReached,  ///< the next step would exceed the error budget
  kCannotSimplify,      ///< no allowed operation is left (topology, borders, features...)
  kNoReduction,         ///< the target asked for no reduction
};

/// "target reached", "error budget reached", ...
const char* to_string(StopReason reason);

/// The target shared by all simplifiers. Give a triangle count or a ratio
/// (the smaller result wins if both are given) and/or an error budget; `{}`
/// keeps the mesh as it is.
struct SimplifyTarget {
  std::size_t triangles = 0;  ///< stop at or below this many triangles (0: unused)
  float ratio = 0;            ///< stop at or below ratio x input triangles (0: unused)
  /// Stop before the error (in model units) would exceed this.
  float max_error = std::numeric_limits<float>::infinity();

  /// The triangle count the target asks for, given the input's.
  std::size_t triangle_target(std::size_t input_triangles) const;
};

struct SimplifyResult {
  TriangleMesh mesh;
  /// #V of `mesh`: the original vertex each new vertex stands for (a birth map;
  /// for a vertex placed at a new position, the original vertex it merged into).
  std::vector<std::uint32_t> vertex_map;
  /// #F of `mesh`: the original triangle each new triangle descends from.
  std::vector<std::uint32_t> face_map;
  /// The geometric error reached, in model units. Each simplifier documents
  /// whether this is an upper bound or a measurement (and of what).
  float error = 0;
  StopReason stop_reason = StopReason::kNoReduction;
  std::string stop_detail;  ///< a human sentence, e.g. "every remaining edge is a border"
};

/// Throws DataError (naming `who`) when a triangle or line index of `mesh` is
/// out of range or a coordinate a triangle or line uses is not finite.
void check_simplify_input(const TriangleMesh& mesh, std::string_view who);

}  // namespace lodforge
