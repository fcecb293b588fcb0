// The chain of levels of one shape, with measured errors.
#include "lodforge/lod/simplify_levels.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <tbb/parallel_for.h>

#include "lodforge/lod/measure_deviation.h"

namespace lodforge {

std::size_t measure_samples_for(std::size_t triangles, std::size_t requested, SimplifyMethod method,
                                std::size_t most) {
  if (requested) return requested;
  const std::size_t per_triangle = method == SimplifyMethod::kDecimate ? 4 : 1;
  return per_triangle *
         std::clamp<std::size_t>(triangles, 20000, std::max<std::size_t>(most, 20000));
}

namespace {

// Each level's error against `meter` (in full, or its quick estimate), side
// by side (level 0 sampled once), `units` of progress each.
void measure(std::vector<MeasuredLevel>& levels, std::span<const std::size_t> which,
             const DeviationMeter& meter, bool in_full, ProgressCounter& progress,
             std::uint64_t units) {
  tbb::parallel_for(std::size_t(0), which.size(), [&](std::size_t k) {
    MeasuredLevel& m = levels[which[k]];
    // An estimate is a distance measured from the reference to the level: the
    // full measurement starts from it.
    const double known = m.measured_in_full ? 0.0 : m.error / kErrorMargin;
    m.error = kErrorMargin * (in_full ? meter.hausdorff(m.level.mesh, m.level.face_map, known)
                                      : meter.estimate(m.level.mesh));
    m.measured_in_full = in_full;
    progress.add(units);
  });
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
  const std::size_t samples =
      measure_samples_for(mesh.triangle_count(), options.measure_samples, options.method);
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
  // The choice is made once, on the estimates, and only its levels are
  // measured in full: choosing again on the full figures would measure
  // further levels, each as dear as the first ones, for little gain.
  // Levels the size rule can never keep lead the chain (it only shrinks).
  std::size_t first = 0;
  while (options.most_kept_drawn && first < out.size() &&
         drawn_count(out[first].level.mesh) > options.most_kept_drawn)
    out[first++].measured_in_full = false;
  std::erase_if(pending, [&](std::size_t i) { return i < first; });
  measure(out, pending, full, false, progress, 1);
  std::vector<std::size_t> kept;
  for (std::size_t i : options.keep(std::span(out).subspan(first)))
    if (i + first < out.size() && !out[i + first].measured_in_full) kept.push_back(i + first);
  const std::uint64_t units =
      kept.empty() ? 0 : std::min<std::uint64_t>(kFull, (total - pending.size()) / kept.size());
  measure(out, kept, full, true, progress, units);
  progress.add(total - pending.size() - units * kept.size());
  return out;
}

}  // namespace lodforge
