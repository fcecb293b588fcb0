#pragma once
/// Vertex decimation (Schroeder, Zarge, Lorensen 1992):
/// repeatedly remove the vertex whose removal changes the surface least and
/// re-triangulate the hole it leaves. Vertices are removed, never moved, so a
/// level is a subset of the input's vertices with their attributes untouched.
///
/// Vertex classes (decided on the current mesh, after welding equal positions)
/// and their criterion d:
///
/// | class         | fan of triangles around the vertex         | d: distance to       |
/// |---------------|--------------------------------------------|----------------------|
/// | simple        | one closed ring, no feature edge           | the average plane    |
/// | boundary      | one open fan of >= 2 triangles, no feature | the line through its |
/// |               |                                            | 2 border neighbours  |
/// | interior edge | one closed ring, exactly 2 feature edges   | the line through its |
/// |               | with >= 2 triangles on each side           | 2 feature neighbours |
/// | corner        | other feature edges (1, >= 3, or on a      | the average plane    |
/// |               | boundary)                                  | (if not preserved)   |
/// | complex       | non-manifold, duplicate or degenerate fan, | never removed        |
/// |               | on a line segment, boundary ear (1         |                      |
/// |               | triangle), > kMaxDecimationValence tris    |                      |
///
/// The average plane of a fan has the area-weighted normal of its triangles and
/// passes through the area-weighted mean of their centroids (thesis eq. 3.1-3.3).
/// A feature edge joins two triangles whose normals differ by more than
/// `feature_angle`, or whose materials differ, or across which a vertex's
/// attributes change (a texture/normal seam: equal positions, different
/// normals/texcoords/colours). Material borders and seams are never crossed:
/// with `preserve_feature_edges` they are kept like any feature, without it a
/// vertex on them may still be removed along the border (interior edge) but a
/// corner with a material/seam feature never is.
///
/// The hole is re-triangulated by Schroeder's recursive loop splitting: the split
/// line (a new edge between two loop vertices) with the best aspect ratio
/// (smallest distance of the other loop vertices to the split plane, through the
/// line and perpendicular to the average plane, divided by the line's length)
/// is taken among those whose two halves lie strictly on the correct opposite
/// sides of the split plane and that do not already exist as mesh edges. An
/// interior-edge vertex is first split along its feature line, and each side is
/// triangulated against its own average plane. A removal is rejected (the
/// vertex stays, and is retried only when its neighbourhood changes) when no
/// split is valid, when a new triangle is degenerate or its normal does not
/// point to the side of the average plane's normal (a fold), or when a new edge
/// or triangle already exists (which would make a non-manifold edge, a
/// duplicate triangle, or change the topology). A boundary removal never closes
/// or opens a hole. Hence the Euler characteristic and the boundary loops of
/// every manifold part are kept, and non-manifold parts are left untouched.
///
/// Re-triangulated faces take the material of the removed triangles on their
/// side of the feature line (one material per side by construction), and for
/// `face_map` the original triangle of the removed triangle that shared one of
/// their loop edges (else the first removed triangle on their side).
///
/// Input robustness: open meshes, several components, degenerate triangles
/// (dropped if they use a vertex twice after welding; zero-area ones are kept
/// and never make feature edges), duplicate vertices (welded internally: equal
/// positions are one vertex for the topology; equal positions with different
/// attributes stay distinct output vertices along a seam), non-manifold parts
/// (left alone). Bad data (an index out of range, a used coordinate that is
/// not finite) throws DataError naming it; options out of range are caller
/// bugs (asserted, see VertexDecimationOptions).
#include <cstddef>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

/// The order in which candidate vertices are removed (smallest first).
enum class DecimationPriority {
  /// The volume between the vertex's fan and the triangles that would replace
  /// it (sum over the new triangles of the tetrahedron they span with the
  /// vertex, model units cubed), plus, for a boundary or interior-edge
  /// vertex, d x the area of the triangle (neighbour, vertex, neighbour) its
  /// line cuts off: the criterion d weighted by the area it affects, measured
  /// on the actual re-triangulation. It minimises the added
  /// mean deviation per removal (lower mean deviation than kDistance at the
  /// same triangle count: docs/RESULTS.md). It costs a planned
  /// re-triangulation per queued vertex.
  kErrorVolume,
  /// Schroeder's criterion d itself (distance to the average plane or the
  /// feature/boundary line), as in the 1992 paper and the thesis.
  kDistance,
};

