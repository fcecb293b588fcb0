#pragma once
/// Synthetic range scans of a mesh (Kim, sec. 4.4: "the input data are
/// generated from mesh models instead of range scanner"), so that the
/// range-image path can be tested end to end without a scanner.
#include <vector>

#include "lodforge/mcoctree/range_scan.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct ScanOptions {
  /// Viewing directions, spread evenly on the sphere (a Fibonacci lattice), 1..1000.
  int views = 6;
  /// Grid points across the square each view covers (the bounding sphere's
  /// silhouette), 4..4096: the spacing is the bounding-box diagonal / resolution.
  int resolution = 256;
};

/// Casts one parallel ray per grid point from each view towards the mesh and
/// keeps the nearest hit (a z-buffer over the triangles: exact ray-triangle
/// hits, O(triangles + grid points hit) per view). Scan k is named
/// `scanNNN.ply`, its frame has the sensor on +z (the layout of range_scan.h)
/// and its transformation maps it onto the mesh. Points carry the mesh's
/// interpolated colour when it has colours.
///
/// Throws DataError for a mesh without triangles or with non-finite
/// coordinates; DataError for options out of range.
std::vector<RangeScan> scan_mesh(const TriangleMesh& mesh, const ScanOptions& options = {});

}  // namespace lodforge
