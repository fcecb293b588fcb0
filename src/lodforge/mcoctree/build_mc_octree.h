#pragma once
/// Building the marching-cube octree of a mesh (Kim, "LOD mesh modeling with
/// the marching cube octree", ch. 4-5): leaves from signed distances, parents
/// bottom-up, priority numbering, the LOD array and the accumulation table.
#include <cstddef>

#include <vector>

#include "lodforge/core/memory_budget.h"
#include "lodforge/core/progress.h"
#include "lodforge/mcoctree/mc_octree.h"
#include "lodforge/mcoctree/range_scan.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

/// What the model of an open mesh does at the input's holes.
enum class McHoles {
  kOpen,   ///< no surface where the input has none: the model has borders there
  kCapped  ///< closed across each hole (a cap about midway between inside and outside)
};

/// How the priority numbering orders the expansions.
enum class McPriorityMetric {
  /// The thesis's LOD metric: area of the children's triangulation minus the
  /// node's own (its magnitude).
  kArea,
  /// How far the finest surface inside the node lies from the node's own
  /// triangles (the sum over the surface points): the error a coarse level
  /// shows. Lower deviation at every level at somewhat more build time
  /// (docs/RESULTS.md).
  kDistance
};

struct McBuildOptions {
  /// Finest cells across the longest side of the mesh's bounding box (2..1000),
  /// or 0: chosen so that the full-resolution model has about as many
  /// triangles as the input (a mesh: from its area, about 2.9 triangles per
  /// cell face of surface; range scans: cells twice the scans' point spacing,
  /// Kim sec. 4.4). The root cube has the next power of two above
  /// resolution + 2 cells per axis, so that one empty cell surrounds the
  /// mesh. The sign lattice takes one byte per lattice point of the mesh's
  /// box grown by a cell (at most (resolution + 3)^3: about 127 MB at 500).
  int resolution = 0;
  /// Worker threads (distances, edge points, holes, areas); 0 = all cores.
  /// The build runs in a task arena of this size (the process's TBB settings
  /// are left alone); the result is the same for any count.
  int threads = 0;
  /// Meshes only (range scans are always capped where no scan saw the
  /// object). kOpen by default: the model does not invent surface the input
  /// lacks (a cap over a scan's unseen bottom would be the largest error of
  /// every level); kCapped gives a closed (watertight) model.
  McHoles holes = McHoles::kOpen;
  /// The priority metric; kArea by default, as the thesis defines it.
  McPriorityMetric metric = McPriorityMetric::kArea;
  /// true (default): a coarse level's edge point is a vertex of its own, the
  /// finest crossing its edge picks moved along its normal (by at most a
  /// quarter of the level's cell) to where the quadric of the finest surface
  /// in the cells around the edge is least, so that coarse triangles straddle
  /// the surface instead of cutting chords on one side of it (lower
  /// deviation at the coarse levels; docs/RESULTS.md), unless the move is
  /// under 5 % of a finest cell (then the finer level's vertex serves). The
  /// placed vertices are extra vertices of the model (their count and bytes:
  /// docs/RESULTS.md). false: every vertex of every level is a finest
  /// crossing, on the input surface.
  bool place_coarse_vertices = true;
  /// The build may take at most this many bytes, as mc_build_bytes estimates
  /// them before the lattice is allocated (DataError if more). 0: no limit.
  std::uint64_t max_memory = kDefaultMemoryBudget;
  /// The build's stages as they run (core/progress.h), from worker threads:
  /// "signs" (slabs of the lattice, or its layers for range scans),
  /// "surface points" (crossed lattice edges), "tree" (nodes made, level by
  /// level), "priorities" (expansions of the numbering). Empty: none.
  ProgressCallback progress;
};

/// The memory a build of the lattice over `box` at `resolution` takes, about
/// 5 bytes per lattice point (signs, distances, the tree; a 948-triangle
/// mesh at resolution 1000: 4.6 GB measured, 4.7 GiB estimated).
double mc_build_bytes(const Box3& box, int resolution);

