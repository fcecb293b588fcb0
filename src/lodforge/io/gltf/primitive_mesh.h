#pragma once
/// The geometry of one glTF mesh primitive as a TriangleMesh in the mesh's
/// own (local) coordinates: every vertex of its POSITION accessor, triangles
/// from TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN (strips and fans converted
/// as the glTF 2.0 specification's "Primitive" section orders them, so the
/// triangles keep their facing), segments from LINES, LINE_LOOP and
/// LINE_STRIP. POINTS give vertices only.
#include "lodforge/mesh/triangle_mesh.h"

#include <tiny_gltf.h>

namespace lodforge::gltf {

/// Positions, triangles and lines of `primitive` (no other attributes;
/// empty for a primitive without POSITION, which glTF viewers skip).
/// Triangles with two equal indices are dropped. Preconditions: the model
/// passed read_gltf's checks. Throws DataError naming the mesh for a
/// POSITION that is not VEC3, or an index past the vertex count.
TriangleMesh primitive_mesh(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                            int mesh_index = -1);

}  // namespace lodforge::gltf
