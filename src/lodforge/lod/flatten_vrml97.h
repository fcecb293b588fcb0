#pragma once
/// A VRML97 / X3D (classic encoding) scene as one triangle mesh in world
/// space, for the commands that work on one surface (info, render, compare,
/// simplify): every Shape reached through the grouping nodes (Transform,
/// Group, Anchor, Billboard, Collision and any node with `children`; a LOD's
/// chosen level; a Switch's chosen choice; a Skin's shapes and an
/// HAnimHumanoid's skin in the pose their coordinates hold), each USE again in
/// its own place.
/// Geometry: IndexedFaceSet, IndexedTriangleSet, TriangleSet, IndexedQuadSet,
/// ElevationGrid and the primitives Box, Sphere, Cone, Cylinder. Shapes inside
/// PROTO bodies, Inline scenes and other geometry are not drawn (counted in
/// FlatVrml97::skipped).
#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include "lodforge/core/log.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/lod_shapes.h"
#include "lodforge/scene/node.h"

namespace lodforge {

struct FlattenVrml97Options {
  int lod_level = 0;  ///< which level of every LOD (clamped to its last)
  /// The eye in world space: each LOD shows the level its `range` gives for
  /// the distance from the eye to its `center` (as in scene::TraverseOptions).
  std::optional<Vec3> viewpoint;
  TriangulateOptions triangulation;
};

struct FlatVrml97 {
  /// The mesh; with colours (per vertex: the Shape's Color node, per vertex or
  /// per face, else its
  /// Material's diffuseColor, else 0.8 grey) and opacity when some Shape has
  /// a Material or a Color node (FlatScene's layout, without textures).
  scene::FlatScene flat;
  std::size_t shapes = 0;                      ///< Shapes drawn (each occurrence)
  std::map<std::string, std::size_t> skipped;  ///< geometry or nodes not drawn, by type
};

/// The VRML97 / X3D Viewpoint's default fieldOfView, π/4.
inline constexpr float kDefaultFieldOfView = 0.785398f;

/// The first Viewpoint's fieldOfView, in file order (depth first through the
/// fields; statements skipped): its value when within (0, 3.1), else
/// kDefaultFieldOfView; nullopt when the scene has no Viewpoint.
std::optional<float> viewpoint_field_of_view(const scene::Scene& scene);

/// Throws DataError for a coordinate that is not finite or a primitive size
/// that is not. Warnings (bad indices) go to `log`.
FlatVrml97 flatten_vrml97(const scene::Scene& scene, const FlattenVrml97Options& options, Log& log);

/// The shapes of a VRML97 / X3D scene one by one, in world space with their
/// colours, texture coordinates and texture, grouped by the LOD node they are
/// drawn under with every level's shapes (a LOD inside a level drawn at its
/// first level): what gltf::lod_shapes_to_gltf makes a glTF model of. Beside
/// the geometry flatten_vrml97 draws, IndexedLineSets are shapes of line
/// segments (their Color node's colours, else the Material's emissiveColor).
struct Vrml97LodShapes {
  scene::LodShapes shapes;  ///< `camera` stays null: the angle is viewpoint_field_of_view's
  /// The Texture2 nodes (filename, wrapS, wrapT) the shapes' textures point
  /// to, one per ImageTexture drawn.
  std::vector<scene::NodePtr> textures;
  std::map<std::string, std::size_t> skipped;  ///< geometry or nodes not drawn, by type
};

/// Throws as flatten_vrml97.
Vrml97LodShapes vrml97_lod_shapes(const scene::Scene& scene, Log& log);

}  // namespace lodforge
