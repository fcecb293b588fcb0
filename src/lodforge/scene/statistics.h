#pragma once
/// Counts over a scene graph, as `lodforge info` shows them and as tests
/// compare with other readers.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/scene/node.h"

namespace lodforge::scene {

struct SceneStatistics {
  /// Distinct node objects per type (a node shared by USE counts once).
  std::map<std::string, std::size_t> node_counts;
  /// Node instances met by a rendering traversal (USE counts every time;
  /// Switch follows whichChild, LOD takes its first child).
  std::size_t shapes_traversed = 0;
  /// Triangles of IndexedFaceSets met by the traversal: every face with n >= 3
  /// vertices gives n - 2 triangles (the count a renderer draws).
  std::size_t ifs_triangles = 0;
  /// Faces of IndexedFaceSets met by the traversal.
  std::size_t ifs_faces = 0;
  /// Line segments of IndexedLineSets met by the traversal.
  std::size_t ils_segments = 0;
  /// Points of Coordinate3 nodes (distinct nodes).
  std::size_t coordinate_points = 0;
  /// Triangles of all shapes met by the traversal, primitives tessellated.
  std::size_t total_triangles = 0;
  /// Vertices of all shapes met by the traversal.
  std::size_t total_vertices = 0;
  /// World-space bounding box of all shapes met by the traversal.
  Box3 bounds;
  /// Shapes whose geometry cannot be built (index out of range, NaN, ...):
  /// the reason, with the line. They count as empty in the totals.
  std::vector<std::string> problems;
};

/// Traverses the scene once and counts.
SceneStatistics scene_statistics(const Scene& scene);

}  // namespace lodforge::scene
