#pragma once
/// Crack checks for extracted meshes: after exact welding of coincident
/// vertices, no boundary edge, no non-manifold edge, no T-junction (a vertex
/// strictly inside another triangle's edge) and consistent orientation.
#include <sstream>
#include <string>

#include "lodforge/mesh/adjacency.h"
#include "lodforge/mesh/weld.h"

namespace lodforge::test {

struct CrackReport {
  TopologyReport topology;
  std::size_t t_junctions = 0;
  bool ok() const {
    return topology.boundary_edges == 0 && topology.non_manifold_edges == 0 &&
           topology.inconsistent_edges == 0 && topology.degenerate_triangles == 0 &&
           t_junctions == 0;
  }
  std::string describe() const {
    std::ostringstream s;
    s << "boundary " << topology.boundary_edges << ", non-manifold " << topology.non_manifold_edges
      << ", inconsistent " << topology.inconsistent_edges << ", degenerate "
      << topology.degenerate_triangles << ", T-junctions " << t_junctions;
    return s.str();
  }
};

/// A T-junction leaves the long edge with one triangle, so after exact welding
/// it shows as boundary edges; t_junctions counts the boundary edges that have
/// a vertex on them (the strict T-junction test), for the message.
inline CrackReport crack_report(const TriangleMesh& mesh) {
  WeldResult w = weld(mesh, {.epsilon = 0, .remove_degenerate = false});
  CrackReport r;
  r.topology = mesh_topology_report(w.mesh);
  if (r.topology.boundary_edges > 0) {
    MeshAdjacency adj = build_adjacency(w.mesh);
    for (auto e : adj.boundary_edges) {
      Vec3 a = w.mesh.positions[adj.edges[e][0]], b = w.mesh.positions[adj.edges[e][1]];
      Vec3 d = b - a;
      float l2 = dot(d, d);
      for (std::size_t v = 0; v < w.mesh.positions.size(); ++v) {
        if (v == adj.edges[e][0] || v == adj.edges[e][1]) continue;
        Vec3 p = w.mesh.positions[v] - a;
        float t = dot(p, d) / l2;
        if (t <= 0 || t >= 1) continue;
        if (length_squared(p - d * t) <= 1e-12f * l2) {
          ++r.t_junctions;
          break;
        }
      }
    }
  }
  return r;
}

}  // namespace lodforge::test
