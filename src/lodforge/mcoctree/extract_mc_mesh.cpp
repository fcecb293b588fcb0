// Extraction of a level of detail (Kim, "Level-of-detail mesh modeling using
// the marching cube octree", ch. 6.1-6.2): for N, walk the LOD array from N
// down to 1 and triangulate the children of each node that are not expanded
// themselves. The thesis marks nodes 'expanded' during the walk; a child is
// expanded exactly when its priority is <= N, so a comparison replaces the
// mark and nothing has to be reset between calls.
//
// Crack patching is not a vertex move here but the choice of each cell's
// boundary resolution (see cell_polygonize.cpp): face f of a cell is split
// when its same-level neighbour is expanded (face_split[f] <= N), an edge when
// any same-level cell sharing it is (edge_split[e] <= N). Those thresholds are
// precomputed, so the loop compares integers and copies vertices.
#include "lodforge/mcoctree/extract_mc_mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lodforge/mcoctree/cell_mesh.h"

namespace lodforge {

std::uint32_t priority_for_triangles(const McOctree& tree, std::uint64_t triangles) {
  std::uint32_t best = 0;
  std::uint64_t best_diff = UINT64_MAX;
  for (std::size_t n = 0; n < tree.accumulated.size(); ++n) {
    std::uint64_t a = tree.accumulated[n];
    std::uint64_t diff = a > triangles ? a - triangles : triangles - a;
    if (diff < best_diff) best_diff = diff, best = static_cast<std::uint32_t>(n);
  }
  return best;
}

McExtractor::McExtractor(const McOctree& tree)
    : tree_(tree), stamp_(tree.positions.size(), 0), remap_(tree.positions.size(), 0) {}

std::size_t McExtractor::extract(std::uint32_t priority, TriangleMesh& out) {
  const McOctree& t = tree_;
  const std::uint32_t N =
      std::min<std::uint32_t>(priority, static_cast<std::uint32_t>(t.lod.size()));
  out.positions.clear();
  out.normals.clear();
  out.colors.clear();
  out.triangles.clear();
  out.texcoords.clear();
  out.materials.clear();
  out.lines.clear();
  if (t.nodes.empty()) return 0;
  if (++epoch_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    epoch_ = 1;
  }
  const bool colored = !t.colors.empty();
  constexpr std::uint32_t kOutput = 0x80000000u;  // already an output index (a centroid)
  auto use = [&](std::uint32_t v) {
    if (v & kOutput) return v & ~kOutput;
    if (stamp_[v] != epoch_) {
      stamp_[v] = epoch_;
      remap_[v] = static_cast<std::uint32_t>(out.positions.size());
      out.positions.push_back(t.positions[v]);
      out.normals.push_back(t.normals[v]);
      if (colored)
        out.colors.push_back(
            Vec3{t.colors[v][0] / 255.0f, t.colors[v][1] / 255.0f, t.colors[v][2] / 255.0f});
    }
    return remap_[v];
  };
  auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    out.triangles.push_back({use(a), use(b), use(c)});
  };
  auto cell = [&](const McNode& n) {
    std::uint16_t halved = 0;
    std::uint8_t split = 0;
    for (int e = 0; e < 12; ++e) halved |= static_cast<std::uint16_t>((n.edge_split[e] <= N) << e);
    for (int f = 0; f < 6; ++f) split |= static_cast<std::uint8_t>((n.face_split[f] <= N) << f);
    detail::triangulate_node(
        t, n, halved, split, emit, [&](const std::uint8_t* slots, int count, std::uint16_t h) {
          // The one floating-point step: a loop no diagonal may cut.
          Vec3 p{}, nn{}, col{};
          for (int k = 0; k < count; ++k) {
            std::uint32_t v = detail::slot_vertex(t, n, slots[k], h);
            p += t.positions[v];
            nn += t.normals[v];
            if (colored)
              col +=
                  Vec3{t.colors[v][0] / 255.0f, t.colors[v][1] / 255.0f, t.colors[v][2] / 255.0f};
          }
          ++centroids_;
          out.positions.push_back(p / static_cast<float>(count));
          out.normals.push_back(normalized(nn));
          if (colored) out.colors.push_back(col / static_cast<float>(count));
          return static_cast<std::uint32_t>(out.positions.size() - 1) | kOutput;
        });
  };
  if (N == 0) {
    cell(t.nodes[0]);
  } else {
    for (std::uint32_t i = N; i >= 1; --i) {
      const McNode& n = t.nodes[t.lod[i - 1]];
      for (int o = 0; o < 8; ++o) {
        std::uint32_t c = n.child(o);
        if (c == McNode::kNone || t.nodes[c].priority <= N) continue;
        cell(t.nodes[c]);
      }
    }
  }
  return out.triangles.size();
}

McExtractResult extract_mc_mesh(const McOctree& tree, const McExtractOptions& options) {
  int set = (options.priority >= 0) + (options.triangles >= 0) + (options.percent >= 0);
  if (set > 1) throw std::invalid_argument("mcoctree: set one of priority, triangles, percent");
  if (options.percent >= 0 && !std::isfinite(options.percent))
    throw std::invalid_argument("mcoctree: percent must be finite");
  McExtractResult result;
  const auto max_priority = static_cast<std::int64_t>(tree.lod.size());
  const std::uint64_t full = tree.full_triangles();
  if (options.priority >= 0) {
    result.clamped = options.priority > max_priority;
    result.priority = static_cast<std::uint32_t>(std::min(options.priority, max_priority));
  } else if (options.triangles >= 0 || options.percent >= 0) {
    double want = options.triangles >= 0 ? static_cast<double>(options.triangles)
                                         : options.percent / 100.0 * static_cast<double>(full);
    result.clamped = want > static_cast<double>(full) || (options.percent > 100);
    want = std::clamp(want, 0.0, static_cast<double>(full));
    result.requested = static_cast<std::uint64_t>(std::llround(want));
    result.priority = priority_for_triangles(tree, result.requested);
  } else {
    result.priority = static_cast<std::uint32_t>(max_priority);
  }
  McExtractor extractor(tree);
  extractor.extract(result.priority, result.mesh);
  result.centroid_vertices = extractor.centroid_vertices();
  return result;
}

}  // namespace lodforge
