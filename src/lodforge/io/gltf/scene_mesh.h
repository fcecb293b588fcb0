#pragma once
/// What a glTF scene draws, as one TriangleMesh in world coordinates: every
/// triangle and line segment of every primitive of every mesh of the shown
/// scene's nodes (node_placements), once per node that uses the mesh.
#include <tiny_gltf.h>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/scene/flatten_scene.h"

namespace lodforge::gltf {

/// Positions, triangles and lines; with `colors`, also each vertex's colour:
/// its primitive's base colour (the material's baseColorFactor, white
/// without a material) times its COLOR_0 when it has one, RGB; and its
/// base-colour texture: texture coordinates (#V, as the texture's
/// KHR_texture_transform maps them, t = 1 - glTF's v) and per triangle its
/// material's index in the model (materials, scene::kUntextured without a
/// base-colour texture); drawn_textures turns those into images to draw.
/// `lod_level` K > 0 draws, for a node with `MSFT_lod`, the mesh of its level
/// K (its coarsest level when it has fewer) in the node's place. Throws
/// DataError as primitive_mesh, or for an MSFT_lod id that is not a node with
/// a mesh.
TriangleMesh scene_mesh(const tinygltf::Model& model, int lod_level = 0, bool colors = false);

/// A camera choosing levels by screen coverage: at `eye`, `height_angle`
/// (radians) high.
struct CoverageView {
  Vec3 eye;
  double height_angle = 0.785398;
};

/// The screen coverage of a bounding sphere of radius `radius` whose centre
/// is `distance` from the eye: the fraction of the screen height it covers,
/// radius / (distance tan(height_angle / 2)) (what MSFT_screencoverage holds).
double screen_coverage(double radius, double distance, double height_angle);

/// As scene_mesh, but a node with `MSFT_lod` draws the level its
/// `MSFT_screencoverage` (in the node's extras) chooses for `view`, as a
/// viewer does: value k is the coverage below which level k gives way to
/// level k + 1, a value past the last level the coverage below which the node
/// is not drawn at all. The coverage is that of the sphere about the centre
/// of the node's level-0 mesh's bounding box through its farthest vertex,
/// placed and scaled (by its largest scale) by the node's transform. A node
/// without coverages draws level 0.
TriangleMesh scene_mesh_seen_from(const tinygltf::Model& model, const CoverageView& view,
                                  bool colors = false);

/// The base-colour textures of a scene_mesh(..., colors = true) mesh, as a
/// renderer loads them: one per material the mesh uses, its triangles'
/// `materials` renumbered into this list. Each scales the base colour
/// (SceneTexture::modulates); its alpha cuts holes as the material's
/// alphaMode says (MASK: below alphaCutoff; BLEND: below one half; OPAQUE:
/// never). An embedded image (a buffer view or
/// a data URI) comes as its bytes, an external one as its URI (percent-escapes
/// decoded; relative to the glTF file); wrap modes from the sampler (mirrored
/// repeat drawn as repeat).
std::vector<scene::SceneTexture> drawn_textures(const tinygltf::Model& model, TriangleMesh& mesh);

/// `part` (primitive_mesh of `p`) with its vertices' colours: the
/// primitive's base colour (baseColorFactor, white without a material)
/// times its COLOR_0 when it has one, RGB.
void add_colors(const tinygltf::Model& model, const tinygltf::Primitive& p, TriangleMesh& part);

/// The base-colour texture of material `m`, or null.
const tinygltf::TextureInfo* base_color_texture(const tinygltf::Model& model, int m);

/// `part` (primitive_mesh of `p`) with its base-colour texture: texture
/// coordinates (as its KHR_texture_transform maps them; t = 1 - v: glTF's v
/// runs down the image) and, per triangle, its material's index in the model
/// (scene::kUntextured without a base-colour texture or without its
/// coordinates).
void add_texture(const tinygltf::Model& model, const tinygltf::Primitive& p, TriangleMesh& part);

/// The base-colour texture of material `m` (which has one: base_color_texture)
/// as a renderer loads it: it scales the base colour; its alpha makes holes
/// only in alphaMode MASK (below alphaCutoff) and BLEND (below one half: the
/// renderer draws no blending); an embedded image as its bytes, an external
/// one as its file name (the URI's percent-escapes decoded); wrap modes from
/// the sampler.
scene::SceneTexture material_texture(const tinygltf::Model& model, int m);

/// The levels scene_mesh can show: 1 + the most `MSFT_lod` ids of a node
/// (1 when no node has any).
std::size_t lod_level_count(const tinygltf::Model& model);

}  // namespace lodforge::gltf
