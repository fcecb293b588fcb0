// The deviation colour scale of the LODCreator thesis (§5.2, Figure 5.16, as in M. Roy's
// Mesh comparison tool): a two-segment linear ramp through the RGB primaries,
//   t = value / max in [0, 1/2]: blue  -> green, (0, 2t, 1 - 2t)
//   t             in [1/2, 1]: green -> red,   (2t - 1, 2 - 2t, 0)
// so the ends and the middle are pure primaries a viewer can name at a glance.
#include "lodforge/metrics/colorize_deviation.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace lodforge {

std::vector<Vec3> colorize_deviation([[maybe_unused]] const TriangleMesh& mesh,
                                     std::span<const float> values, float max) {
  assert(values.size() == mesh.vertex_count());
  std::vector<Vec3> colors(values.size(), kDeviationScale[0]);
  if (!(max > 0) || !std::isfinite(max)) return colors;
  for (std::size_t v = 0; v < values.size(); ++v) {
    if (std::isnan(values[v])) continue;
    float t = std::clamp(values[v] / max, 0.f, 1.f);
    const std::size_t i = t <= 0.5f ? 0 : 1;
    const float f = 2 * t - float(i);
    colors[v] = kDeviationScale[i] * (1 - f) + kDeviationScale[i + 1] * f;
  }
  return colors;
}

}  // namespace lodforge
