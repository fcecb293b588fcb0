#pragma once
/// A VRML 1.0 or Open Inventor scene graph (as read, or as `lod` writes it)
/// as a VRML97 or X3D classic scene, so a scene of LOD nodes reaches the
/// browsers that read only the newer languages.
///
/// VRML 1.0's state (transforms, materials and bindings, coordinates,
/// textures) has no one-to-one VRML97 form (MatrixTransform with shear,
/// material rows bound per face or vertex, Inventor's VertexProperty), so it
/// is baked: every shape the scene draws (scene::collect_lod_shapes, each USE
/// again) becomes a VRML97 Shape in world coordinates with what it looks
/// like:
///  - faces (IndexedFaceSet, the Inventor sets and strips, and the primitives
///    Cube, Sphere, Cone, Cylinder tessellated by the Complexity in effect) as
///    an IndexedFaceSet of triangles, `solid FALSE` (VRML 1.0 does not know a
///    face's side), creaseAngle 0.5 (VRML 1.0's default);
///  - IndexedLineSet / LineSet as IndexedLineSet, PointSet as PointSet;
///  - one colour for the shape as Material diffuseColor (emissiveColor for
///    lines and points, which VRML97 draws unlit) and transparency, several
///    as a Color node per vertex; colours are diffuse + emissive of the
///    Material row, as scene::shape_surface resolves them;
///  - texture coordinates as TextureCoordinate, a Texture2 file as
///    ImageTexture (wrapS / wrapT as repeatS / repeatT), an inline Texture2
///    image as PixelTexture (the SFImage is the same value).
///
/// Each LOD node occurrence becomes a LOD at the top level with its `range`
/// unchanged, its `center` carried into world coordinates by the transform in
/// effect at the LOD (the distance a VRML 1.0 viewer compares with the range,
/// as scene::traverse measures it), its DEF name, and one Group per child
/// holding that child's shapes (an empty child an empty Group). Shapes
/// outside any LOD are top-level Shapes, named by their node's DEF name.
///
/// Nothing is dropped silently: shapes without geometry (AsciiText) and
/// WWWInline / camera / light nodes, which the conversion does not carry, are
/// counted by type in one warning each.
#include "lodforge/core/log.h"
#include "lodforge/scene/node.h"

namespace lodforge::vrml97 {

struct Vrml1ToVrml97Options {
  bool x3d = false;  ///< X3D classic (`#X3D V3.0 utf8`, PROFILE Immersive), else VRML97
};

/// The converted scene, ready for write_vrml97. Throws the DataErrors of
/// scene::shape_surface (an index out of range, coordinates not finite).
scene::Scene vrml1_to_vrml97(const scene::Scene& scene, const Vrml1ToVrml97Options& options,
                             Log& log);

}  // namespace lodforge::vrml97
