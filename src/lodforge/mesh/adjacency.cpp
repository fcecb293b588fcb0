// Mesh adjacency in CSR form, built in linear time.
//
// The vertex -> triangle lists are a counting sort of the triangle corners.
// Edges are then enumerated per vertex v from its triangle list: each
// neighbour w > v seen for the first time while visiting v gets a new edge
// (a "last visited by" mark per vertex replaces a hash table), which gives the
// unique edges sorted by (lo, hi) without any sort.
#include "lodforge/mesh/adjacency.h"

#include <algorithm>
#include <cassert>
#include <numeric>

#include "lodforge/core/union_find.h"
#include "lodforge/mesh/weld.h"

namespace lodforge {

std::uint32_t MeshAdjacency::find_edge(std::uint32_t a, std::uint32_t b) const {
  if (a == b) return kNoEdge;
  for (std::uint32_t t : triangles_of_vertex(a))
    for (std::uint32_t e : triangle_edges[t])
      if (e != kNoEdge && edges[e] == Segment{std::min(a, b), std::max(a, b)}) return e;
  return kNoEdge;
}

MeshAdjacency build_adjacency(std::size_t vertex_count, std::span<const Triangle> triangles) {
  MeshAdjacency adj;
  std::size_t nv = vertex_count;
  std::size_t nf = triangles.size();

  // Vertex -> triangles (a triangle appears once per distinct corner vertex).
  adj.vertex_offsets.assign(nv + 1, 0);
  auto distinct = [](const Triangle& t, int k) {
    return k == 0 || (k == 1 && t[1] != t[0]) || (k == 2 && t[2] != t[0] && t[2] != t[1]);
  };
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) {
      assert(t[k] < nv);
      if (distinct(t, k)) ++adj.vertex_offsets[t[k] + 1];
    }
  for (std::size_t v = 0; v < nv; ++v) adj.vertex_offsets[v + 1] += adj.vertex_offsets[v];
  adj.vertex_triangles.resize(adj.vertex_offsets[nv]);
  {
    std::vector<std::uint32_t> fill(adj.vertex_offsets.begin(), adj.vertex_offsets.end() - 1);
    for (std::uint32_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k)
        if (distinct(triangles[f], k)) adj.vertex_triangles[fill[triangles[f][k]]++] = f;
  }

  // Unique edges, and each triangle side's edge.
  adj.triangle_edges.assign(
      nf, {MeshAdjacency::kNoEdge, MeshAdjacency::kNoEdge, MeshAdjacency::kNoEdge});
  std::vector<std::uint32_t> mark(nv, kNone), edge_of(nv, kNone);
  for (std::uint32_t v = 0; v < nv; ++v) {
    for (std::uint32_t f : adj.triangles_of_vertex(v)) {
      const Triangle& t = triangles[f];
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = t[k], b = t[(k + 1) % 3];
        if (a == b || std::min(a, b) != v) continue;
        std::uint32_t w = std::max(a, b);
        if (mark[w] != v) {
          mark[w] = v;
          edge_of[w] = static_cast<std::uint32_t>(adj.edges.size());
          adj.edges.push_back({v, w});
        }
        adj.triangle_edges[f][k] = edge_of[w];
      }
    }
  }

  // Edge -> triangles (once per triangle even if two of its sides are the edge).
  std::size_t ne = adj.edges.size();
  auto repeated = [&](std::uint32_t f, int k) {
    const auto& te = adj.triangle_edges[f];
    return te[k] == MeshAdjacency::kNoEdge || (k >= 1 && te[k] == te[0]) ||
           (k == 2 && te[2] == te[1]);
  };
  adj.edge_offsets.assign(ne + 1, 0);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (!repeated(f, k)) ++adj.edge_offsets[adj.triangle_edges[f][k] + 1];
  for (std::size_t e = 0; e < ne; ++e) adj.edge_offsets[e + 1] += adj.edge_offsets[e];
  adj.edge_triangles.resize(adj.edge_offsets[ne]);
  {
    std::vector<std::uint32_t> fill(adj.edge_offsets.begin(), adj.edge_offsets.end() - 1);
    for (std::uint32_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k)
        if (!repeated(f, k)) adj.edge_triangles[fill[adj.triangle_edges[f][k]]++] = f;
  }
  for (std::uint32_t e = 0; e < ne; ++e) {
    std::size_t valence = adj.edge_valence(e);
    if (valence == 1) adj.boundary_edges.push_back(e);
    if (valence >= 3) adj.non_manifold_edges.push_back(e);
  }
  return adj;
}

