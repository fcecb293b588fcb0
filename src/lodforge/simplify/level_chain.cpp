// The chain contract over each method's own chain: quadric collapse aims
// each target at the previous result in one collapse sequence; clustering's
// octree levels and decimation's vertex steps are selected by their counts.
#include "lodforge/simplify/level_chain.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/vertex_clustering.h"
#include "lodforge/simplify/vertex_decimation.h"

namespace lodforge {

const char* to_string(SimplifyMethod method) {
  switch (method) {
    case SimplifyMethod::kCluster:
      return "cluster";
    case SimplifyMethod::kDecimate:
      return "decimate";
    case SimplifyMethod::kQem:
      return "qem";
  }
  return "?";
}

namespace {

std::size_t count_of(const TriangleMesh& m, bool lines) {
  return lines ? m.lines.size() : m.triangle_count();
}

// The most the level after one of `previous` may keep.
std::optional<std::size_t> limit_after(const ChainTargets& t, std::size_t level,
                                       std::size_t previous) {
  if (previous == 0 || (t.max_levels && level >= t.max_levels)) return std::nullopt;
  if (!t.counts.empty()) {
    if (level >= t.counts.size()) return std::nullopt;
    return std::min(t.counts[level], previous - 1);
  }
  if (previous <= t.smallest) return std::nullopt;
  const double step = std::clamp(double(t.step), 0.0, 1.0);
  const auto limit = std::size_t(std::floor(double(previous) * (1.0 - step)));
  if (limit == 0) return std::nullopt;
  return std::max(limit, std::min(t.smallest, previous - 1));
}

// The method's own levels (coarser and coarser, level 0 not among them).
std::vector<SimplifyResult> method_levels(const TriangleMesh& mesh, SimplifyMethod method,
                                          const ChainTargets& t, bool lines) {
  const std::size_t last = t.counts.empty() ? t.smallest : t.counts.back();
  const float step = std::clamp(t.step, 0.01f, 1.0f);
  if (method == SimplifyMethod::kCluster || lines) {
    VertexClusteringOptions c;
    c.min_diff = step;
    c.target.triangles = std::max<std::size_t>(last, 1);
    auto chain = vertex_clustering(mesh, c);
    if (!chain.empty()) chain.erase(chain.begin());  // level 0: the input itself
    return chain;
  }
  if (method == SimplifyMethod::kDecimate) {
    VertexDecimationOptions d;
    d.step = std::min(step, 0.99f);
    d.target.triangles = std::max<std::size_t>(last, 1);
    return vertex_decimation_chain(mesh, d);
  }
  return quadric_collapse_chain(mesh, {}, [&](std::size_t level, std::size_t previous) {
    return limit_after(t, level, previous);
  });
}

}  // namespace

std::vector<SimplifyResult> simplify_chain(const TriangleMesh& mesh, SimplifyMethod method,
                                           const ChainTargets& targets) {
  const bool lines = mesh.triangles.empty();
  std::vector<SimplifyResult> out;
  if (!limit_after(targets, 0, count_of(mesh, lines))) return out;
  std::vector<SimplifyResult> made = method_levels(mesh, method, targets, lines);
  std::size_t previous = count_of(mesh, lines);
  bool met = false;  // the chain's end was reached by its targets
  std::optional<std::size_t> limit = limit_after(targets, 0, previous);
  for (auto& level : made) {
    const std::size_t count = count_of(level.mesh, lines);
    if (count == 0) break;
    if (count > *limit) continue;
    previous = count;
    out.push_back(std::move(level));
    limit = limit_after(targets, out.size(), previous);
    if (!limit) {
      met = true;
      break;
    }
  }
  if (out.empty()) return out;
  const StopReason end = made.back().stop_reason;
  const std::string end_detail = made.back().stop_detail;
  for (auto& l : out) {
    l.stop_reason = StopReason::kTargetReached;
    l.stop_detail.clear();
  }
  if (!met) {
    // The method ran out before the targets did.
    SimplifyResult& l = out.back();
    l.stop_reason = end == StopReason::kTargetReached ? StopReason::kCannotSimplify : end;
    l.stop_detail = end == StopReason::kTargetReached
                        ? "no further level of the method keeps fewer triangles by the step"
                        : end_detail;
  }
  return out;
}

}  // namespace lodforge
