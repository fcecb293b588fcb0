// Ray and closest-point queries through the marching-cube octree (Kim,
// "Level-of-detail mesh modeling using the marching cube octree", Table 7.1:
// collision detection in O(log n) through the octree), on the run-time model.
//
// The model keeps the tree implicitly: cell 0 is the root, and the children
// of the cell expanded at priority k (its `until`) are the cells of group k.
// At level N a cell of groups 0..N is either expanded (until <= N: its
// children stand for it) or emitted (its triangles are part of the level).
// The search tree is that tree cut at N: one node per cell with triangles
// below it, each with the bounding box of those triangles, which lies inside
// the cell's cube (a cell's triangles join points on its edges and faces,
// or their centroids) and is usually much tighter.
//
//   query    | order of the cells                  | a cell is skipped when
//   ---------+-------------------------------------+------------------------------
//   ray      | depth first, children nearest entry | its box's entry is beyond the
//            | first                               | nearest hit found
//   closest  | depth first, children nearest box   | its box is farther than the
//            | first                               | nearest point found (the
//            |                                     | radius shrinks as they come)
//
// The closest-point search is not a global best-first one (a heap ordered by
// box distance): that visits fewer cells, but its heap costs more than the
// cells it saves (slower on the bunny at every resolution: docs/RESULTS.md),
// and the stack needs no allocation.
//
// Ties (equal distances) go to the lowest triangle index, and a box at
// exactly the best distance is still visited (the boxes are grown a little,
// so a tied triangle's box is nearer than the tie), so the answer does not
// depend on the order of the visits.
#include "lodforge/mcoctree/mc_query.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <string>
#include <utility>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/mesh_signs.h"
#include "lodforge/metrics/ray.h"

namespace lodforge {
namespace {

// Depth-first stacks: at most 7 siblings wait per level of the tree.
constexpr std::size_t kStackSize = 8 * (std::size_t{McQuery::kMaxDepth} + 1);

// The triangles of cell c at priority `level`: the last interval with from
// <= level (as extract_mc_indices picks it). Returns {first, count} in
// model.triangles.
std::pair<std::uint32_t, std::uint32_t> cell_triangles(const McLodModel& m, std::uint32_t c,
                                                       std::uint32_t level) {
  std::uint32_t j = m.cells[c].first_interval;
  const std::uint32_t last = m.cells[c + 1].first_interval - 1;
  while (j < last && m.intervals[j + 1].from <= level) ++j;
  const std::uint32_t b = m.intervals[j].first_triangle;
  return {b, m.intervals[j + 1].first_triangle - b};
}

float box_distance_squared(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  float s = 0;
  for (int a = 0; a < 3; ++a) {
    float e = std::max({lo[a] - p[a], 0.0f, p[a] - hi[a]});
    s += e * e;
  }
  return s;
}

}  // namespace

McQuery::McQuery(const McLodModel& model, const McExtractOptions& level)
    : McQuery(model, extract_mc_mesh(model, level)) {}

McQuery::McQuery(const McLodModel& model, McExtractResult level)
    : priority_(level.priority),
      signs_(std::make_unique<const detail::SignedDistance>(std::move(level.mesh))) {
  const TriangleMesh& mesh = signs_->mesh();
  prepared_.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    prepared_.push_back(
        PreparedTriangle::of(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
  build_tree(model);
}

McQuery::McQuery(McQuery&&) noexcept = default;
McQuery& McQuery::operator=(McQuery&&) noexcept = default;
McQuery::~McQuery() = default;

const TriangleMesh& McQuery::mesh() const {
  return signs_->mesh();
}

// The tree cut at priority_, in three passes over the cells of groups
// 0..N: where each emitted cell's triangles start in mesh() (extraction
// order: emitted cells in cell order), the boxes bottom-up (a child comes
// after its parent in the cell array), and the nodes breadth first so that
// a node's children are contiguous.
void McQuery::build_tree(const McLodModel& m) {
  const TriangleMesh& mesh = signs_->mesh();
  if (m.cells.empty() || m.group.empty() || mesh.triangles.empty()) return;
  const std::uint32_t level = priority_;
  const std::uint32_t end = m.group[level + 1];
  auto expanded = [&](std::uint32_t c) { return m.cells[c].until <= level; };

  std::vector<std::uint32_t> first(end, 0);
  std::uint32_t next = 0;
  for (std::uint32_t c = 0; c < end; ++c)
    if (!expanded(c)) {
      first[c] = next;
      next += cell_triangles(m, c, level).second;
    }
  assert(next == mesh.triangles.size());

  std::vector<Box3> box(end);
  for (std::uint32_t c = end; c-- > 0;) {
    if (expanded(c)) {
      const std::uint32_t u = m.cells[c].until;
      for (std::uint32_t k = m.group[u]; k < m.group[u + 1]; ++k) box[c].add(box[k]);
      continue;
    }
    const std::uint32_t n = cell_triangles(m, c, level).second;
    for (std::uint32_t t = first[c]; t < first[c] + n; ++t)
      for (auto v : mesh.triangles[t]) box[c].add(mesh.positions[v]);
  }

  // Boxes grown by a little more than float rounding of coordinates of the
  // model's size, so that a ray along a face of a box still enters it.
  const float pad = 1e-4f * m.cell_size + 4 * std::numeric_limits<float>::min();
  auto node_of = [&](std::uint32_t c) {
    Node n{box[c].lo - Vec3{pad, pad, pad}, box[c].hi + Vec3{pad, pad, pad}, 0, 0, !expanded(c)};
    if (n.leaf) n.first = first[c], n.count = cell_triangles(m, c, level).second;
    return n;
  };
  if (box[0].empty()) return;
  std::vector<std::uint32_t> cell_of{0};
  std::vector<int> level_of{0};
  nodes_.push_back(node_of(0));
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].leaf) continue;
    if (level_of[i] >= kMaxDepth)
      throw DataError("mcoctree: the model's tree is deeper than " + std::to_string(kMaxDepth) +
                      " levels");
    const std::uint32_t u = m.cells[cell_of[i]].until;
    nodes_[i].first = static_cast<std::uint32_t>(nodes_.size());
    for (std::uint32_t k = m.group[u]; k < m.group[u + 1]; ++k)
      if (!box[k].empty()) {
        nodes_.push_back(node_of(k));
        cell_of.push_back(k);
        level_of.push_back(level_of[i] + 1);
      }
    nodes_[i].count = static_cast<std::uint32_t>(nodes_.size()) - nodes_[i].first;
  }
}