TopologyReport mesh_topology_report(const TriangleMesh& mesh) {
  TopologyReport r;
  MeshAdjacency adj = build_adjacency(mesh);
  std::size_t nv = mesh.vertex_count();
  r.vertices = nv;
  r.triangles = mesh.triangle_count();
  r.edges = adj.edges.size();
  r.boundary_edges = adj.boundary_edges.size();
  r.non_manifold_edges = adj.non_manifold_edges.size();

  for (const Triangle& t : mesh.triangles)
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) ++r.degenerate_triangles;

  // Does triangle f traverse edge {lo, hi} from lo to hi?
  auto forward = [&](std::uint32_t f, const Segment& e) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] == e[0] && t[(k + 1) % 3] == e[1]) return true;
    return false;
  };
  for (std::uint32_t e = 0; e < adj.edges.size(); ++e) {
    if (adj.edge_valence(e) != 2) continue;
    auto tris = adj.triangles_of_edge(e);
    if (forward(tris[0], adj.edges[e]) == forward(tris[1], adj.edges[e])) ++r.inconsistent_edges;
  }

  // Fans around each vertex: its triangles linked through 2-triangle edges.
  std::vector<std::uint32_t> local_parent;
  for (std::uint32_t v = 0; v < nv; ++v) {
    auto tris = adj.triangles_of_vertex(v);
    if (tris.empty()) {
      ++r.isolated_vertices;
      continue;
    }
    local_parent.resize(tris.size());
    std::iota(local_parent.begin(), local_parent.end(), 0u);
    auto find = [&](std::uint32_t a) {
      while (local_parent[a] != a) a = local_parent[a] = local_parent[local_parent[a]];
      return a;
    };
    std::size_t fans = tris.size();
    for (std::uint32_t i = 0; i < tris.size(); ++i) {
      for (std::uint32_t e : adj.triangle_edges[tris[i]]) {
        if (e == MeshAdjacency::kNoEdge || adj.edge_valence(e) != 2) continue;
        if (adj.edges[e][0] != v && adj.edges[e][1] != v) continue;
        auto et = adj.triangles_of_edge(e);
        std::uint32_t other = et[0] == tris[i] ? et[1] : et[0];
        auto it = std::lower_bound(tris.begin(), tris.end(), other);
        std::uint32_t a = find(i), b = find(static_cast<std::uint32_t>(it - tris.begin()));
        if (a != b) {
          local_parent[a] = b;
          --fans;
        }
      }
    }
    if (fans > 1) ++r.non_manifold_vertices;
  }

  UnionFind components(nv);
  for (const Triangle& t : mesh.triangles) {
    components.unite(t[0], t[1]);
    components.unite(t[1], t[2]);
  }
  for (std::uint32_t v = 0; v < nv; ++v)
    if (adj.vertex_offsets[v + 1] > adj.vertex_offsets[v] && components.find(v) == v)
      ++r.components;

  UnionFind loops(nv);
  std::vector<bool> on_boundary(nv, false);
  for (std::uint32_t e : adj.boundary_edges) {
    loops.unite(adj.edges[e][0], adj.edges[e][1]);
    on_boundary[adj.edges[e][0]] = on_boundary[adj.edges[e][1]] = true;
  }
  for (std::uint32_t v = 0; v < nv; ++v)
    if (on_boundary[v] && loops.find(v) == v) ++r.boundary_loops;
  return r;
}

std::vector<std::uint32_t> triangle_parts(const TriangleMesh& mesh) {
  // Vertices at one position are one vertex here.
  const std::vector<std::uint32_t> vertex = weld(mesh, {.remove_degenerate = false}).remap;
  UnionFind parts(mesh.positions.size());
  for (const Triangle& t : mesh.triangles) {
    parts.unite(vertex[t[0]], vertex[t[1]]);
    parts.unite(vertex[t[1]], vertex[t[2]]);
  }
  std::vector<std::uint32_t> label(mesh.positions.size(), kNone), out;
  out.reserve(mesh.triangles.size());
  std::uint32_t next = 0;
  for (const Triangle& t : mesh.triangles) {
    std::uint32_t& l = label[parts.find(vertex[t[0]])];
    if (l == kNone) l = next++;
    out.push_back(l);
  }
  return out;
}

}  // namespace lodforge
