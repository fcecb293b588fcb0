#include "lodforge/mesh/vertex_normals.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace lodforge {

std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh) {
  struct PositionHash {
    std::size_t operator()(const Vec3& p) const {
      const float v[3] = {p.x + 0.f, p.y + 0.f, p.z + 0.f};  // -0 hashes like +0
      std::uint32_t bits[3];
      std::memcpy(bits, v, sizeof bits);
      return (bits[0] * 73856093u) ^ (bits[1] * 19349663u) ^ (bits[2] * 83492791u);
    }
  };
  std::unordered_map<Vec3, std::uint32_t, PositionHash> first_at;
  std::vector<std::uint32_t> slot(mesh.positions.size());
  for (std::size_t i = 0; i < slot.size(); ++i)
    slot[i] = first_at.try_emplace(mesh.positions[i], static_cast<std::uint32_t>(i)).first->second;
  std::vector<Vec3> n(mesh.positions.size());
  for (const auto& t : mesh.triangles) {
    const Vec3 fn = normalized(cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                     mesh.positions[t[2]] - mesh.positions[t[0]]));
    if (!is_finite(fn) || fn == Vec3{}) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions[t[k]];
      const Vec3 e1 = normalized(mesh.positions[t[(k + 1) % 3]] - p);
      const Vec3 e2 = normalized(mesh.positions[t[(k + 2) % 3]] - p);
      const float angle = std::acos(std::clamp(dot(e1, e2), -1.f, 1.f));
      n[slot[t[k]]] += fn * angle;
    }
  }
  for (std::size_t i = 0; i < n.size(); ++i) n[i] = normalized(n[slot[i]]);
  return n;
}

}  // namespace lodforge
