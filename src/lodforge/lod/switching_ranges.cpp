// Switching ranges from screen-space error (the original thesis §4.2; SPEC §2).
// A length eps at distance d covers eps / (2 d tan(alpha/2)) of the screen
// height; setting that to p and adding the bounding radius gives d.
#include "lodforge/lod/switching_ranges.h"

#include <algorithm>
#include <cassert>
#include <cmath>

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

SpacedLevels space_levels(std::span<const double> candidate_errors, double radius,
                          const RangeOptions& options, double spacing) {
  SpacedLevels out;
  // Distances at scale 1 (every distance scales with the transform alike).
  std::vector<double> error, d;
  for (double e : candidate_errors) {
    error.push_back(error.empty() ? e : std::max(error.back(), e));
    d.push_back(switch_distance(error.back(), 1.0, radius, options));
  }
  const double vanish = switch_distance(vanishing_error(radius), 1.0, radius, options);
  const double per_unit =
      2 * std::tan(double(options.camera_angle) / 2) * double(options.error_range);
  double previous = 0;  // switching distance of the last kept level (level 0: 0)
  std::size_t next = 0;
  while (next < d.size()) {
    double at = std::max(spacing * previous, d[next]);
    // Too close to the vanishing distance to be seen over a spaced interval.
    if (at >= vanish || std::max(spacing, 1.0) * at > vanish) {
      out.vanished = true;
      break;
    }
    std::size_t best = next;
    while (best + 1 < d.size() && d[best + 1] <= at) ++best;
    out.levels.push_back({best, std::max((at - radius) * per_unit, error[best])});
    previous = at;
    next = best + 1;
  }
  return out;
}

}  // namespace lodforge
