// Simplification to a count or to a measured error budget: the method's chain
// brackets the budget, a geometric scan of counts narrows the bracket.
#include "lodforge/lod/measured_simplify.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "lodforge/lod/measure_deviation.h"
#include "lodforge/lod/simplify_levels.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/vertex_clustering.h"
#include "lodforge/simplify/vertex_decimation.h"

namespace lodforge {
namespace {

/// measure_samples_for's `most` here: the search makes dozens of measurements.
constexpr std::size_t kMaxSamples = 100000;

SimplifyResult run_to_count(const TriangleMesh& mesh, SimplifyMethod method, std::size_t count) {
  SimplifyTarget target;
  target.triangles = std::max<std::size_t>(count, 1);
  switch (method) {
    case SimplifyMethod::kQem:
      return quadric_collapse(mesh, {.target = target});
    case SimplifyMethod::kDecimate:
      return vertex_decimation(mesh, {.target = target});
    case SimplifyMethod::kCluster:
      break;
  }
  VertexClusteringOptions c;
  c.target = target;
  std::vector<SimplifyResult> chain = vertex_clustering(mesh, c);
  SimplifyResult r = std::move(chain.back());
  if (r.mesh.triangle_count() < count && r.stop_reason == StopReason::kTargetReached) {
    const std::size_t above = chain.size() >= 2 ? chain[chain.size() - 2].mesh.triangle_count() : 0;
    r.stop_detail = fmt::format(
        "{}; {} triangles asked, {} made ({:.1f} % below): the clustering level before it has "
        "{} (octree cells merge a whole cell at a time)",
        r.stop_detail, count, r.mesh.triangle_count(),
        100.0 * (1.0 - double(r.mesh.triangle_count()) / double(count)), above);
  }
  return r;
}

/// The input itself as a result (nothing could be removed within the budget).
SimplifyResult unchanged(const TriangleMesh& mesh) {
  SimplifyResult r;
  r.mesh = mesh;
  r.vertex_map.resize(mesh.vertex_count());
  std::iota(r.vertex_map.begin(), r.vertex_map.end(), 0u);
  r.face_map.resize(mesh.triangle_count());
  std::iota(r.face_map.begin(), r.face_map.end(), 0u);
  return r;
}

class Search {
 public:
  Search(const TriangleMesh& mesh, const MeasuredSimplifyOptions& o)
      : mesh_(mesh),
        options_(o),
        meter_(mesh, {.samples = measure_samples_for(mesh.triangle_count(), o.samples, o.method,
                                                     kMaxSamples)}) {}

  MeasuredSimplifyResult run() {
    const std::size_t n = mesh_.triangle_count();
    const std::size_t count = options_.target.triangle_target(n);
    const double budget = options_.target.max_error;
    MeasuredSimplifyResult out;
    if (count >= n && !std::isfinite(budget)) {
      out.result = unchanged(mesh_);
      out.result.stop_reason = StopReason::kNoReduction;
      out.result.stop_detail = "the target asks for no reduction";
      return out;  // the input itself: error 0
    }
    if (count < n) {
      // Progress: the simplification, then its measurement.
      ProgressCounter steps(options_.progress, "simplify", 2, 1);
      out.result = run_to_count(mesh_, options_.method, count);
      ++out.simplifier_runs;
      steps.add(1);
      out.error = bound(out.result, out);
      steps.add(1);
      if (out.error <= budget) return finish(std::move(out));
    }
    return finish(within_budget(count < n ? std::max<std::size_t>(count, 1) : 1, budget, out));
  }

 private:
  double bound(const SimplifyResult& r, MeasuredSimplifyResult& out) const {
    ++out.measurements;
    return kErrorMargin * meter_.distance_to_reference(r.mesh, r.face_map);
  }

  MeasuredSimplifyResult finish(MeasuredSimplifyResult out) const {
    if (out.measurements == 0) out.error = bound(out.result, out);
    return out;
  }

  // The method's chain down to `floor` triangles: halving steps for quadric
  // collapse and decimation, the octree's own levels for clustering.
  std::vector<SimplifyResult> chain(std::size_t floor) const {
    if (options_.method == SimplifyMethod::kCluster) {
      VertexClusteringOptions c;
      c.target.triangles = floor;
      std::vector<SimplifyResult> levels = vertex_clustering(mesh_, c);
      levels.erase(levels.begin());  // level 0: the input itself
      std::erase_if(levels, [](const SimplifyResult& l) { return l.mesh.triangles.empty(); });
      return levels;
    }
    return simplify_chain(mesh_, options_.method,
                          {.step = 0.5f, .smallest = std::max<std::size_t>(floor, 4)});
  }

