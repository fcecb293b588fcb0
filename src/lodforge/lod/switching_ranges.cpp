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

}  // namespace lodforge
