// Bridges across the thin places of a closed mesh's parts in the sign
// lattice.
//
// A sign lattice samples a part thinner than a cell only where lattice
// points happen to fall inside it, so its marching cubes surface falls apart
// into pieces (the cow's legs, horns and tail at the default resolution).
// The exact signed distances of the band say which input part each inside
// region lies in; regions of one part are joined along the path of least
// "largest distance to the surface" (a minimax, or bottleneck, shortest path:
// Dijkstra's search with the maximum in place of the sum), which follows the
// thin part's core. The surface then keeps the part in one piece, about a
// cell thick where the input is thinner.
#include "lodforge/mcoctree/part_bridges.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "lodforge/core/union_find.h"
#include "lodforge/mesh/adjacency.h"

namespace lodforge::detail {
namespace {

constexpr std::uint32_t kNoRegion = std::numeric_limits<std::uint32_t>::max();
// A state bit the sign sources leave free: visited by the labelling.
constexpr std::uint8_t kSeen = 16;

// Position of exact point idx in lat.distance.
std::size_t exact_index(const Lattice& lat, std::int64_t idx) {
  return static_cast<std::size_t>(lat.find_distance(idx) - lat.distance.data());
}

struct Regions {
  std::vector<std::uint32_t> of_exact;  // per lat.distance entry: its inside region
  std::vector<std::size_t> size;        // points per region
};

// The 6-connected inside regions, by breadth-first search from each unseen
// inside point in index order (the queue keeps only its frontier: a region
// may be most of the lattice).
Regions inside_regions(Lattice& lat) {
  assert(lat.state.size() <= std::numeric_limits<std::uint32_t>::max());
  Regions r;
  r.of_exact.assign(lat.distance.size(), kNoRegion);
  std::vector<std::uint32_t> queue;
  const auto count = static_cast<std::int64_t>(lat.state.size());
  for (std::int64_t seed = 0; seed < count; ++seed) {
    if ((lat.state[seed] & (kInside | kSeen)) != kInside) continue;
    const auto id = static_cast<std::uint32_t>(r.size.size());
    queue.assign(1, static_cast<std::uint32_t>(seed));
    lat.state[seed] |= kSeen;
    std::size_t points = 0;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      if (head >= (1u << 20) && 2 * head >= queue.size()) {
        points += head;
        queue.erase(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
      const std::int64_t idx = queue[head];
      if (lat.state[idx] & kExact) r.of_exact[exact_index(lat, idx)] = id;
      lattice_neighbours(lat, idx, [&](std::int64_t q) {
        if ((lat.state[q] & (kInside | kSeen)) != kInside) return;
        lat.state[q] |= kSeen;
        queue.push_back(static_cast<std::uint32_t>(q));
      });
    }
    r.size.push_back(points + queue.size());
  }
  for (auto& s : lat.state) s &= static_cast<std::uint8_t>(~kSeen);
  return r;
}

// Regions whose exact points are nearest one input part are one group.
UnionFind group_by_part(const Lattice& lat, const Regions& r, const SignedDistance& sd) {
  const std::vector<std::uint32_t> part = triangle_parts(sd.mesh());
  std::vector<std::uint32_t> first(
      part.empty() ? 0 : *std::max_element(part.begin(), part.end()) + 1, kNoRegion);
  UnionFind groups(r.size.size());
  for (std::size_t e = 0; e < lat.distance.size(); ++e) {
    const std::uint32_t region = r.of_exact[e];
    if (region == kNoRegion) continue;
    std::uint32_t& f = first[part[lat.distance[e].triangle]];
    if (f == kNoRegion) f = region;
    groups.unite(f, region);
  }
  return groups;
}

// Joins region `from` to another region of its group, not yet joined to it,
// by the minimax path through exact points; false when there is none.
bool bridge(Lattice& lat, Regions& r, UnionFind& groups, UnionFind& joined, std::uint32_t from,
            PartBridges& out) {
  using Item = std::pair<float, std::size_t>;  // largest |distance| so far, exact point
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  std::unordered_map<std::size_t, std::size_t> parent;
  constexpr std::size_t kStart = std::numeric_limits<std::size_t>::max();
  for (std::size_t e = 0; e < r.of_exact.size(); ++e)
    if (r.of_exact[e] != kNoRegion && joined.find(r.of_exact[e]) == joined.find(from))
      open.push({0.0f, e}), parent.emplace(e, kStart);
  const std::uint32_t group = groups.find(from);
  while (!open.empty()) {
    const auto [key, e] = open.top();
    open.pop();
    const std::uint32_t region = r.of_exact[e];
    if (region != kNoRegion && joined.find(region) != joined.find(from)) {
      if (groups.find(region) != group) continue;  // another part's: not a way through
      for (std::size_t p = parent[e]; p != kStart; p = parent[p]) {
        if (lat.state[lat.distance[p].idx] & kInside) continue;
        lat.state[lat.distance[p].idx] |= kInside;
        lat.distance[p].distance = -lat.distance[p].distance;
        ++out.points;
      }
      joined.unite(region, from);
      return true;
    }
    lattice_neighbours(lat, lat.distance[e].idx, [&](std::int64_t q) {
      if (!(lat.state[q] & kExact) || lat.on_border(q)) return;
      const std::size_t eq = exact_index(lat, q);
      if (!parent.emplace(eq, e).second) return;
      const bool in = r.of_exact[eq] != kNoRegion;
      open.push({std::max(key, in ? 0.0f : std::abs(lat.distance[eq].distance)), eq});
    });
  }
  return false;
}

}  // namespace

PartBridges bridge_mesh_parts(Lattice& lat, const SignedDistance& sd) {
  PartBridges out;
  Regions r = inside_regions(lat);
  out.regions = r.size.size();
  if (out.regions < 2) return out;
  UnionFind groups = group_by_part(lat, r, sd);
  // Each region of a group but its largest bridges to another (the smallest
  // first: a piece to the body rather than the body to a piece).
  std::vector<std::uint32_t> order(r.size.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return r.size[a] < r.size[b]; });
  std::vector<std::size_t> pieces(r.size.size(), 0);
  for (std::uint32_t g = 0; g < r.size.size(); ++g) ++pieces[groups.find(g)];
  UnionFind joined(r.size.size());
  for (std::uint32_t from : order) {
    std::size_t& left = pieces[groups.find(from)];
    if (left > 1 && bridge(lat, r, groups, joined, from, out)) --left, ++out.bridges;
  }
  return out;
}

}  // namespace lodforge::detail
