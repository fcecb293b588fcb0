// The chain of levels of one shape, with measured errors.
#include "lodforge/lod/simplify_levels.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <tbb/parallel_for.h>

#include "lodforge/lod/measure_deviation.h"

namespace lodforge {

std::size_t measure_samples_for(std::size_t triangles, std::size_t requested) {
  if (requested) return requested;
  return std::clamp<std::size_t>(triangles, 20000, 200000);
}

namespace {

// Each level's error against `meter` (in full, or its quick estimate), side
// by side (level 0 sampled once), `units` of progress each.
void measure(std::vector<MeasuredLevel>& levels, std::span<const std::size_t> which,
             const DeviationMeter& meter, bool in_full, ProgressCounter& progress,
             std::uint64_t units) {
  tbb::parallel_for(std::size_t(0), which.size(), [&](std::size_t k) {
    MeasuredLevel& m = levels[which[k]];
    m.error = kErrorMargin * (in_full ? meter.hausdorff(m.level.mesh, m.level.face_map)
                                      : meter.estimate(m.level.mesh, m.level.face_map));
    m.measured_in_full = in_full;
    progress.add(units);
  });
}

// A level not measured in full is compared with those that are at this
// factor above its calibrated estimate: a level measured in full is kept
// unless one not measured looks clearly better, so the search settles after
// few full measurements.
constexpr double kUnmeasuredPenalty = 1.1;

// How far an estimate is taken to fall short at most: errors near float
// noise (a level that only removed coplanar triangles) give ratios that say
// nothing about the levels beside them.
const double kMaxLogShortfall = std::log(2.0);

// The estimate falls short of the full measurement by a factor that changes
// slowly along the chain. Each level not measured in full takes its estimate
// times that factor at the nearest levels measured in full on either side
// (interpolated in log by position, at most 2), and the penalty.
void calibrate(std::vector<MeasuredLevel>& levels, std::span<const std::size_t> pending,
               std::span<const double> estimated) {
  std::vector<std::size_t> full;
  for (std::size_t i : pending)
    if (levels[i].measured_in_full && estimated[i] > 0 && levels[i].error > 0) full.push_back(i);
  if (full.empty()) return;
  auto log_ratio = [&](std::size_t i) { return std::log(levels[i].error / estimated[i]); };
  for (std::size_t i : pending) {
    if (levels[i].measured_in_full) continue;
    const auto above = std::lower_bound(full.begin(), full.end(), i);
    double r = 0;
    if (above == full.begin()) {
      r = log_ratio(*above);
    } else if (above == full.end()) {
      r = log_ratio(full.back());
    } else {
      const std::size_t lo = *(above - 1), hi = *above;
      const double t = double(i - lo) / double(hi - lo);
      r = (1 - t) * log_ratio(lo) + t * log_ratio(hi);
    }
    levels[i].error =
        estimated[i] * std::exp(std::clamp(r, 0.0, kMaxLogShortfall)) * kUnmeasuredPenalty;
  }
}

}  // namespace

std::vector<MeasuredLevel> simplify_levels(const TriangleMesh& mesh,
                                           const LevelChainOptions& options) {
  std::vector<MeasuredLevel> out;
  for (auto& level : simplify_chain(mesh, options.method,
                                    {.counts = options.triangle_targets,
                                    .step = options.min_diff,
                                    .smallest = 4,
                                    .max_levels = options.max_levels}))
    out.push_back({std::move(level), 0.0});
  // Line sets and empty levels keep the simplifier's own bound.
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (mesh.triangles.empty() || out[i].level.mesh.triangles.empty())
      out[i].error = out[i].level.error;
    else
      pending.push_back(i);
  }
  if (pending.empty()) return out;
  const std::size_t samples = measure_samples_for(mesh.triangle_count(), options.measure_samples);
  const DeviationMeter full(mesh, {.samples = samples});
  // Progress in eighths of a full measurement: an estimate costs about one.
  // With estimates, the full measurements are counted against about a third
  // of the levels (what the spacing keeps, typically), and the rest is added
  // at the end.
  constexpr std::uint64_t kFull = 8;
  const std::uint64_t total =
      options.keep ? pending.size() * (1 + kFull / 3) : pending.size() * kFull;
  ProgressCounter progress(options.progress, "measure", total, 1);
  if (!options.keep) {
    measure(out, pending, full, true, progress, kFull);
    return out;
  }
  measure(out, pending, full, false, progress, 1);
  std::vector<double> estimated(out.size(), 0.0);
  for (std::size_t i : pending) estimated[i] = out[i].error;
  std::uint64_t done = pending.size();
  for (;;) {
    calibrate(out, pending, estimated);
    std::vector<std::size_t> unmeasured;
    for (std::size_t i : options.keep(out))
      if (i < out.size() && !out[i].measured_in_full) unmeasured.push_back(i);
    if (unmeasured.empty()) break;
    // Each full measurement as its share of what is left of the total.
    const std::uint64_t units = std::min<std::uint64_t>(kFull, (total - done) / unmeasured.size());
    measure(out, unmeasured, full, true, progress, units);
    done += units * unmeasured.size();
  }
  progress.add(total - done);
  return out;
}

}  // namespace lodforge
