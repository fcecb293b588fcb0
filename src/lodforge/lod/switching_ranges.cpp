// Switching ranges from screen-space error (the original thesis §4.2).
// A length eps at distance d covers eps / (2 d tan(alpha/2)) of the screen
// height; setting that to p and adding the bounding radius gives d.
#include "lodforge/lod/switching_ranges.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>

namespace lodforge {

double switch_distance(double error, double scale, double radius, const RangeOptions& o) {
  assert(error >= 0 && scale > 0 && radius >= 0);
  assert(o.camera_angle > 0 && o.camera_angle < 3.14159265 && o.error_range > 0);
  return scale * error / (2 * std::tan(double(o.camera_angle) / 2) * double(o.error_range)) +
         radius;
}

std::vector<float> switching_ranges(std::span<const double> level_errors, double scale,
                                    double radius, const RangeOptions& options) {
  std::vector<float> ranges;
  double worst = 0;
  for (double e : level_errors) {
    worst = std::max(worst, e);
    float d = static_cast<float>(switch_distance(worst, scale, radius, options));
    if (!ranges.empty() && d <= ranges.back()) d = std::nextafter(ranges.back(), INFINITY);
    ranges.push_back(d);
  }
  return ranges;
}

void apply_given_ranges(std::vector<float>& ranges, std::span<const float> given) {
  for (std::size_t i = 0; i < given.size() && i < ranges.size(); ++i) ranges[i] = given[i];
  for (std::size_t i = 1; i < ranges.size(); ++i)
    if (ranges[i] <= ranges[i - 1]) ranges[i] = std::nextafter(ranges[i - 1], INFINITY);
}

// The choice of switching distances as a shortest path. Distances from the
// first candidate's to the vanishing one are a geometric grid (kGridSteps
// steps per spacing factor). A level starting at grid point g is the coarsest
// candidate allowed there (coarser is never worse for the distances; with the
// size rule a finer one could leave a later level open that the coarsest
// closes, which the grid does not try). best[g] = the fewest triangles drawn, integrated over log
// distance (grid steps), from g to the vanishing distance, with the level of g shown for at least
// one spacing factor. Level 0 is shown up to the first switch.
SpacedLevels space_levels(const LevelCandidates& candidates, double radius,
                          const RangeOptions& options, const SpacingOptions& spacing_options) {
  const std::span<const double> candidate_errors = candidates.errors;
  const std::span<const std::size_t> candidate_triangles = candidates.triangles;
  const std::size_t level0_triangles = candidates.level0_triangles;
  const double spacing = spacing_options.spacing;
  SpacedLevels out;
  const std::size_t n = candidate_errors.size();
  // Distances at scale 1 (every distance scales with the transform alike).
  std::vector<double> error, d;
  for (double e : candidate_errors) {
    error.push_back(error.empty() ? e : std::max(error.back(), e));
    d.push_back(switch_distance(error.back(), 1.0, radius, options));
  }
  const double vanish = switch_distance(vanishing_error(radius), 1.0, radius, options);
  const double per_unit =
      2 * std::tan(double(options.camera_angle) / 2) * double(options.error_range);
  auto level_at = [&](double at) {
    return SpacedLevel{0, std::max((at - radius) * per_unit, 0.0)};
  };
  if (n == 0) return out;
  if (spacing <= 1 || d[0] <= 0) {
    // Every candidate below the vanishing distance, at its own distance.
    for (std::size_t j = 0; j < n; ++j) {
      if (d[j] >= vanish) {
        out.vanished = true;
        break;
      }
      if (j + 1 < n && d[j + 1] <= d[j]) continue;  // an equal, coarser one follows
      SpacedLevel l = level_at(d[j]);
      l.candidate = j;
      l.switch_error = std::max(l.switch_error, error[j]);
      out.levels.push_back(l);
    }
    return out;
  }
  constexpr int kGridSteps = 16;
  const double step = std::log(spacing) / kGridSteps;
  if (d[0] * spacing > vanish) {
    out.vanished = true;
    return out;
  }
  const auto grid = std::size_t(std::floor(std::log(vanish / d[0]) / step));  // points 0..grid
  auto at = [&](std::size_t g) { return g == 0 ? d[0] : d[0] * std::exp(double(g) * step); };
  // The coarsest candidate allowed at each grid point (-1: none).
  std::vector<std::ptrdiff_t> level(grid + 1, -1);
  for (std::size_t g = 0, j = 0; g <= grid; ++g) {
    while (j < n && d[j] <= at(g) * (1 + 1e-12)) ++j;
    level[g] = std::ptrdiff_t(j) - 1;
  }
  const double end = std::log(vanish / d[0]) / step;  // the vanishing distance in grid steps
  auto triangles = [&](std::ptrdiff_t j) {
    return j < 0 ? double(level0_triangles)
           : std::size_t(j) < candidate_triangles.size()
               ? double(candidate_triangles[std::size_t(j)])
               : double(n - std::size_t(j));  // no counts: later is coarser
  };
  // The size rule, between a level and the one after it (j < 0: level 0).
  const bool sized = !candidate_triangles.empty() && spacing_options.max_ratio < 1;
  auto small_enough = [&](std::ptrdiff_t after, std::ptrdiff_t j) {
    return !sized || (after < 0 && level0_triangles == 0) ||
           triangles(j) <= spacing_options.max_ratio * triangles(after);
  };
  const double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> best(grid + 1, kInf);
  std::vector<std::size_t> next(grid + 1, SIZE_MAX);  // SIZE_MAX: shown until vanishing
  for (std::size_t g = grid + 1; g-- > 0;) {
    const std::ptrdiff_t j = level[g];
    if (j < 0) continue;
    const double here = triangles(j);
    if (end - double(g) >= kGridSteps) best[g] = here * (end - double(g));
    for (std::size_t h = g + kGridSteps; h <= grid; ++h) {
      if (level[h] <= j || best[h] == kInf || !small_enough(j, level[h])) continue;
      const double c = here * double(h - g) + best[h];
      if (c < best[g]) {
        best[g] = c;
        next[g] = h;
      }
    }
  }
  // Level 0 up to the first switch.
  std::size_t first = SIZE_MAX;
  double total = kInf;
  for (std::size_t g = 0; g <= grid; ++g) {
    if (best[g] == kInf || !small_enough(-1, level[g])) continue;
    const double c = double(level0_triangles ? level0_triangles : n + 1) * double(g) + best[g];
    if (c < total) {
      total = c;
      first = g;
    }
  }
  if (first == SIZE_MAX) {
    out.vanished = true;
    return out;
  }
  for (std::size_t g = first; g != SIZE_MAX; g = next[g]) {
    SpacedLevel l = level_at(at(g));
    l.candidate = std::size_t(level[g]);
    l.switch_error = std::max(l.switch_error, error[l.candidate]);
    out.levels.push_back(l);
  }
  out.vanished = out.levels.back().candidate + 1 < n;
  return out;
}

}  // namespace lodforge
