// Chains of levels from the three simplifiers, with measured errors.
#include "lodforge/lod/simplify_levels.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "lodforge/lod/measure_deviation.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/vertex_clustering.h"
#include "lodforge/simplify/vertex_decimation.h"

namespace lodforge {

const char* to_string(LodMethod method) {
  switch (method) {
    case LodMethod::kCluster:
      return "cluster";
    case LodMethod::kDecimate:
      return "decimate";
    case LodMethod::kQem:
      return "qem";
  }
  return "?";
}

namespace {

std::vector<SimplifyResult> run_method(const TriangleMesh& mesh, const LevelChainOptions& o) {
  const bool lines_only = mesh.triangles.empty();
  if (o.method == LodMethod::kCluster || lines_only) {
    // Line sets are always clustered (weighted mean), as in the original.
    VertexClusteringOptions c;
    c.min_diff = std::clamp(o.min_diff, 0.01f, 1.0f);
    if (!o.triangle_targets.empty())
      c.target.triangles = std::max<std::size_t>(o.triangle_targets.back(), 1);
    auto chain = vertex_clustering(mesh, c);
    if (!chain.empty() && chain.front().stop_reason == StopReason::kNoReduction)
      chain.erase(chain.begin());  // level 0: the input itself
    return chain;
  }
  if (o.method == LodMethod::kDecimate) {
    VertexDecimationOptions d;
    d.step = std::clamp(o.min_diff, 0.01f, 1.0f);
    if (!o.triangle_targets.empty())
      d.target.triangles = std::max<std::size_t>(o.triangle_targets.back(), 1);
    return vertex_decimation_chain(mesh, d);
  }
  std::vector<std::size_t> targets = o.triangle_targets;
  if (targets.empty()) {
    double t = double(mesh.triangle_count());
    while (true) {
      t = std::floor(t * (1.0 - double(o.min_diff)));
      if (t < 4) break;
      targets.push_back(std::size_t(t));
      if (o.max_levels && targets.size() >= o.max_levels) break;
    }
    if (targets.empty() && mesh.triangle_count() > 4) targets.push_back(4);
  }
  if (targets.empty()) return {};
  return quadric_collapse_chain(mesh, {}, targets);
}

}  // namespace

std::size_t measure_samples_for(std::size_t triangles, std::size_t requested) {
  if (requested) return requested;
  return std::clamp<std::size_t>(20 * triangles, 20000, 200000);
}

std::vector<MeasuredLevel> simplify_levels(const TriangleMesh& mesh,
                                           const LevelChainOptions& options) {
  std::vector<MeasuredLevel> out;
  if (options.min_diff >= 1.0f && options.triangle_targets.empty()) return out;
  std::vector<SimplifyResult> chain = run_method(mesh, options);
  const bool lines_only = mesh.triangles.empty();
  std::size_t previous = lines_only ? mesh.lines.size() : mesh.triangle_count();
  const bool manual = !options.triangle_targets.empty();
  for (auto& level : chain) {
    std::size_t count = lines_only ? level.mesh.lines.size() : level.mesh.triangle_count();
    // A level must be smaller than the previous kept one by min diff (manual
    // targets: smaller at all). The simplifiers aim their targets at the
    // previous target, not the previous result (quadric collapse lands a
    // triangle or two below its target), so a level that misses the step is
    // skipped: the next, smaller one is tried against the same result.
    if (count == 0) break;
    double limit = manual ? double(previous) - 1 : double(previous) * (1.0 - options.min_diff);
    if (double(count) > limit + 1e-9) continue;
    out.push_back({std::move(level), 0.0});
    previous = count;
    if (options.max_levels && out.size() >= options.max_levels) break;
  }
  // The measurements are independent: run them side by side against one
  // reference (level 0 sampled once).
  if (out.empty()) return out;
  std::unique_ptr<DeviationMeter> meter;
  if (!lines_only)
    meter = std::make_unique<DeviationMeter>(
        mesh, DeviationOptions{
                  .samples = measure_samples_for(mesh.triangle_count(), options.measure_samples)});
  tbb::parallel_for(std::size_t(0), out.size(), [&](std::size_t i) {
    MeasuredLevel& m = out[i];
    if (lines_only || m.level.mesh.triangles.empty()) {
      m.error = m.level.error;
      return;
    }
    m.error = kErrorMargin * meter->hausdorff(m.level.mesh);
  });
  return out;
}

}  // namespace lodforge
