// Quadric edge collapse.
//
// M. Garland, P. S. Heckbert, "Surface Simplification Using Quadric Error
// Metrics", SIGGRAPH 1997: every vertex carries the sum of the (area-weighted)
// squared-distance quadrics of its planes; the cheapest edge collapse goes
// first, to the position that minimises the summed quadric (with a fallback to
// the best point of the edge when that system is ill-conditioned), and border
// edges add penalty planes perpendicular to their face.
//
// H. Hoppe, "New Quadric Metric for Simplifying Meshes with Appearance
// Attributes", IEEE Visualization 1999: each attribute channel s is modelled
// over a triangle as a linear function g.p + d of the position; the quadric
// sum_t area_t (s - g_t.p - d_t)^2, minimised over s, is a quadric in p that
// joins the geometric one, and its minimiser gives the attribute at the new
// position. Attributes live on wedges (a position's distinct attribute sets),
// so attribute seams stay sharp.
//
// Implementation notes (meshoptimizer's simplifier is the speed model): the
// collapse loop is bound by memory latency (collapses jump around the mesh in
// cost order), so per-vertex and per-triangle state sit in one record each
// (128 and 32 bytes) and small per-vertex state (versions) in compact arrays;
// a per-position list of live triangles rewritten by appending; a bucket
// queue of 16-byte edge entries with lazy deletion (an entry carries the sum
// of the version stamps of its two vertices; stale entries are dropped in bulk
// when their bucket comes up and when they outnumber the live edges); set-up
// in a few linear passes without maps or sorting (the vertex kinds, the
// quadrics and the first plans of the edges in parallel, each summed or
// queued in triangle order, so the result does not depend on the thread
// count); no allocation per collapse beyond amortised vector growth;
// coordinates in power-of-two normalised units, so results do not depend on
// the model's unit. Per collapse the work is: one valid pop, the checks over
// the two fans, and one evaluation and push per edge of the merged vertex.
//
// The collapse loop is inherently sequential, so a large reduction starts
// with a regional phase (run_regions): the mesh is cut into a few regions,
// which collapse their own edges side by side on TBB's threads, each with its
// own queue, in rounds up to a common cost limit, so the order stays close to
// one queue's; the vertices on the cuts wait, and the whole mesh then goes on
// from one queue. The quality stays close to that of one queue throughout (a
// test bounds the difference in mean deviation).
#include "lodforge/simplify/quadric_collapse.h"

#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lodforge/simplify/detail/collapser.h"

namespace lodforge {
namespace {

using detail::qem::Collapser;

/// The triangle count `target` asks for; an error budget alone asks for as
/// few as the budget allows.
std::size_t triangle_goal(const SimplifyTarget& target, std::size_t input) {
  if (target.triangles == 0 && target.ratio <= 0)
    return std::isfinite(target.max_error) ? 0 : input;
  return target.triangle_target(input);
}

}  // namespace

std::vector<SimplifyResult> quadric_collapse_chain(
    const TriangleMesh& mesh, const QuadricCollapseOptions& options,
    const std::function<std::optional<std::size_t>(std::size_t level, std::size_t previous)>&
        next_target) {
  std::vector<SimplifyResult> results;
  const std::size_t input = mesh.triangles.size();
  std::optional<std::size_t> next = next_target(0, input);
  if (!next) return results;
  Collapser collapser(mesh, options);
  bool stopped = false;
  StopReason last_reason = StopReason::kNoReduction;
  std::string last_detail;
  while (next) {
    const std::size_t target = *next;
    if (!stopped) {
      if (target >= input && !std::isfinite(options.target.max_error)) {
        last_reason = StopReason::kNoReduction;
        last_detail = "the target (" + std::to_string(target) +
                      " triangles) asks for no "
                      "reduction of " +
                      std::to_string(input) + " triangles";
      } else {
        last_reason = collapser.run(target, last_detail);
        stopped = last_reason != StopReason::kTargetReached;
      }
    }
    SimplifyResult r = collapser.snapshot();
    r.stop_reason = last_reason;
    r.stop_detail = last_detail;
    const std::size_t reached = r.mesh.triangles.size();
    results.push_back(std::move(r));
    if (stopped) break;
    next = next_target(results.size(), reached);
  }
  return results;
}

std::vector<SimplifyResult> quadric_collapse_chain(
    const TriangleMesh& mesh, const QuadricCollapseOptions& options,
    const std::vector<std::size_t>& triangle_targets) {
  std::vector<SimplifyResult> results = quadric_collapse_chain(
      mesh, options, [&](std::size_t level, std::size_t) -> std::optional<std::size_t> {
        if (level < triangle_targets.size()) return triangle_targets[level];
        return std::nullopt;
      });
  // After an early stop, the remaining targets get the last mesh again.
  while (!results.empty() && results.size() < triangle_targets.size())
    results.push_back(results.back());
  return results;
}

SimplifyResult quadric_collapse(const TriangleMesh& mesh, const QuadricCollapseOptions& options) {
  std::size_t target = triangle_goal(options.target, mesh.triangles.size());
  return std::move(quadric_collapse_chain(mesh, options, {target}).front());
}

}  // namespace lodforge
