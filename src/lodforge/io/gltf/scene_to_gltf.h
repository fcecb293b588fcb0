#pragma once
/// A VRML 1.0 or Open Inventor scene graph (as read, or as `lod` writes it)
/// as a glTF 2.0 model, so a scene of LOD nodes can be shipped to the engines
/// and viewers that read glTF.
///
/// Every shape the scene draws becomes a primitive in world coordinates
/// (each USE again: instancing is not kept), with what it looks like: vertex
/// colours from its Material and MaterialBinding (opacity below 1 makes the
/// material blended), texture coordinates and the Texture2 file as the base
/// colour texture (an image given inline in the file is left out, with a
/// warning), smooth vertex normals from the geometry, line sets as LINES.
/// Materials are double-sided, as VRML 1.0 lights both sides of a face whose
/// vertex ordering it does not know.
///
/// Each LOD node becomes one glTF node holding its first child's geometry,
/// with `MSFT_lod` listing a node for each further child that draws
/// something, and the screen coverages of the switches in its `extras`
/// (`MSFT_screencoverage`, what Babylon.js reads): the fraction of the
/// screen height the LOD's bounding sphere (radius r about its centre) fills
/// at switching distance d, r / (d tan(alpha / 2)) with alpha the camera's
/// height angle. The last coverage is where the last child begins: an empty
/// last child (as `lod` writes) makes it the coverage below which nothing is
/// drawn. The extras also hold the VRML ranges themselves, per level
/// (`lodforge: {ranges, camera_angle, radius}`), so any engine can switch by
/// distance instead. A LOD inside another LOD's child is drawn at the level
/// its parent shows.
#include <string>

#include "lodforge/core/log.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/scene/lod_shapes.h"
#include "lodforge/scene/node.h"

namespace lodforge::gltf {

struct SceneToGltfOptions {
  /// Camera height angle for the screen coverages (radians); <= 0: the
  /// scene's first PerspectiveCamera's heightAngle, else pi/4.
  double camera_angle = 0;
  /// Folder the scene's relative Texture2 file names resolve against (the
  /// input file's folder): GltfScene::base_dir of the result.
  std::string base_dir;
};

/// The scene as a glTF model. Warnings (inline images left out, shapes that
/// could not be read) go to `log`. Throws DataError for a shape whose
/// indices are out of range, as scene::shape_mesh does.
GltfScene scene_to_gltf(const scene::Scene& scene, const SceneToGltfOptions& options, Log& log);

/// The shapes of a scene as collect_lod_shapes gives them (or a VRML97 /
/// X3D scene's, lod/flatten_vrml97.h), as scene_to_gltf makes them a glTF
/// model. Each LodGroup's `lod` node gives its name and `range`; a
/// DrawnShape's texture is a Texture2 node (`filename`, `wrapS`, `wrapT`).
GltfScene lod_shapes_to_gltf(const scene::LodShapes& shapes, const SceneToGltfOptions& options,
                             Log& log);

}  // namespace lodforge::gltf