struct VertexDecimationOptions {
  /// Triangle count / ratio and/or error budget (see SimplifyTarget). For
  /// vertex_decimation_chain an empty count/ratio means "as far as possible".
  /// The error budget bounds the accumulated error (see SimplifyResult::error
  /// below): a vertex whose removal would exceed it is not removed.
  SimplifyTarget target;
  /// Dihedral angle (radians, between the normals of two adjacent triangles)
  /// above which an edge is a feature edge. 1.2 rad (69 degrees) is the value
  /// of the original tool's dialog (the LODCreator thesis, Figure A.12; the scan reads
  /// "IU-1 2 radians", which we take for 1.2).
  float feature_angle = 1.2f;
  /// true: interior-edge and corner vertices are never removed. false:
  /// interior-edge vertices are removed by their distance to the feature line
  /// (split along it first, so the line stays a line), corners without a
  /// material/seam feature by the average-plane distance (Schroeder's option
  /// for noisy meshes). Off by default: on scanned meshes the coarse levels'
  /// own dihedral angles exceed any feature angle and freezing them costs
  /// quality.
  bool preserve_feature_edges = false;
  /// Removal order (see DecimationPriority). Either way, a vertex is removable
  /// and its error accumulates by its criterion d.
  DecimationPriority priority = DecimationPriority::kErrorVolume;
  /// vertex_decimation_chain only: each level has at most (1 - step) x the
  /// previous level's vertices (it removed at least `step` of them). Must be
  /// in (0, 1): another value is a caller bug (asserted).
  float step = 0.10f;
};

/// Largest fan (triangles around a vertex) considered for removal.
inline constexpr std::size_t kMaxDecimationValence = 64;

/// Removes vertices in order of their priority (smallest first, see
/// DecimationPriority; the neighbours of a removal are re-evaluated when
/// their queue entry comes up) until the triangle target
/// (options.target.triangle_target(#F of `mesh`)) is met, or no vertex can be
/// removed within the error budget or at all.
///
/// Threads: the first plan of every vertex runs on TBB's threads. From 32 768
/// triangles on, when the target keeps at most 72 % of them, a
/// regional first phase (simplify/regions.h) removes vertices in up to four kd
/// regions side by side on TBB's threads, each region only the vertices whose
/// whole ring it owns, with its own queue, in rounds up to a common priority
/// limit, down to 4x the target; then every vertex left is planned again and
/// one queue over the whole mesh goes on (about the quality of one queue:
/// docs/RESULTS.md). The result is the same on any number of threads. vertex_decimation_chain
/// (below) always runs one queue.
///
/// Result (see SimplifyResult): `mesh` holds the used input vertices (in input
/// order) with all their attributes, the remaining and new triangles,
/// per-face materials if the input had them, and the input's line segments.
/// `vertex_map` maps each output vertex to its input vertex (the first of a
/// group of identical duplicates). `error` is Schroeder's accumulated error:
/// every triangle carries e (0 for input triangles); when a vertex with
/// criterion d is removed, each new triangle gets d + the largest e among the
/// removed triangles; `error` is the largest e among the output triangles, in
/// model units. It is an estimate, in the spirit of an upper bound, of the
/// distance between the original surface and the simplified one (it adds up
/// the plane/line distances of the vertices removed beneath each triangle),
/// not a measurement and not a proven bound (lod/measured_simplify.h
/// measures the result).
/// `stop_detail` says why vertices could not be removed. Throws DataError
/// when an index is out of range or a used coordinate is not finite.
SimplifyResult vertex_decimation(const TriangleMesh& mesh,
                                 const VertexDecimationOptions& options = {});

/// The chain of levels of one decimation run (the original tool's "decimation
/// step"): level k keeps at most floor((1 - step) x vertices of level k-1)
/// vertices (level 0 is compared with the input's; vertices are counted as
/// distinct positions used by triangles, which is the output vertex count
/// unless attribute seams duplicate positions), except the
/// last level, which holds as much as could be removed. Stops after the level
/// that meets options.target (count, ratio, or as far as possible if neither is
/// given) or when no vertex can be removed; every level's SimplifyResult is as
/// for vertex_decimation (stop_reason kTargetReached for a level that met its
/// step, else why the run stopped). Empty if nothing could be removed.
std::vector<SimplifyResult> vertex_decimation_chain(const TriangleMesh& mesh,
                                                    const VertexDecimationOptions& options = {});

}  // namespace lodforge