struct McBuildStats {
  std::size_t band_points = 0;     ///< lattice points with an exact signed distance
  std::size_t flooded_points = 0;  ///< signs from the flood fill (range scans: from the vote)
  std::size_t sign_repairs = 0;    ///< flooded points later given an exact distance
  std::size_t carved_points = 0;   ///< range scans: points a line of sight shows empty
  std::size_t filled_voids = 0;    ///< range scans: enclosed outside regions made inside
  std::size_t dropped_parts = 0;   ///< range scans: small inside regions (bubbles) made outside
  std::size_t sign_flips = 0;      ///< range scans: lone outside corners (pits) made inside
  /// Closed meshes: bridges of lattice points made inside so that a part
  /// thinner than a cell somewhere stays in one piece (part_bridges.h).
  std::size_t part_bridges = 0;
  std::size_t leaves = 0;           ///< finest cells with a crossing
  std::size_t expansion_waits = 0;  ///< times a node was popped while a neighbour was too coarse
  std::size_t hole_nodes = 0;       ///< nodes left without triangles over the input's holes
  int resolution = 0;               ///< the resolution used (options.resolution or the chosen one)
  double seconds_signs = 0, seconds_tree = 0, seconds_priorities = 0;
};

struct McBuildResult {
  McOctree tree;
  McBuildStats stats;
};

/// Builds the octree of `mesh` (triangles; lines are ignored).
///
/// Corner signs: the exact closest surface point (metrics/
/// closest_point_on_triangle; metrics/triangle_bvh.h for the few points the
/// band's triangle scan does not reach) and the side of it by the
/// angle-weighted pseudo-normal
/// (Baerentzen & Aanaes 2005: face, edge or vertex normal by where the closest
/// point lies), computed in a band one cell wide around the triangles; the
/// rest of the lattice, and the band points nearest an open rim (where the
/// pseudo-normal's side is meaningless), take their sign by flood fill from
/// the band, and any flooded point whose sign disagrees with a neighbour's
/// gets an exact one where it has one. Edge points from the signed
/// distances' ratio, normals and colours from the closest point of the mesh.
///
/// Holes (McHoles::kOpen): a surface point is invented when it lies farther
/// from the input than a finest cell's edge, or more than a quarter of that
/// beyond an open rim; a node most of whose edge points are invented has no
/// triangles (its signs are cleared). The model's borders then follow the
/// input's rims to within about a cell, at every level; closed inputs invent
/// nothing and stay closed.
///
/// Parts (closed meshes): where a part is thinner than a cell the lattice may
/// hold its inside in separate pieces; pieces nearest one connected part of
/// the input are joined by bridges of lattice points along the thin place
/// (part_bridges.h), so that the model's full-resolution surface has the
/// input's parts, about a cell thick where the input is thinner.
///
/// Throws DataError for a mesh without triangles (or with only degenerate
/// ones), with a triangle index out of range, with colours not one per
/// vertex, with coordinates outside the range of check_coordinate_range
/// (non-finite, huge or a tiny model), with all vertices at one point, or
/// whose surface crosses no lattice edge, and when the build would take more
/// than options.max_memory; DataError for a resolution out of
/// range.
McBuildResult build_mc_octree(const TriangleMesh& mesh, const McBuildOptions& options = {});

/// Builds the octree of range scans, merged without zippering in the world
/// frame their alignment gives (Kim, ch. 4; `resolution` counts cells across
/// the longest side of all points' bounding box; `holes` is not used).
///
/// Corner signs: within two cells of the data, the distance to the plane of
/// the nearby range points of one sheet (their normals from their 4 lattice
/// neighbours' triangles), fitted with Gaussian weights times each point's
/// trust (RangeScan::weights: grazing, rim and stray samples count little)
/// so that overlapping scans out of register by a fraction of a cell agree; outside wherever a line
/// of sight shows the space empty (in front of the surface a scan measured: space carving) and on
/// the root cube's faces; everywhere else a vote of the scans: inside where more scans see the
/// point behind a measured surface than see it beyond their data (outside the silhouette or the
/// window), else outside (a line through a gap in a scan's data says nothing). Where no scan saw
/// the surface (under an object that stood on a turntable) the model is closed by a cap where the
/// vote changes, near the rim of the unseen region. Lone outside corners (a band
/// point within a cell of the plane with 4 or more of its 6 neighbours
/// inside: a pit) are made inside. Normals and colours: the same weighted average
/// of the nearby points' normals and colours.
///
/// Throws DataError for no scans, no measured point, a grid of the wrong
/// size, a grid index out of range, colours or confidences not one per
/// point, a negative or non-finite confidence, a world coordinate outside the range of
/// check_coordinate_range, and when the build would take more than options.max_memory; DataError
/// for a resolution out of range.
McBuildResult build_mc_octree(const std::vector<RangeScan>& scans,
                              const McBuildOptions& options = {});

}  // namespace lodforge
