#pragma once
/// The geometry of a scene's LOD levels for the studio's 3D view: what a
/// VRML 1.0 browser draws at each level of each LOD node instance, with
/// the distances at which the node switches, so the page can build one
/// THREE.LOD per instance and switch it exactly as a browser switches the
/// file.
#include <string>

#include "lodforge/core/log.h"
#include "lodforge/scene/node.h"

namespace lodforge::studio {

struct LevelGeometryOptions {
  /// At most this many triangles in all (every level of every LOD instance
  /// and every shape outside LODs): a larger scene throws DataError, as
  /// the page cannot hold it.
  std::size_t max_triangles = 20'000'000;
  /// Measure every LOD level's per-vertex deviation from level 0 and add it
  /// to the meshes ("deviation", "deviation_colors", "deviation_max").
  bool deviation = true;
};

/// JSON text:
///
///     {"lods": [{"center": [x,y,z] (world), "ranges": [...], "line": N,
///                "name": "DEF", "levels": [[MESH, ...], ...]}, ...],
///      "shapes": [MESH, ...], "deviation_max": D}
///
/// MESH = {"type", "line", "matrix": 16 numbers (object to world,
/// column-major as THREE.Matrix4.fromArray reads it), "positions": [x,y,z,
/// ...] (object space), "colors": [r,g,b, ...] (per vertex: the Material's
/// diffuse + emissive, as `render` draws it), "indices": [a,b,c, ...],
/// "lines": [a,b, ...], "deviation": [d, ...], "deviation_colors": [r,g,b,
/// ...], "texture": {"file": NAME} or {"image": [w, h, components, pixel,
/// ...]}, "texcoords": [s,t, ...]}; the texture is the Texture2 drawn on the
/// shape (its filename as written, relative to the scene's folder, or its
/// SFImage), present with the texture coordinates when the shape has both.
///
/// "deviation" is, per vertex, the world-space distance to the surface of
/// its LOD instance's level 0 (closest points on metrics' TriangleBvh, the
/// vertex deviation of `compare`; 0 on level 0 and outside LODs), and
/// "deviation_colors" are those values through colorize_deviation with max
/// D, the largest deviation in the scene: the colours of `lodforge compare
/// --colored --color-max D`, one scale for every shape.
///
/// An LOD instance is one LOD node reached along one path (a USEd LOD is
/// several instances); its levels are its children as the traversal draws
/// them (an empty level is an empty list). Its centre is taken to world
/// space by the transform in effect at the node (read from a shape that is
/// its direct child; the level-0 shapes' transform otherwise). Shapes under
/// nested LODs belong to the innermost one. Shapes outside any LOD are in
/// "shapes". Throws DataError as shape_mesh does.
std::string level_geometry(const scene::Scene& scene, const LevelGeometryOptions& options = {},
                           Log* log = nullptr);

}  // namespace lodforge::studio
