// The chain of levels of one shape, with measured errors.
#include "lodforge/lod/simplify_levels.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "lodforge/lod/measure_deviation.h"

namespace lodforge {

std::size_t measure_samples_for(std::size_t triangles, std::size_t requested) {
  if (requested) return requested;
  return std::clamp<std::size_t>(20 * triangles, 20000, 200000);
}

std::vector<MeasuredLevel> simplify_levels(const TriangleMesh& mesh,
                                           const LevelChainOptions& options) {
  std::vector<MeasuredLevel> out;
  const bool lines_only = mesh.triangles.empty();
  for (auto& level : simplify_chain(mesh, options.method,
                                    {.counts = options.triangle_targets,
                                    .step = options.min_diff,
                                    .smallest = 4,
                                    .max_levels = options.max_levels}))
    out.push_back({std::move(level), 0.0});
  // The measurements are independent: run them side by side against one
  // reference (level 0 sampled once).
  if (out.empty()) return out;
  std::unique_ptr<DeviationMeter> meter;
  if (!lines_only)
    meter = std::make_unique<DeviationMeter>(
        mesh, DeviationOptions{
                  .samples = measure_samples_for(mesh.triangle_count(), options.measure_samples)});
  ProgressCounter measured(options.progress, "measure", out.size(), 1);
  tbb::parallel_for(std::size_t(0), out.size(), [&](std::size_t i) {
    MeasuredLevel& m = out[i];
    if (lines_only || m.level.mesh.triangles.empty()) {
      m.error = m.level.error;
    } else {
      m.error = kErrorMargin * meter->hausdorff(m.level.mesh, m.level.face_map);
    }
    measured.add(1);
  });
  return out;
}

}  // namespace lodforge
