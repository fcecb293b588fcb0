#pragma once
/// Points spread over a mesh's surface, for measuring distances between
/// surfaces (Metro-style comparison).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct SampleOptions {
  std::size_t count = 100'000;  ///< area-weighted samples inside triangles (0: none)
  std::uint64_t seed = 1;       ///< same seed, same mesh, same options -> same samples
  bool vertices = true;         ///< add every vertex used by a triangle, once
  std::size_t edge_count = 0;   ///< samples along the edges, spread by length (0: none)
  bool vertex_normals = true;   ///< interpolate the mesh's vertex normals if it has any
};

/// Samples, all arrays #S long. Order: vertex samples, then edge samples, then
/// area samples.
struct SurfaceSamples {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;             ///< unit; zero where the triangle is degenerate
  std::vector<std::uint32_t> triangles;  ///< triangle each sample lies on
  /// #S, the mesh's vertex colours interpolated at each sample; empty when
  /// the mesh has no colours.
  std::vector<Vec3> colors;
  std::size_t vertex_samples = 0;  ///< how many of the first samples are vertices
  std::size_t edge_samples = 0;    ///< how many edge samples follow them
  double area = 0;                 ///< total surface area of the mesh

  std::size_t size() const { return positions.size(); }
};

/// Samples `mesh`'s surface. Area samples are stratified over the cumulative
/// triangle areas (sample i falls in the i-th of `count` equal slices of the
/// total area, at a random place in it), so every triangle receives its share
/// up to one sample; inside a triangle the place is uniform. Randomness comes
/// from a counter-based generator keyed by (seed, i): the result does not
/// depend on the number of threads.
///
/// Colours, when the mesh has them, are interpolated like vertex normals
/// (a vertex sample takes its vertex's colour).
/// The normal of a sample interpolates the mesh's per-vertex normals when it
/// has them (and options.vertex_normals), else it is the face normal. A vertex sample takes the
/// first triangle using that vertex. Degenerate triangles get no area samples (their area is zero);
/// a mesh without area gets vertex and edge samples only. Preconditions: triangle indices < #V
/// (assert).
SurfaceSamples sample_surface(const TriangleMesh& mesh, const SampleOptions& options = {});

}  // namespace lodforge
