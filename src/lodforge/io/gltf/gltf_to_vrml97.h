#pragma once
/// A glTF 2.0 model as a VRML97 scene graph, so that a glTF scene can be
/// written as VRML97 or X3D (classic or XML) and given LOD nodes by the
/// VRML97 pipeline.
///
/// The shown scene's nodes (shown_roots) become Transforms nested as in the
/// model (translation, rotation, scale; a `matrix` decomposed into them, a
/// sheared one to its nearest rotation and scale with a warning), named by
/// the node's name where it is a usable DEF name. A mesh used by several
/// nodes is one Group, DEF'd once and USEd. Each primitive is a Shape:
/// triangles (strips and fans converted, primitive_mesh) an IndexedFaceSet
/// (counter-clockwise, solid unless the material is double-sided) with the
/// primitive's normals, its base-colour texture's coordinates (t = 1 - v,
/// KHR_texture_transform applied) and, with COLOR_0, a Color node of base
/// colour x COLOR_0; lines an IndexedLineSet; points a PointSet.
///
/// Materials (Phong's approximation of the metallic-roughness model):
/// diffuseColor = baseColorFactor, transparency = 1 - its alpha in alphaMode
/// BLEND, emissiveColor = emissiveFactor; KHR_materials_unlit as an
/// emissive colour on black. The base-colour texture is an ImageTexture:
/// an external image by its file name (relative to the glTF file's folder,
/// as GltfScene::base_dir), an embedded one as a `data:` URI; a clamping
/// sampler sets repeatS / repeatT FALSE. A perspective camera becomes a
/// Viewpoint (fieldOfView = yfov) in its node's Transform.
///
/// What VRML97 cannot hold is left out and named in one warning: animations,
/// skins (their meshes written in the bind pose), morph targets (the base
/// shape written), MSFT_lod levels (level 0 written), lights, orthographic
/// cameras, and textures other than the base colour.
#include "lodforge/core/log.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/scene/node.h"

namespace lodforge::gltf {

/// The VRML97 scene ("#VRML V2.0 utf8") drawing what `model` shows. Warnings
/// go to `log`. Throws DataError for a primitive primitive_mesh refuses.
scene::Scene gltf_to_vrml97(const tinygltf::Model& model, Log& log);

}  // namespace lodforge::gltf
