#pragma once
/// The scene LOD pipeline for VRML97 and X3D (classic encoding) scenes as read
/// by io/vrml97: every Shape whose geometry is an IndexedFaceSet,
/// IndexedTriangleSet, TriangleSet, IndexedQuadSet or ElevationGrid becomes
///
///     LOD { range [...] center C
///           level [ <the input Shape, unchanged>,
///                   Shape { appearance USE <same> geometry IndexedFaceSet {
///                           coord USE <one Coordinate shared by the simplified levels>
///                           normal / texCoord / color USE <the input's nodes> ... } },
///                   ...,
///                   Group {} ] }
///
/// (X3D: `children` instead of `level`). Levels come from choose_levels, the
/// ranges from switching_ranges with the largest accumulated Transform scale
/// of the shape's occurrences and the first Viewpoint's fieldOfView (π/4 by
/// default) unless LodOptions::camera_angle_given. Normals, texture
/// coordinates and colours follow the simplifier's vertex_map (per-vertex)
/// and face_map (per-face) into the input's own attribute nodes (an
/// ElevationGrid's points and default texture coordinates become new nodes). A Shape
/// DEF/USEd several times is simplified once and its LOD shared. Shapes inside
/// PROTO bodies (kept verbatim) and other geometry are left as they are.
#include "lodforge/lod/generate_lod.h"
#include "lodforge/scene/node.h"

namespace lodforge {

/// Runs the pipeline on a scene whose header is VRML97 or X3D classic; the
/// output keeps the header. Uses of LodOptions: method, range,
/// camera_angle_given, min_diff, level_spacing, level_ratio, max_levels,
/// triangulation, measure_samples, threads. A shape whose coordinate index is
/// out of range is left as it is, with a warning in the log naming its line;
/// an attribute index out of range drops that attribute from its levels.
/// Throws DataError (from the simplifiers) for coordinates that are not finite.
LodResult generate_lod_vrml97(scene::Scene scene, const LodOptions& options = {});

}  // namespace lodforge
