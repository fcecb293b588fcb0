// The priority numbering of the marching-cube octree (Kim, "Level-of-detail
// mesh modeling using the marching cube octree", ch. 6): every node gets a
// priority by repeatedly expanding the expandable node of largest LOD metric
// (area of the children's triangulation minus the node's own), and the
// accumulation table maps priorities to triangle counts. Choices where the
// thesis is vague:
//
//   * metric: the magnitude of the thesis's area difference, and a node
//     inherits a descendant's when that exceeds kHiddenDetail of its own
//     area (see area_metric).
//   * expandability: a node is expandable when no cell of the current cut that
//     touches it (26-neighbourhood: face, edge or corner) is coarser than it,
//     so that after expanding, neighbours differ by at most one level. A node
//     popped from the priority queue while a coarser neighbour blocks it waits
//     on that neighbour and re-enters the queue when it is expanded: every
//     pop either expands or parks a node, so the numbering is O(n log n).
//   * the accumulation table is exact: each expansion re-counts the node, its
//     children and the same-level cut cells around it whose faces or edges it
//     splits, with the same triangulation the extraction uses.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <queue>

#include "lodforge/mcoctree/cell_mesh.h"
#include "lodforge/mcoctree/node_error.h"
#include "lodforge/mcoctree/octree_builder.h"