McRayHit McQuery::ray(const Vec3& origin, const Vec3& direction, float max_distance) const {
  if (!is_finite(origin)) throw DataError("mcoctree query: the ray's origin is not finite");
  const Vec3 unit = normalized(direction);
  if (!is_finite(direction) || length_squared(unit) == 0)
    throw DataError("mcoctree query: the ray's direction is zero or not finite");
  McRayHit hit;
  if (nodes_.empty()) return hit;
  const Ray r(origin, unit);
  const TriangleMesh& mesh = signs_->mesh();
  float best = max_distance;
  // At most 7 siblings wait per level while the nearest child is entered.
  struct Entry {
    std::uint32_t node;
    float t;
  };
  std::array<Entry, kStackSize> stack;
  int top = 0;
  if (float t = r.enter(nodes_[0].lo, nodes_[0].hi, best); t >= 0) stack[top++] = {0, t};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.t > best) continue;
    const Node& n = nodes_[e.node];
    if (n.leaf) {
      for (std::uint32_t t = n.first; t < n.first + n.count; ++t) {
        const auto& f = mesh.triangles[t];
        const double s = r.hit(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]);
        // Compared as floats, the distance reported: equal floats are a tie.
        const auto sf = static_cast<float>(s);
        if (s < 0 || sf > best) continue;
        if (sf < best || t < hit.triangle) best = sf, hit.triangle = t;
      }
      continue;
    }
    // Children nearest first: pushed farthest first.
    std::array<Entry, 8> kids;
    int k = 0;
    for (std::uint32_t c = n.first; c < n.first + n.count; ++c)
      if (float t = r.enter(nodes_[c].lo, nodes_[c].hi, best); t >= 0) kids[k++] = {c, t};
    for (int i = 1; i < k; ++i)  // insertion sort, farthest first: k <= 8
      for (int j = i; j > 0 && kids[j - 1].t < kids[j].t; --j) std::swap(kids[j - 1], kids[j]);
    for (int i = 0; i < k; ++i) stack[top++] = kids[i];
  }
  if (!hit.hit()) return hit;
  const auto& f = mesh.triangles[hit.triangle];
  const Vec3 &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
  hit.distance = best;
  hit.point = origin + unit * best;
  hit.normal = normalized(cross(b - a, c - a));
  return hit;
}

McClosest McQuery::closest(const Vec3& p) const {
  if (!is_finite(p)) throw DataError("mcoctree query: the point is not finite");
  McClosest out;
  if (nodes_.empty()) return out;
  ClosestPoint best;
  struct Entry {
    std::uint32_t node;
    float d2;
  };
  std::array<Entry, kStackSize> stack;
  int top = 0;
  stack[top++] = {0, box_distance_squared(p, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 > best.distance_squared) continue;
    const Node& n = nodes_[e.node];
    if (!n.leaf) {
      std::array<Entry, 8> kids;
      int k = 0;
      for (std::uint32_t c = n.first; c < n.first + n.count; ++c)
        if (float d = box_distance_squared(p, nodes_[c].lo, nodes_[c].hi);
            d <= best.distance_squared)
          kids[k++] = {c, d};
      for (int i = 1; i < k; ++i)
        for (int j = i; j > 0 && kids[j - 1].d2 < kids[j].d2; --j) std::swap(kids[j - 1], kids[j]);
      for (int i = 0; i < k; ++i) stack[top++] = kids[i];
      continue;
    }
    for (std::uint32_t t = n.first; t < n.first + n.count; ++t) {
      TrianglePoint tp = closest_point_on_triangle(p, prepared_[t]);
      if (tp.distance_squared < best.distance_squared ||
          (tp.distance_squared == best.distance_squared && t < best.triangle))
        best = {tp.point, t, tp.barycentric, tp.distance_squared};
    }
  }
  const auto sample = signs_->sample(p, best);
  out.point = best.point;
  out.triangle = best.triangle;
  out.distance = sample.distance;
  out.open = sample.open;
  return out;
}

}  // namespace lodforge
