#pragma once
/// One chain contract for the three simplifiers: the levels of detail of a
/// mesh, each coarser than the one before, with the same meaning whichever
/// method makes them, so that callers (the scene LOD pipeline) use them alike.
#include <cstddef>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

enum class SimplifyMethod { kCluster, kDecimate, kQem };

/// "cluster", "decimate", "qem".
const char* to_string(SimplifyMethod method);

/// What the levels of a chain aim at. Counts are triangles, or line segments
/// for a mesh without triangles.
struct ChainTargets {
  /// Explicit counts, decreasing: level k has at most counts[k] (and fewer
  /// than level k - 1). Empty: the step rule below.
  std::vector<std::size_t> counts;
  /// The step rule: each level keeps at most (1 - step) x the count of the
  /// level before it as it came out (the previous *result*; before level 1:
  /// the input), step in (0, 1]; the chain ends at the first level of at most
  /// `smallest`.
  float step = 0.2f;
  std::size_t smallest = 4;
  std::size_t max_levels = 0;  ///< levels at most (0: no limit)
};

/// Levels 1..n of `mesh` made by `method` (level 0, the input, is not among
/// them), each meeting its target (above) and smaller than the level before
/// it; a level the method makes that misses its step is skipped, the next
/// one is tried against the same previous result. Never an empty level: a
/// method that would empty the mesh ends the chain before it. Empty when
/// nothing can be removed. The last level's stop_reason says why the chain
/// ended: kTargetReached (the last explicit count or `smallest` was met, or
/// max_levels), or the method's own reason (kCannotSimplify with its detail:
/// nothing more can be removed within a step); earlier levels carry
/// kTargetReached. A mesh without triangles (a line set) is clustered
/// whatever the method, as in the original tool. Throws DataError when an
/// index is out of range or a used coordinate is not finite.
std::vector<SimplifyResult> simplify_chain(const TriangleMesh& mesh, SimplifyMethod method,
                                           const ChainTargets& targets);

}  // namespace lodforge
