#pragma once
/// The chain of simplified levels of one mesh with the method the user chose,
/// each level keeping at most (1 - min_diff) of the previous level's triangles
/// (the original's "min diff"), each with its error measured against level 0.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "lodforge/core/progress.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/level_chain.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

struct LevelChainOptions {
  SimplifyMethod method = SimplifyMethod::kQem;
  float min_diff = 0.2f;       ///< each level <= (1 - min_diff) x the previous one
  std::size_t max_levels = 0;  ///< simplified levels at most (0: until exhausted)
  /// Explicit triangle counts per level instead of the min-diff progression
  /// (manual mode); decreasing.
  std::vector<std::size_t> triangle_targets;
  std::size_t measure_samples = 0;  ///< compare_meshes samples (0: measure_samples_for)
  int threads = 0;                  ///< for the measurements (0: all cores)
  /// When set, only the levels it keeps are measured in full: it is given
  /// every level with its estimated error (DeviationMeter::estimate) and
  /// returns the indices of the levels it would keep; those are measured in
  /// full, the others keep their estimate (MeasuredLevel::measured_in_full
  /// false) and must not be written. Unset: every level is measured in full.
  std::function<std::vector<std::size_t>(std::span<const struct MeasuredLevel> levels)> keep;
  /// With `keep`: the size rule of the spacing (SpacingOptions::max_ratio x
  /// level 0) as a count of triangles plus line segments. The leading levels
  /// that draw more can never be kept, so they are not estimated either:
  /// `keep` is given the levels from the first that draws at most this many
  /// (its indices count from there), and the ones before keep error 0 and
  /// measured_in_full false. 0: no such levels.
  std::size_t most_kept_drawn = 0;
  /// Stage "measure": levels measured of the chain's levels, reported once
  /// the chain is made (0 of n) and after each level (from worker threads).
  ProgressCallback progress;
};

/// Sampling finds the largest distance between two surfaces only up to the
/// sample spacing, so the error the ranges use is the measured two-sided
/// Hausdorff distance enlarged by this factor: a denser measurement (another
/// seed, more samples) stays below it.
constexpr double kErrorMargin = 1.1;

struct MeasuredLevel {
  SimplifyResult level;
  /// kErrorMargin x the two-sided Hausdorff distance between level 0 and this
  /// level measured by DeviationMeter::hausdorff (model units); for line sets
  /// the simplifier's own bound.
  double error = 0;
  /// false: a level that LevelChainOptions::keep did not keep, whose `error`
  /// is kErrorMargin x DeviationMeter::estimate, no bound.
  bool measured_in_full = true;
};

/// What a level draws: its triangles plus its line segments.
inline std::size_t drawn_count(const TriangleMesh& m) {
  return m.triangle_count() + m.lines.size();
}

/// Area samples per direction for measuring a level that `method` made of a
/// mesh with `triangles` triangles: `requested` if non-zero, else one per
/// triangle within [20 000, `most`] (every vertex, and a quarter as many
/// points along the edges, are sampled as well; the farthest samples are
/// refined), four times that for vertex decimation: it keeps the input's
/// vertices, so its deviation peaks lie inside triangles where a result
/// triangle bridges a narrow fold, about as wide as the sample spacing (the
/// measurements behind the factor: docs/RESULTS.md, `## simplify`).
std::size_t measure_samples_for(std::size_t triangles, std::size_t requested,
                                SimplifyMethod method = SimplifyMethod::kQem,
                                std::size_t most = 200000);

/// Levels 1..n of `mesh` (level 0 is `mesh` itself) by simplify_chain (the
/// chain contract of simplify/level_chain.h): each at most (1 - min_diff) x
/// the triangles of the level before it, or the explicit triangle targets,
/// down to a few triangles; each with its error measured against level 0
/// (with LevelChainOptions::keep: the kept ones in full, the others estimated).
/// Deterministic: the same levels and errors for any number of threads.
std::vector<MeasuredLevel> simplify_levels(const TriangleMesh& mesh,
                                           const LevelChainOptions& options);

}  // namespace lodforge