namespace lodforge::detail {
namespace {

// A descendant's metric above this fraction of a node's own area raises the
// node's (see area_metric).
constexpr float kHiddenDetail = 0.2f;

// Slots (dx + 1) + 3 (dy + 1) + 9 (dz + 1) of the neighbour table: across
// face f, and around edge e = 4a + b (offsets on a + 1 and a + 2 by b's
// bits: one, the other, both).
constexpr std::array<std::uint8_t, 6> kFaceSlot = [] {
  std::array<std::uint8_t, 6> slot{};
  for (int f = 0; f < 6; ++f) {
    int d[3] = {0, 0, 0};
    d[f / 2] = f % 2 ? 1 : -1;
    slot[f] = static_cast<std::uint8_t>((d[0] + 1) + 3 * (d[1] + 1) + 9 * (d[2] + 1));
  }
  return slot;
}();
constexpr std::array<std::array<std::uint8_t, 3>, 12> kEdgeSlots = [] {
  std::array<std::array<std::uint8_t, 3>, 12> slot{};
  for (int e = 0; e < 12; ++e) {
    int a = e / 4, b = e % 4;
    int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    int s1 = b & 1 ? 1 : -1, s2 = b >> 1 ? 1 : -1;
    for (int k = 1; k < 4; ++k) {
      int d[3] = {0, 0, 0};
      if (k & 1) d[a1] = s1;
      if (k & 2) d[a2] = s2;
      slot[e][k - 1] = static_cast<std::uint8_t>((d[0] + 1) + 3 * (d[1] + 1) + 9 * (d[2] + 1));
    }
  }
  return slot;
}();

}  // namespace

// The same-level neighbours of every internal node (kNone where there is
// none): near(i, dx, dy, dz) reads them.
void OctreeBuilder::make_near() {
  internal_ = static_cast<std::uint32_t>(level_offset_[t_.depth]);
  near_.resize(27 * static_cast<std::size_t>(internal_));
  tbb::parallel_for(std::uint32_t{0}, internal_, [&](std::uint32_t i) {
    const McNode& n = t_.nodes[i];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          near_[27 * static_cast<std::size_t>(i) + (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1)] =
              find(n.level, std::int64_t{n.coords[0]} + dx, std::int64_t{n.coords[1]} + dy,
                   std::int64_t{n.coords[2]} + dz);
  });
}

// The edges node i has halved and the faces it has split as a cell of the
// current cut: where a same-level neighbour is expanded.

std::pair<std::uint16_t, std::uint8_t> OctreeBuilder::context(std::uint32_t i) const {
  std::uint16_t halved = 0;
  std::uint8_t split = 0;
  if (i >= internal_) return {halved, split};
  const std::uint32_t* row = &near_[27 * static_cast<std::size_t>(i)];
  auto expanded = [&](std::uint8_t slot) {
    const std::uint32_t m = row[slot];
    return m != McNode::kNone && expanded_[m];
  };
  for (int f = 0; f < 6; ++f)
    if (expanded(kFaceSlot[f])) split |= static_cast<std::uint8_t>(1u << f);
  for (int e = 0; e < 12; ++e)
    if (expanded(kEdgeSlots[e][0]) || expanded(kEdgeSlots[e][1]) || expanded(kEdgeSlots[e][2]))
      halved |= static_cast<std::uint16_t>(1u << e);
  return {halved, split};
}

// Triangles of node i as a cell of the current cut. A split cell is
// triangulated in full to be counted; configurations recur (a smooth
// surface meets few sign patterns), so counts are remembered by
// (signs, halved edges, split faces).
int OctreeBuilder::count_now(std::uint32_t i) {
  auto [halved, split] = context(i);
  const McNode& n = t_.nodes[i];
  if (!halved && !split) return node_triangle_count(n, 0, 0);
  // A halved edge or split face without a sign change on it changes
  // nothing (polygonize_cell contours only crossings): left out of the key,
  // so that more configurations share a count.
  static const auto masks = [] {
    std::array<std::uint32_t, 18> m{};  // 12 edges' 3 points, 6 faces' 9
    for (int e = 0; e < 12; ++e) {
      auto [lo, hi] = edge_corners(e);
      int plo = corner_point(lo), phi = corner_point(hi);
      m[e] = 1u << plo | 1u << phi | 1u << (plo + phi) / 2;
    }
    for (int p = 0; p < 27; ++p) {
      const int c[3] = {p % 3, (p / 3) % 3, p / 9};
      for (int f = 0; f < 6; ++f)
        if (c[f / 2] == 2 * (f % 2)) m[12 + f] |= 1u << p;
    }
    return m;
  }();
  static const std::uint32_t corners = [] {
    std::uint32_t m = 0;
    for (int c = 0; c < 8; ++c) m |= 1u << corner_point(c);
    return m;
  }();
  auto uniform = [&](std::uint32_t mask) {
    const std::uint32_t in = n.signs27 & mask;
    return in == 0 || in == mask;
  };
  // Nor do the signs of points no face contour reads (the centre; an edge's
  // midpoint unless it is halved or on a split face; a face's centre
  // unless it is split).
  std::uint16_t h = 0;
  std::uint8_t sp = 0;
  std::uint32_t read = corners;
  for (std::uint32_t bits = halved; bits; bits &= bits - 1) {
    const int e = __builtin_ctz(bits);
    if (!uniform(masks[e])) h |= static_cast<std::uint16_t>(1u << e), read |= masks[e];
  }
  for (std::uint32_t bits = split; bits; bits &= bits - 1) {
    const int f = __builtin_ctz(bits);
    if (!uniform(masks[12 + f])) sp |= static_cast<std::uint8_t>(1u << f), read |= masks[12 + f];
  }
  const std::uint64_t key =
      std::uint64_t{n.signs27 & read} | std::uint64_t{h} << 27 | std::uint64_t{sp} << 39;
  if (auto c = counts_.find(key); c != McNode::kNone) return static_cast<int>(c);
  int c = node_triangle_count(n, halved, split);
  if (counts_.size() < counts_.capacity() / 2) counts_.insert(key, static_cast<std::uint32_t>(c));
  return c;
}

// The area of node n's own triangulation.
double OctreeBuilder::own_area(const McNode& n) const {
  double area = 0;
  triangulate_node(
      t_, n, 0, 0,
      [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        area += 0.5 *
                length(cross(t_.positions[b] - t_.positions[a], t_.positions[c] - t_.positions[a]));
      },
      [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
  return area;
}

// The coarsest unexpanded cut cell touching n that is coarser than n, or kNone.
// The first level up is read from the parent's neighbour table (the cell
// one level coarser around n is the parent or one of its neighbours).
std::uint32_t OctreeBuilder::blocker(std::uint32_t i) const {
  const McNode& n = t_.nodes[i];
  const std::uint32_t parent = parent_[i];
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (!dx && !dy && !dz) continue;
        std::int64_t q[3] = {std::int64_t{n.coords[0]} + dx, std::int64_t{n.coords[1]} + dy,
                             std::int64_t{n.coords[2]} + dz};
        std::int64_t size = std::int64_t{1} << n.level;
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= size || q[1] >= size || q[2] >= size)
          continue;
        if (parent != McNode::kNone) {
          const McNode& p = t_.nodes[parent];
          std::uint32_t a = near(parent, static_cast<int>((q[0] >> 1) - p.coords[0]),
                                 static_cast<int>((q[1] >> 1) - p.coords[1]),
                                 static_cast<int>((q[2] >> 1) - p.coords[2]));
          if (a != McNode::kNone) {
            if (!expanded_[a]) return a;
            continue;
          }
        }
        for (int l = n.level - 2; l >= 0; --l) {
          int sh = n.level - l;
          std::uint32_t a = find(l, q[0] >> sh, q[1] >> sh, q[2] >> sh);
          if (a == McNode::kNone) continue;
          if (!expanded_[a]) return a;
          break;
        }
      }
  return McNode::kNone;
}

// The thesis's metric: |area of the children's triangulation -
// area of the node's own|, raised to a descendant's where that hides detail.
std::vector<float> OctreeBuilder::area_metric() const {
  const auto count = static_cast<std::uint32_t>(t_.nodes.size());
  std::vector<float> metric(count, 0);
  std::vector<double> area(count);
  tbb::parallel_for(std::uint32_t{0}, count,
                    [&](std::uint32_t i) { area[i] = own_area(t_.nodes[i]); });
  for (std::size_t i = 0; i < count; ++i) {
    const McNode& n = t_.nodes[i];
    if (n.leaf()) continue;
    double children = 0;
    for (int o = 0; o < 8; ++o)
      if (auto c = n.child(o); c != McNode::kNone) children += area[c];
    // The thesis's metric is the area the expansion adds; a node over a
    // hole of an open input (its children are partly holes) removes area
    // by expanding, which is as much a change of shape: the magnitude.
    metric[i] = static_cast<float>(std::abs(children - area[i]));
  }
  // A node is expanded no later than a descendant, which cannot be
  // expanded before it, whose metric exceeds kHiddenDetail x the node's
  // own area: detail the node hides, such as an ear tip its corners miss
  // (no crossing on its edges: it adds no area while its cells stay
  // coarser than it) or a hole's real surface next to the rim; without
  // this its ancestors wait at the end of the queue and whole features
  // are missing at 20 %. Smooth regions (children's metrics a few % of
  // the parent's area) keep the thesis's order. Inheriting always (a
  // fraction of 0) favours the coarsest levels over the finer ones and
  // coarsens the budget steps of small models.
  for (std::size_t i = count; i-- > 0;) {
    const McNode& n = t_.nodes[i];
    for (int o = 0; o < 8; ++o)
      if (auto c = n.child(o);
          c != McNode::kNone && !t_.nodes[c].leaf() && metric[c] > kHiddenDetail * area[i])
        metric[i] = std::max(metric[i], metric[c]);
  }
  return metric;
}

// McPriorityMetric::kDistance: how far the finest surface under a node lies
// from the node's own triangles (summed over the surface points, see
// node_error.h), raised to the largest of any descendant's so that a node
// is never expanded after one of its descendants would be.
std::vector<float> OctreeBuilder::distance_metric() const {
  const std::vector<double> distance = node_distance_sums(t_);
  std::vector<float> metric(distance.begin(), distance.end());
  for (std::size_t i = metric.size(); i-- > 0;) {
    const McNode& n = t_.nodes[i];
    for (int o = 0; o < 8; ++o)
      if (auto c = n.child(o); c != McNode::kNone && !t_.nodes[c].leaf())
        metric[i] = std::max(metric[i], metric[c]);
  }
  return metric;
}

void OctreeBuilder::number(McPriorityMetric which) {
  const auto count = static_cast<std::uint32_t>(t_.nodes.size());
  make_near();
  parent_.assign(count, McNode::kNone);
  for (std::uint32_t i = 0; i < internal_; ++i)
    for (int o = 0; o < 8; ++o)
      if (auto c = t_.nodes[i].child(o); c != McNode::kNone) parent_[c] = i;
  counts_.reserve(count);
  expanded_.assign(count, 0);
  std::vector<float> metric = which == McPriorityMetric::kArea ? area_metric() : distance_metric();
  expand_all(metric);
  split_priorities();
}

// Expands the expandable node of largest metric (ties: the lowest index)
// until none is left, numbering the expansions and counting the triangles
// of the cut after each. A node a coarser neighbour blocks waits on it.
void OctreeBuilder::expand_all(std::vector<float>& metric) {
  const auto count = static_cast<std::uint32_t>(t_.nodes.size());
  ProgressCounter expansions(progress_, "priorities", internal_);
  std::vector<int> tri(count, 0);
  std::vector<std::vector<std::uint32_t>> waiting(count);
  using Entry = std::pair<float, std::uint32_t>;
  auto later = [](const Entry& a, const Entry& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  };
  std::priority_queue<Entry, std::vector<Entry>, decltype(later)> queue(later);
  tri[0] = count_now(0);
  t_.accumulated.assign(1, static_cast<std::uint64_t>(tri[0]));
  if (!t_.nodes[0].leaf()) queue.push({metric[0], 0});
  std::vector<std::uint32_t> around;
  while (!queue.empty()) {
    auto [m, i] = queue.top();
    queue.pop();
    if (expanded_[i]) continue;  // a second entry (below)
    McNode& n = t_.nodes[i];
    if (auto b = blocker(i); b != McNode::kNone) {
      waiting[b].push_back(i);
      ++stats_.expansion_waits;
      // The coarser neighbour inherits the waiting node's metric (it is
      // expanded as early as the detail it holds back needs): without this,
      // detail next to a flat coarse cell waits for the flat cell's own turn
      // near the end.
      if (metric[b] < m) {
        metric[b] = m;
        queue.push({m, b});
      }
      continue;
    }
    // Same-level cut cells around n whose faces or edges n's expansion splits.
    around.clear();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          // Only face and edge neighbours' splits change (a corner
          // neighbour shares no edge with n).
          int moved = (dx != 0) + (dy != 0) + (dz != 0);
          if (moved == 0 || moved == 3) continue;
          std::uint32_t a = near(i, dx, dy, dz);
          if (a != McNode::kNone && !expanded_[a]) around.push_back(a);
        }
    std::int64_t delta = -tri[i];
    for (auto a : around) delta -= tri[a];
    expanded_[i] = 1;
    expansions.add(1);
    n.priority = static_cast<std::uint32_t>(t_.lod.size() + 1);
    t_.lod.push_back(i);
    for (auto a : around) delta += tri[a] = count_now(a);
    for (int o = 0; o < 8; ++o) {
      auto c = n.child(o);
      if (c == McNode::kNone) continue;
      delta += tri[c] = count_now(c);
      if (!t_.nodes[c].leaf()) queue.push({metric[c], c});
    }
    t_.accumulated.push_back(
        static_cast<std::uint64_t>(static_cast<std::int64_t>(t_.accumulated.back()) + delta));
    for (auto w : waiting[i]) queue.push({metric[w], w});
    waiting[i].clear();
    waiting[i].shrink_to_fit();
  }
}

// Split priorities for extraction: per face and edge of each node, the
// lowest priority of the same-level nodes sharing it (kNone: none; a leaf's
// are all kNone, as leaves are never expanded).
void OctreeBuilder::split_priorities() {
  const auto count = static_cast<std::uint32_t>(t_.nodes.size());
  tbb::parallel_for(std::uint32_t{0}, count, [&](std::uint32_t i) {
    McNode& n = t_.nodes[i];
    const std::uint32_t* row = i < internal_ ? &near_[27 * static_cast<std::size_t>(i)] : nullptr;
    auto lowest = [&](std::uint32_t& split, std::uint8_t slot) {
      const std::uint32_t m = row ? row[slot] : McNode::kNone;
      if (m != McNode::kNone) split = std::min(split, t_.nodes[m].priority);
    };
    for (int f = 0; f < 6; ++f) {
      n.face_split[f] = McNode::kNone;
      lowest(n.face_split[f], kFaceSlot[f]);
    }
    for (int e = 0; e < 12; ++e) {
      n.edge_split[e] = McNode::kNone;
      for (int k = 0; k < 3; ++k) lowest(n.edge_split[e], kEdgeSlots[e][k]);
    }
  });
}

}  // namespace lodforge::detail
