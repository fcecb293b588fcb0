// Compiling the marching-cube octree (Kim, "Level-of-detail mesh modeling
// using the marching cube octree", ch. 6) into its run-time model.
//
// The thesis triangulates the children of the visited nodes during the walk.
// Everything that triangulation reads is fixed once N is known, and for one
// node it changes with N only at a handful of priorities: the node is emitted
// from its parent's priority to its own, and its boundary resolution (which
// faces and edges are split, see cell_polygonize.cpp) changes only at the
// split priorities of its faces and edges inside that range. So the walk's
// work is done here, once per node and interval:
//
//   interval start s           | state
//   ---------------------------+---------------------------------------------
//   parent's priority p        | faces / edges with split priority <= p split
//   each split priority in     | the same rule with s: one more face or edge
//   (p, own priority)          | (or several, when they share the priority)
//
// and the run-time walk copies triangle indices. The loop centroids, the one
// floating-point step of the old walk, become vertices of the table here.
#include "lodforge/mcoctree/mc_lod_model.h"

#include <algorithm>
#include <cassert>

#include "lodforge/mcoctree/cell_mesh.h"

namespace lodforge {
namespace {

std::uint16_t snorm16(float x) {
  auto q = static_cast<std::int16_t>(std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f));
  return static_cast<std::uint16_t>(q);
}

class Compiler {
 public:
  Compiler(const McOctree& tree, McLodModel& model)
      : t_(tree), m_(model), vmap_(tree.positions.size(), McNode::kNone) {}

  void run() {
    const auto L = static_cast<std::uint32_t>(t_.lod.size());
    m_.depth = t_.depth;
    m_.origin = t_.origin;
    m_.cell_size = t_.cell_size;
    m_.accumulated = t_.accumulated;
    m_.group.assign(L + 2, 0);
    if (!t_.nodes.empty()) add_cell(t_.nodes[0], 0);
    for (std::uint32_t k = 1; k <= L; ++k) {
      m_.group[k] = static_cast<std::uint32_t>(m_.cells.size());
      const McNode& p = t_.nodes[t_.lod[k - 1]];
      for (int o = 0; o < 8; ++o)
        if (auto c = p.child(o); c != McNode::kNone) add_cell(t_.nodes[c], k);
    }
    m_.group[L + 1] = static_cast<std::uint32_t>(m_.cells.size());
    m_.cells.push_back({0, static_cast<std::uint32_t>(m_.intervals.size())});
    m_.intervals.push_back({McLodModel::kNever, static_cast<std::uint32_t>(m_.triangles.size())});
    m_.triangles.resize(m_.triangles.size() + McLodModel::kCopyBlock, Triangle{0, 0, 0});
    m_.positions.shrink_to_fit();
    m_.normals.shrink_to_fit();
    m_.colors.shrink_to_fit();
    m_.cells.shrink_to_fit();
    m_.intervals.shrink_to_fit();
    m_.triangles.shrink_to_fit();
  }

 private:
  // Centroids are model vertices already; emit() tells them apart by this bit.
  static constexpr std::uint32_t kModelVertex = 0x80000000u;

  // The model's index of tree vertex v, numbering it at its first use.
  std::uint32_t vertex(std::uint32_t v) {
    if (v & kModelVertex) return v & ~kModelVertex;
    if (vmap_[v] == McNode::kNone) {
      vmap_[v] = static_cast<std::uint32_t>(m_.positions.size());
      push_vertex(t_.positions[v], t_.normals[v], t_.colors.empty() ? nullptr : &t_.colors[v]);
    }
    return vmap_[v];
  }
  void push_vertex(Vec3 p, Vec3 n, const Rgb8* c) {
    m_.positions.push_back(p);
    m_.normals.push_back(encode_normal(n));
    if (c) m_.colors.push_back(*c);
  }