  // The smallest result of at least `floor` triangles whose bound is within
  // `budget`; `spent` carries the counters of the runs made so far. The
  // measured error does not fall strictly with the count (a thin part may
  // vanish at one count and not at a smaller one), so every level of the
  // chain is measured, and for the methods that can land on any count, counts
  // below the smallest result within the budget are tried in steps of 2^(1/8)
  // until one at most half its size measures twice the budget.
  MeasuredSimplifyResult within_budget(std::size_t floor, double budget,
                                       MeasuredSimplifyResult spent) {
    MeasuredSimplifyResult best = spent;
    best.result = unchanged(mesh_);
    std::size_t beyond = 0;  // the largest count below the best that measured beyond the budget
    double beyond_error = 0;
    auto consider = [&](SimplifyResult& r) {
      const std::size_t made = r.mesh.triangle_count();
      const double e = bound(r, best);
      if (e <= budget && made < best.result.mesh.triangle_count()) {
        best.result = std::move(r);
        best.error = e;
      } else if (e > budget && made > beyond) {
        beyond = made;
        beyond_error = e;
      }
      return e;
    };
    if (options_.progress) options_.progress("chain", 0, 1);
    std::vector<SimplifyResult> levels = chain(floor);
    ++best.simplifier_runs;
    ProgressCounter measured(options_.progress, "measure", levels.size(), 1);
    for (SimplifyResult& l : levels) {
      consider(l);
      measured.add(1);
    }
    if (levels.empty()) {
      best.result.stop_reason = StopReason::kCannotSimplify;
      best.result.stop_detail = "nothing can be removed";
      return best;
    }
    const bool reached_end =
        best.result.mesh.triangle_count() == levels.back().mesh.triangle_count();
    if (!reached_end && options_.method != SimplifyMethod::kCluster) {
      constexpr double kStep = 0.917004043204671;  // 2^(-1/8)
      double count = double(best.result.mesh.triangle_count());
      std::size_t previous = best.result.mesh.triangle_count();
      // Progress: the steps down to the floor, most of which the stop rule
      // below usually spares.
      const auto steps = static_cast<std::uint64_t>(
          std::ceil(std::log(std::max(count, 1.0) / double(std::max<std::size_t>(floor, 1))) /
                    -std::log(kStep)));
      ProgressCounter scanned(options_.progress, "scan", std::max<std::uint64_t>(steps, 1), 1);
      while (true) {
        count *= kStep;
        const auto target = std::size_t(count);
        if (target < std::max<std::size_t>(floor, 1) || target >= previous) break;
        SimplifyResult r = run_to_count(mesh_, options_.method, target);
        ++best.simplifier_runs;
        previous = r.mesh.triangle_count();
        // Far beyond the budget, and a halving below the best: stop.
        scanned.add(1);
        if (consider(r) > 2 * budget && 2 * previous <= best.result.mesh.triangle_count()) break;
      }
    }
    if (beyond >= best.result.mesh.triangle_count()) beyond = 0;
    if (reached_end && beyond == 0) return best;  // the chain's end is within the budget
    best.result.stop_reason = StopReason::kErrorBudgetReached;
    best.result.stop_detail =
        beyond ? fmt::format(
                     "{} triangles measure {:.6g} (within {:.6g}); {} triangles measured "
                     "{:.6g}",
                     best.result.mesh.triangle_count(), best.error, budget, beyond, beyond_error)
               : fmt::format(
                     "{} triangles measure {:.6g} (within {:.6g}); every smaller result "
                     "tried measured more",
                     best.result.mesh.triangle_count(), best.error, budget);
    return best;
  }

  const TriangleMesh& mesh_;
  MeasuredSimplifyOptions options_;
  DeviationMeter meter_;
};

}  // namespace

MeasuredSimplifyResult simplify_measured(const TriangleMesh& mesh,
                                         const MeasuredSimplifyOptions& options) {
  // Checked before the meter samples the mesh.
  check_simplify_input(mesh, to_string(options.method));
  return Search(mesh, options).run();
}

}  // namespace lodforge
