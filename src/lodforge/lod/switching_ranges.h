#pragma once
/// Switching distances of LOD levels from their geometric error:
/// level l may be shown beyond the distance at which its error, seen by the
/// camera, covers at most a fraction p of the screen height:
///
///     d_l = k * eps_l / (2 * tan(alpha / 2) * p) + r
///
/// eps_l: geometric error of level l in object units (its measured deviation
/// from level 0); k: scale of the current transform; alpha: the camera's
/// height angle; p: the error range (fraction of the screen height); r: the
/// radius of the shape's bounding sphere (distances are measured from the
/// centre, the surface can be r closer).
#include <cstddef>
#include <span>
#include <vector>

namespace lodforge {

struct RangeOptions {
  float error_range = 0.02f;       ///< p, fraction of the screen height (2 %)
  float camera_angle = 0.785398f;  ///< alpha, radians (pi/4, VRML's default)
};

/// d for one error. Preconditions: error >= 0, scale > 0, radius >= 0,
/// 0 < camera_angle < pi, error_range > 0 (asserted).
double switch_distance(double error, double scale, double radius, const RangeOptions& options);

/// The error at which a whole object of bounding radius r disappears from view
/// at the error range: its diameter. An empty last level takes this error.
inline double vanishing_error(double radius) {
  return 2 * radius;
}

/// LOD.range for levels 1..n given their errors eps_1..eps_n (level 0, the
/// original, has no range). Errors are made non-decreasing (a coarser level is
/// never shown nearer than a finer one) and the ranges strictly increasing
/// (VRML requires it: equal neighbours are nudged up by one float step).
std::vector<float> switching_ranges(std::span<const double> level_errors, double scale,
                                    double radius, const RangeOptions& options);

/// The user's explicit ranges (`--ranges`) in place of the first computed
/// ones, in order (missing ones stay computed); then strictly increasing as
/// VRML requires (a range not above the one before it is nudged up by one
/// float step).
void apply_given_ranges(std::vector<float>& ranges, std::span<const float> given);

/// Default of SpacingOptions::spacing: a kept level is shown over at least a
/// 1.25x distance interval (from d to 1.25 d or farther).
inline constexpr double kDefaultLevelSpacing = 1.25;
/// Default of SpacingOptions::max_ratio: a kept level has at most half the
/// triangles of the one before it, so all simplified levels of a shape
/// together hold no more triangles than level 0 (the output stays within
/// about twice the input).
inline constexpr double kDefaultLevelRatio = 0.5;

struct SpacingOptions {
  /// Each kept level is shown from D to at least spacing x D; <= 1: every
  /// candidate is kept at its own distance (no spacing, no size rule).
  double spacing = kDefaultLevelSpacing;
  /// Triangles of a kept level <= max_ratio x those of the level before it
  /// (level 0 for the first); >= 1: no size rule. Needs candidate counts.
  double max_ratio = kDefaultLevelRatio;
};

/// Candidate levels 1..n of one shape, finer to coarser.
struct LevelCandidates {
  std::span<const double> errors;          ///< eps, model units
  std::span<const std::size_t> triangles;  ///< their sizes; empty: later is smaller
  std::size_t level0_triangles = 0;
};

struct SpacedLevel {
  std::size_t candidate = 0;  ///< index into the candidates
  /// The error whose switch_distance is this level's switching distance: at
  /// least the candidate's own error (switching later than its error allows
  /// is always safe), larger where the spacing pushes the switch outwards.
  double switch_error = 0;
};

struct SpacedLevels {
  std::vector<SpacedLevel> levels;
  /// The chain ended because the next candidate would be shown too close to
  /// (or beyond) the distance at which the object vanishes (vanishing_error),
  /// rather than because the candidates ran out.
  bool vanished = false;
};

/// Chooses the candidate levels worth writing, and where each switches. Each
/// kept level is shown over a distance interval of at least `spacing` x its
/// start, the last one too before the object vanishes (the distance of
/// vanishing_error), and keeps at most max_ratio of the triangles before it;
/// no level switches nearer than its own error allows (switching later is
/// always safe). Among such choices it takes the one drawing the fewest
/// triangles integrated over log distance (a shortest path over a geometric
/// grid of 16 steps per spacing factor, from the first candidate's distance
/// to the vanishing one). Errors are made non-decreasing first, as
/// switching_ranges does. The choice does not depend on the transform scale
/// (every distance scales with it).
SpacedLevels space_levels(const LevelCandidates& candidates, double radius,
                          const RangeOptions& range, const SpacingOptions& options = {});

}  // namespace lodforge