  // A cell emitted from priority `from` (its parent's) until its own.
  void add_cell(const McNode& n, std::uint32_t from) {
    const std::uint32_t until = n.priority;
    assert(until > from || from == 0);
    const auto cell_intervals = static_cast<std::uint32_t>(m_.intervals.size());
    m_.cells.push_back({until, cell_intervals});
    std::uint32_t starts[19];
    int count = 0;
    starts[count++] = from;
    for (auto s : n.face_split)
      if (s > from && s < until) starts[count++] = s;
    for (auto s : n.edge_split)
      if (s > from && s < until) starts[count++] = s;
    std::sort(starts + 1, starts + count);
    count = static_cast<int>(std::unique(starts, starts + count) - starts);
    for (int i = 0; i < count; ++i) {
      const std::uint32_t s = starts[i];
      std::uint16_t halved = 0;
      std::uint8_t split = 0;
      for (int e = 0; e < 12; ++e)
        halved |= static_cast<std::uint16_t>((n.edge_split[e] <= s) << e);
      for (int f = 0; f < 6; ++f) split |= static_cast<std::uint8_t>((n.face_split[f] <= s) << f);
      m_.intervals.push_back({s, static_cast<std::uint32_t>(m_.triangles.size())});
      detail::triangulate_node(
          t_, n, halved, split,
          [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
            m_.triangles.push_back({vertex(a), vertex(b), vertex(c)});
          },
          [&](const std::uint8_t* slots, int k, std::uint16_t h) {
            return centroid(n, slots, k, h);
          });
      drop_if_unchanged(cell_intervals);
    }
  }

  // A split that changes nothing (no crossing on the face or edge split, the
  // common case) leaves the triangles as they were: merge the new interval
  // into the previous one.
  void drop_if_unchanged(std::uint32_t first_of_cell) {
    const auto j = static_cast<std::uint32_t>(m_.intervals.size() - 1);
    if (j == first_of_cell) return;
    const std::uint32_t a = m_.intervals[j - 1].first_triangle, b = m_.intervals[j].first_triangle;
    const auto e = static_cast<std::uint32_t>(m_.triangles.size());
    if (e - b != b - a ||
        !std::equal(m_.triangles.begin() + a, m_.triangles.begin() + b, m_.triangles.begin() + b))
      return;
    m_.triangles.resize(b);
    m_.intervals.pop_back();
  }

  // A loop no diagonal may cut (cell_polygonize.cpp) gets a vertex at its
  // centroid: the average of its points, normals and colours.
  std::uint32_t centroid(const McNode& n, const std::uint8_t* slots, int count, std::uint16_t h) {
    Vec3 p{}, nn{}, col{};
    for (int k = 0; k < count; ++k) {
      std::uint32_t v = detail::slot_vertex(t_, n, slots[k], h);
      p += t_.positions[v];
      nn += t_.normals[v];
      if (!t_.colors.empty())
        for (int a = 0; a < 3; ++a) col[a] += t_.colors[v][a];
    }
    Rgb8 c{};
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<std::uint8_t>(std::lround(col[a] / static_cast<float>(count)));
    auto id = static_cast<std::uint32_t>(m_.positions.size());
    push_vertex(p / static_cast<float>(count), normalized(nn), t_.colors.empty() ? nullptr : &c);
    m_.centroids.push_back(id);
    return id | kModelVertex;
  }

  const McOctree& t_;
  McLodModel& m_;
  std::vector<std::uint32_t> vmap_;
};

}  // namespace

std::uint32_t encode_normal(Vec3 n) {
  float s = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(s > 0)) return 0;  // a zero or NaN normal: +z by convention
  float u = n.x / s, v = n.y / s;
  if (n.z < 0) {
    float pu = (1.0f - std::abs(v)) * (u >= 0 ? 1.0f : -1.0f);
    float pv = (1.0f - std::abs(u)) * (v >= 0 ? 1.0f : -1.0f);
    u = pu, v = pv;
  }
  return snorm16(u) | static_cast<std::uint32_t>(snorm16(v)) << 16;
}

std::size_t McLodModel::memory_bytes() const {
  return positions.size() * sizeof(Vec3) + normals.size() * sizeof(std::uint32_t) +
         colors.size() * sizeof(Rgb8) + group.size() * sizeof(std::uint32_t) +
         cells.size() * sizeof(McLodCell) + intervals.size() * sizeof(McLodInterval) +
         triangles.size() * sizeof(Triangle) + accumulated.size() * sizeof(std::uint64_t) +
         centroids.size() * sizeof(std::uint32_t);
}

McLodModel compile_mc_lod(const McOctree& tree) {
  McLodModel model;
  Compiler(tree, model).run();
  return model;
}

}  // namespace lodforge
