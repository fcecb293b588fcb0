#pragma once
/// The scene LOD pipeline for glTF 2.0: every mesh drawn by the shown scene's
/// nodes gets levels of detail that glTF viewers switch, written into the
/// model in place:
///
/// * each primitive of mode TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN gets
///   the levels of choose_levels (the same levels a VRML shape gets); POINTS
///   and LINES primitives are kept in every level;
/// * the levels of a primitive share one vertex set: the vertices they draw,
///   each once (a vertex the simplifier moved at its new position; its other
///   attributes copied from the input vertex it stands for,
///   SimplifyResult::vertex_map), or the input's own accessors when no vertex
///   moved; each level has its own index accessor; level 0 is the input
///   primitive unchanged (its vertices are not copied);
/// * the levels of a mesh switch where any of its primitives switches (the
///   switching points of its primitives, gathered within the level spacing
///   and moved to the latest of each group, which is always safe); a
///   primitive shrunk below its vanishing error is left out of the level;
/// * every node using the mesh gets the `MSFT_lod` extension, whose `ids`
///   name new level nodes (outside the scene hierarchy: the node's own
///   transform, no children) holding the level meshes, and in its `extras`
///   `MSFT_screencoverage` (what Babylon.js reads) plus `lodforge_lod`: per
///   level its switch distance (world units), measured error and triangles.
///
/// Screen coverage: a bounding sphere of radius r (world units) seen at
/// distance d with a camera of height angle a covers r / (d tan(a/2)) of the
/// screen height. Value i of MSFT_screencoverage is this coverage at the
/// distance where level i + 1 takes over; the last value is the coverage at
/// the distance where the mesh vanishes (its diameter is within the error
/// range). Coverage does not depend on the node's scale (r and d both scale).
///
/// A skinned or morphed mesh gets levels too (measured in its rest pose):
/// each level vertex keeps one input vertex's joints and weights and its
/// morph targets' displacements (those of the vertex the simplifier kept,
/// which moved vertices take as they are); the level nodes get the node's
/// skin and morph weights, and the animation channels of those weights. A
/// mesh whose vertex data is compressed (Draco, meshopt) stays at full detail
/// with a warning naming it. A mesh used by several nodes gets one set of level meshes; each node
/// gets its own level nodes. `MSFT_lod` goes into extensionsUsed only, so a viewer without it draws
/// level 0.
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/lod/generate_lod.h"

namespace lodforge {

/// Runs the pipeline on `scene` (modified in place). Of `options` it uses
/// method, range, camera_angle_given (else the first perspective camera's
/// yfov, else range.camera_angle), min_diff, level_spacing, level_ratio,
/// max_levels, manual["polygon"].quality, measure_samples, threads and
/// progress. The result's `scene` is empty; `shapes` holds one entry per
/// mesh drawn (type "mesh", ranges = the switch distances at its largest
/// node scale). Throws DataError naming the mesh for geometry that cannot
/// be read (an index past its vertices, a coordinate that is not finite).
LodResult gltf_lod(gltf::GltfScene& scene, const LodOptions& options = {});

}  // namespace lodforge
