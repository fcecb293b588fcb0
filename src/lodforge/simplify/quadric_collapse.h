#pragma once
/// Quadric edge collapse (Garland & Heckbert 1997) with attribute-aware
/// quadrics (Hoppe 1999), border and seam preservation: the best-quality
/// simplifier of the toolkit.
///
/// Input: any TriangleMesh. Vertices with equal positions are welded
/// internally; vertices that share a position but differ in normal, texture
/// coordinate or colour stay apart (an attribute seam) and the seam is kept:
/// seam vertices only collapse along the seam, both sides together. Edges
/// between triangles of different materials are kept the same way, and so are
/// open borders (`lock_border` pins them in place). Vertices on non-manifold
/// edges, on inconsistently oriented edges, where three or more feature lines
/// meet, and vertices used by line segments never move. Triangles that use a
/// position twice are dropped (they have no area); everything else is kept.
///
/// The result never has a triangle whose normal turned by more than 90 degrees
/// in one collapse, a new zero-area triangle, a sliver below
/// `min_triangle_quality` (unless it was already worse), two triangles on the
/// same three vertices, or a topology change of a manifold part (link
/// condition).
///
/// ## The reported error (`SimplifyResult::error`)
/// A rigorous **upper bound on the one-sided Hausdorff distance from the
/// simplified surface to the original** (every point of the result lies
/// within `error` model units of the input surface), so it can feed a LOD
/// switching distance without underestimating. Each triangle carries a bound
/// e(T), 0 on the input. When a collapse moves a corner of T from p to w, the
/// new triangle T' is the old one with one corner moved, so by the triangle
/// inequality and the convexity of the distance to a triangle,
/// e(T') <= e(T) + dist(w, T) <= e(T) + |w - p| (p lies on T). The bound adds
/// |w - p|: one distance per collapse and side instead of a point-triangle
/// distance per triangle, at the price of counting the whole corner motion.
/// The result's error is the largest e over its triangles; the error budget
/// `target.max_error` rejects every collapse that would raise a bound above
/// it.
///
/// Why a bound and not a measurement: simplify/ may use only core/ and mesh/
/// (STYLE.md), so the BVH of metrics/ is out of reach, and a sampled
/// measurement could still underestimate between samples. The price: the bound
/// is conservative. It counts tangential motion, so on curved surfaces it is
/// far above the measured Hausdorff distance, and on flat regions it grows
/// where the real deviation stays 0. Callers that need the real value
/// measure it with metrics/compare_meshes (the LOD pipeline may use either;
/// the bound is the safe default).
///
/// Costs: O((V + F) log F) time, about ten edge evaluations and queue entries
/// per collapse (each collapse re-evaluates the edges of the merged vertex),
/// O(V + F) memory (plus O(F) per chain level for its output). Three set-up
/// passes (the vertex kinds, the quadrics and the first plan of every edge)
/// run on TBB's threads. From 32 768 triangles on, when the target keeps at
/// most 72 % of them, a regional first phase collapses up to four kd regions
/// of the mesh side by side on TBB's threads, each on its own queue, in rounds up to a common cost
/// limit, down to twice the target (at most nine tenths of the collapses); the vertices on the cuts
/// wait for the second phase, one queue over the whole mesh on the calling
/// thread. The regions and rounds depend on the mesh and target only: the
/// result is the same on any number of threads. Speed and quality beside
/// meshopt_simplify: docs/RESULTS.md. The result does not depend on the
/// model's unit: a copy scaled by a power of two gives the same triangles,
/// with positions and error scaled exactly.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

struct QuadricCollapseOptions {
  /// Triangle count, ratio and/or error budget (model units, compared with
  /// the error bound above). `{}` keeps the mesh.
  SimplifyTarget target;
  /// Attribute weights (0 = geometry only; attributes are still carried and
  /// interpolated). A difference of 1 in an attribute (unit normal components,
  /// texture coordinates, RGB in [0,1]) costs as much as a displacement of
  /// weight x the bounding-box diagonal over the same area.
  float normal_weight = 0.05f;
  float texcoord_weight = 0.05f;
  float color_weight = 0.05f;
  /// Weight of the penalty planes through border, seam and material edges
  /// (perpendicular to the face), relative to the area-weighted face planes;
  /// higher keeps feature lines straighter. 0 disables them.
  float border_weight = 10.0f;
  /// true: open-border vertices never move (interior vertices may still
  /// collapse onto them).
  bool lock_border = false;
  /// Smallest allowed triangle quality 4 sqrt(3) area / (sum of squared edge
  /// lengths), 1 for equilateral, in [0, 1). A collapse creating a triangle
  /// below it is rejected unless that triangle was already worse.
  float min_triangle_quality = 0.02f;
};

/// Simplifies `mesh` to `options.target`. The result's vertices are a subset
/// of the input's wedges (position + attributes), possibly moved, with
/// attributes re-interpolated; `vertex_map` gives each one's original vertex
/// index, `face_map` each triangle's original triangle index. Stops early, with
/// the reason in `stop_reason`/`stop_detail`, when no allowed collapse is left
/// or the error budget forbids all that remain.
/// Throws DataError, naming the problem, when a triangle or line index is out
/// of range or a coordinate a triangle or line uses is not finite.
SimplifyResult quadric_collapse(const TriangleMesh& mesh,
                                const QuadricCollapseOptions& options = {});

/// One collapse sequence producing several levels: one result per entry of
/// `triangle_targets` (each a triangle count, non-increasing), the mesh when
/// the sequence reaches that count (`options.target.triangles` and `ratio`
/// are ignored; `options.target.max_error` applies to every level). The
/// first level is exactly what quadric_collapse returns with its count as
/// target and the same options; so is every later one when the regional
/// phase (see above) does not run for the first target (under 32 768
/// triangles, or the first target keeps more than 72 % of them). Otherwise a
/// later level continues from the first and differs from an independent run
/// only by the regional phase's small changes. The levels cost little more
/// than the last one alone. Levels after an early stop repeat the last mesh
/// with the same stop reason.
std::vector<SimplifyResult> quadric_collapse_chain(
    const TriangleMesh& mesh, const QuadricCollapseOptions& options,
    const std::vector<std::size_t>& triangle_targets);

/// The same collapse sequence with each target chosen from what the levels
/// before it reached: `next_target(k, previous)` gives level k's triangle
/// target from the triangles of level k - 1 (for k = 0: the input's), or
/// nullopt to end the chain. The chain also ends after a level whose run
/// stopped early (its stop_reason says why).
std::vector<SimplifyResult> quadric_collapse_chain(
    const TriangleMesh& mesh, const QuadricCollapseOptions& options,
    const std::function<std::optional<std::size_t>(std::size_t level, std::size_t previous)>&
        next_target);

}  // namespace lodforge
