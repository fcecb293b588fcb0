// The distance metric of the priority numbering: instead of the thesis's
// area difference (Kim sec. 5.3), how far the finest surface under a node
// lies from what the node shows while it is not expanded. The surface points
// are the leaves' edge points (every vertex of the model is one); each is
// claimed by the first leaf that holds it, so that the points under any node
// form one contiguous range of the claim order (leaves are in Morton order,
// and a node's descendants at any level are contiguous there). Work: the
// surface points times the depth, each against a handful of triangles.
#include "lodforge/mcoctree/node_error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "lodforge/mcoctree/cell_mesh.h"
#include "lodforge/metrics/closest_point_on_triangle.h"

namespace lodforge::detail {

std::vector<double> node_distance_sums(const McOctree& t) {
  const auto count = static_cast<std::uint32_t>(t.nodes.size());
  // The surface points, leaf by leaf, and each node's range [lo, hi) of them.
  std::vector<std::uint32_t> points, lo(count), hi(count);
  points.reserve(t.positions.size());
  std::vector<std::uint8_t> claimed(t.positions.size(), 0);
  for (std::uint32_t i = 0; i < count; ++i) {
    const McNode& n = t.nodes[i];
    if (!n.leaf()) continue;
    lo[i] = static_cast<std::uint32_t>(points.size());
    for (auto v : n.edge_vertex)
      if (v != McNode::kNone && !claimed[v]) {
        claimed[v] = 1;
        points.push_back(v);
      }
    hi[i] = static_cast<std::uint32_t>(points.size());
  }
  for (std::uint32_t i = count; i-- > 0;) {
    const McNode& n = t.nodes[i];
    if (n.leaf()) continue;
    lo[i] = std::numeric_limits<std::uint32_t>::max();
    hi[i] = 0;
    for (int o = 0; o < 8; ++o)
      if (auto c = n.child(o); c != McNode::kNone) {
        assert(c > i);
        lo[i] = std::min(lo[i], lo[c]);
        hi[i] = std::max(hi[i], hi[c]);
      }
  }
  std::vector<double> sums(count, 0);
  tbb::parallel_for(std::uint32_t{0}, count, [&](std::uint32_t i) {
    const McNode& n = t.nodes[i];
    if (n.leaf() || lo[i] >= hi[i]) return;
    std::array<std::array<Vec3, 3>, kMaxCellTriangles> tris;
    int m = 0;
    triangulate_node(
        t, n, 0, 0,
        [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
          tris[m++] = {t.positions[a], t.positions[b], t.positions[c]};
        },
        [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
    if (m == 0) {
      const float diagonal =
          std::sqrt(3.0f) * t.cell_size * static_cast<float>(1u << (t.depth - n.level));
      sums[i] = double{diagonal} * (hi[i] - lo[i]);
      return;
    }
    double sum = 0;
    for (std::uint32_t k = lo[i]; k < hi[i]; ++k) {
      const Vec3& p = t.positions[points[k]];
      float best = std::numeric_limits<float>::max();
      for (int j = 0; j < m && best > 0; ++j)
        best = std::min(
            best,
            closest_point_on_triangle(p, tris[j][0], tris[j][1], tris[j][2]).distance_squared);
      sum += std::sqrt(best);
    }
    sums[i] = sum;
  });
  return sums;
}

}  // namespace lodforge::detail
