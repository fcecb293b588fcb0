#include "lodforge/lod/choose_levels.h"

#include <fmt/format.h>

#include <cmath>

namespace lodforge {
namespace {

// Manual mode: quality - 2 levels, halving the triangles each time.
std::vector<std::size_t> halving_targets(const TriangleMesh& mesh, int quality) {
  std::vector<std::size_t> targets;
  double count = double(mesh.triangle_count());
  for (int k = 0; k < quality - 2; ++k) {
    count = std::floor(count / 2);
    if (count < 1) break;
    targets.push_back(std::size_t(count));
  }
  return targets;
}

SpacedLevels space(std::span<const MeasuredLevel> candidates, const TriangleMesh& mesh,
                   double radius, const ChooseLevelsOptions& o) {
  std::vector<double> errors;
  std::vector<std::size_t> triangles;
  for (const auto& l : candidates) {
    errors.push_back(l.error);
    triangles.push_back(drawn_count(l.level.mesh));
  }
  return space_levels(
      {.errors = errors, .triangles = triangles, .level0_triangles = drawn_count(mesh)}, radius,
      o.range, o.spacing);
}

std::string chain_end(const SimplifyResult& last) {
  return std::string(to_string(last.stop_reason)) +
         (last.stop_detail.empty() ? "" : ": " + last.stop_detail);
}

}  // namespace

ChosenLevels choose_levels(const TriangleMesh& mesh, double radius, const ChooseLevelsOptions& o) {
  ChosenLevels out;
  out.method = mesh.triangles.empty() ? "cluster" : std::string(to_string(o.method));
  LevelChainOptions c;
  c.method = o.method;
  c.min_diff = o.min_diff;
  c.measure_samples = o.measure_samples;
  c.threads = o.threads;
  c.progress = o.progress;
  const bool manual = o.quality >= 2;
  bool limited = false;  // the level limit cut the levels chosen on the estimates
  if (manual) {
    c.max_levels = o.max_simplified;
    c.triangle_targets = halving_targets(mesh, o.quality);
    if (c.triangle_targets.empty()) return out;
  } else {
    // Only the candidates worth showing need their error measured in full,
    // and only those the size rule allows, an estimate.
    if (o.spacing.spacing > 1 && o.spacing.max_ratio < 1)
      c.most_kept_drawn = std::size_t(std::floor(o.spacing.max_ratio * double(drawn_count(mesh))));
    c.keep = [&](std::span<const MeasuredLevel> candidates) {
      std::vector<std::size_t> kept;
      for (const SpacedLevel& s : space(candidates, mesh, radius, o).levels) {
        if (!o.max_simplified || kept.size() < o.max_simplified)
          kept.push_back(s.candidate);
        else
          limited = true;
      }
      return kept;
    };
  }
  std::vector<MeasuredLevel> levels = simplify_levels(mesh, c);
  if (levels.empty()) {
    out.stop_reason = "nothing could be removed";
    return out;
  }
  const std::string end = chain_end(levels.back().level);
  if (manual) {
    for (auto& l : levels) {
      const double error = l.error;
      out.levels.push_back({std::move(l), error});
    }
    out.stop_reason = end;
    return out;
  }
  // Only levels measured in full are written.
  std::vector<MeasuredLevel> measured;
  for (auto& l : levels)
    if (l.measured_in_full) measured.push_back(std::move(l));
  const SpacedLevels spaced = space(measured, mesh, radius, o);
  for (const SpacedLevel& s : spaced.levels) {
    if (o.max_simplified && out.levels.size() == o.max_simplified) break;
    out.levels.push_back({std::move(measured[s.candidate]), s.switch_error});
  }
  if (limited || out.levels.size() < spaced.levels.size())
    out.stop_reason = fmt::format("level limit ({} levels)", o.max_simplified + 2);
  else if (spaced.vanished)
    out.stop_reason = fmt::format(
        "vanishing error: a coarser level would be seen over less than {}x the distance before "
        "the object vanishes (error 2 r)",
        o.spacing.spacing);
  else
    out.stop_reason = end;
  return out;
}

}  // namespace lodforge
