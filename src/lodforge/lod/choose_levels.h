#pragma once
/// The levels of one mesh worth writing, and the error each switches at:
/// the chain of simplify_levels, thinned by space_levels (automatic mode) or
/// halving triangle counts (manual mode). The one place every scene format
/// (VRML 1.0 and Inventor, VRML97 and X3D, glTF) gets its levels from, so a
/// shape is given the same levels whatever file it was read from.
#include <cstddef>
#include <string>
#include <vector>

#include "lodforge/core/progress.h"
#include "lodforge/lod/simplify_levels.h"
#include "lodforge/lod/switching_ranges.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct ChooseLevelsOptions {
  SimplifyMethod method = SimplifyMethod::kQem;
  float min_diff = 0.2f;  ///< candidates: each <= (1 - min_diff) x the previous one
  /// Automatic mode: the spacing and size rules of space_levels.
  SpacingOptions spacing;
  /// Camera height angle (resolved by the caller) and error range.
  RangeOptions range;
  /// At most this many simplified levels (0: no limit).
  std::size_t max_simplified = 0;
  /// Manual mode when >= 2: quality - 2 simplified levels, each with half the
  /// triangles of the one before it. Below 2: automatic.
  int quality = -1;
  std::size_t measure_samples = 0;  ///< 0: measure_samples_for
  int threads = 0;                  ///< 0: all cores
  ProgressCallback progress;        ///< simplify_levels' stage "measure"
};

struct ChosenLevel {
  /// The simplified mesh with its maps to the input (vertex_map, face_map)
  /// and its measured error (kErrorMargin x the two-sided Hausdorff distance
  /// from level 0, model units).
  MeasuredLevel measured;
  /// The error whose switch_distance is where this level is shown: at least
  /// measured.error, larger where the spacing pushes the switch outwards.
  double switch_error = 0;
};

struct ChosenLevels {
  std::vector<ChosenLevel> levels;  ///< simplified levels 1..n (level 0 is the input)
  std::string method;               ///< the simplifier that made them
  /// Why the chain ended: the vanishing error, the level limit, or the
  /// simplifier's own reason.
  std::string stop_reason;
};

/// The levels of `mesh` (triangles and/or line segments; local units) whose
/// bounding sphere has radius `radius`. Deterministic for any thread count.
/// Throws DataError for an index out of range or a used coordinate that is
/// not finite.
ChosenLevels choose_levels(const TriangleMesh& mesh, double radius,
                           const ChooseLevelsOptions& options);

}  // namespace lodforge
