#pragma once
/// Connectivity of an indexed triangle mesh: vertex -> triangles, the unique
/// undirected edges, edge -> triangles, triangle -> edges, and the boundary and
/// non-manifold edges; plus a topology summary built on top of it.
///
/// All lists are CSR arrays (an offsets array one longer than the number of
/// items, and a flat array), so the structure is a handful of allocations.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct MeshAdjacency {
  /// #V+1 offsets into vertex_triangles; the triangles around vertex v are
  /// vertex_triangles[vertex_offsets[v] .. vertex_offsets[v+1]), ascending.
  std::vector<std::uint32_t> vertex_offsets;
  std::vector<std::uint32_t> vertex_triangles;
  /// #E unique undirected edges, each stored as {lo, hi} with lo < hi.
  /// Edges of degenerate triangles that join a vertex to itself are omitted.
  std::vector<Segment> edges;
  /// #E+1 offsets into edge_triangles (the triangles using each edge, ascending).
  std::vector<std::uint32_t> edge_offsets;
  std::vector<std::uint32_t> edge_triangles;
  /// #F: edge index of the triangle's sides (v0,v1), (v1,v2), (v2,v0); kNoEdge
  /// for a side joining a vertex to itself.
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;
  /// Edges with exactly one triangle, and edges with three or more, ascending.
  std::vector<std::uint32_t> boundary_edges;
  std::vector<std::uint32_t> non_manifold_edges;

  static constexpr std::uint32_t kNoEdge = 0xffffffffu;

  std::span<const std::uint32_t> triangles_of_vertex(std::uint32_t v) const {
    return {vertex_triangles.data() + vertex_offsets[v], vertex_offsets[v + 1] - vertex_offsets[v]};
  }
  std::span<const std::uint32_t> triangles_of_edge(std::uint32_t e) const {
    return {edge_triangles.data() + edge_offsets[e], edge_offsets[e + 1] - edge_offsets[e]};
  }
  std::size_t edge_valence(std::uint32_t e) const { return edge_offsets[e + 1] - edge_offsets[e]; }
  /// Index of edge {a, b} (either order), or kNoEdge. O(valence of a).
  std::uint32_t find_edge(std::uint32_t a, std::uint32_t b) const;
};

/// Builds the adjacency of `triangles` over `vertex_count` vertices in
/// O(V + F). Precondition: every index < vertex_count (asserted).
MeshAdjacency build_adjacency(std::size_t vertex_count, std::span<const Triangle> triangles);
inline MeshAdjacency build_adjacency(const TriangleMesh& mesh) {
  return build_adjacency(mesh.vertex_count(), mesh.triangles);
}

struct TopologyReport {
  std::size_t vertices = 0;               ///< #V
  std::size_t triangles = 0;              ///< #F
  std::size_t edges = 0;                  ///< unique undirected edges
  std::size_t boundary_edges = 0;         ///< edges with one triangle
  std::size_t non_manifold_edges = 0;     ///< edges with three or more triangles
  std::size_t inconsistent_edges = 0;     ///< 2-triangle edges both triangles traverse the same way
  std::size_t non_manifold_vertices = 0;  ///< vertices whose triangles form more than one fan
  std::size_t isolated_vertices = 0;      ///< vertices used by no triangle
  std::size_t degenerate_triangles = 0;   ///< triangles using a vertex twice
  std::size_t components = 0;             ///< groups of triangles connected through shared vertices
  std::size_t boundary_loops = 0;         ///< closed chains of boundary edges (manifold boundaries)
  bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  /// V - E + F over the vertices used by triangles.
  long long euler_characteristic() const {
    return static_cast<long long>(vertices - isolated_vertices) - static_cast<long long>(edges) +
           static_cast<long long>(triangles);
  }
};

/// Counts the topological features of `mesh` (see TopologyReport). O(V + F).
TopologyReport mesh_topology_report(const TriangleMesh& mesh);

/// The connected part of each triangle (#F labels): triangles that share a
/// vertex, or a vertex position (weld's exact merge, so a seam of split
/// vertices does not cut a part in two), are in one part. Parts are numbered from 0 in the order of
/// their first triangle. O(V + F) expected.
std::vector<std::uint32_t> triangle_parts(const TriangleMesh& mesh);

}  // namespace lodforge
