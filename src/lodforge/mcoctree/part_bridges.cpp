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
#include <queue>

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
  std::uint32_t count = 0;              // regions
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
    const std::uint32_t id = r.count++;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    lat.state[seed] |= kSeen;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      if (head >= (1u << 20) && 2 * head >= queue.size()) {
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
  }
  for (auto& s : lat.state) s &= static_cast<std::uint8_t>(~kSeen);
  return r;
}

// Regions whose exact points are nearest one input part are one group.
UnionFind group_by_part(const Lattice& lat, const Regions& r, const SignedDistance& sd) {
  const std::vector<std::uint32_t> part = triangle_parts(sd.mesh());
  std::vector<std::uint32_t> first(
      part.empty() ? 0 : *std::max_element(part.begin(), part.end()) + 1, kNoRegion);
  UnionFind groups(r.count);
  for (std::size_t e = 0; e < lat.distance.size(); ++e) {
    const std::uint32_t region = r.of_exact[e];
    if (region == kNoRegion) continue;
    std::uint32_t& f = first[part[lat.distance[e].triangle]];
    if (f == kNoRegion) f = region;
    groups.unite(f, region);
  }
  return groups;
}

constexpr std::size_t kStart = std::numeric_limits<std::size_t>::max();

// Makes the outside points on the way from exact point e back to where its
// search started inside, their distances negated.
void raise_path(Lattice& lat, const std::vector<std::size_t>& from, std::size_t e,
                PartBridges& out) {
  for (; e != kStart; e = from[e]) {
    std::uint8_t& st = lat.state[lat.distance[e].idx];
    if (st & kInside) continue;
    st |= kInside;
    lat.distance[e].distance = -lat.distance[e].distance;
    ++out.points;
  }
}

// One search from every region at once through the exact points, settled in
// order of the largest |distance| on the way there (Kruskal's order for a
// minimum bottleneck forest): a point belongs to the region whose search
// reached it first, and where a settled point of one region meets a settled
// point of another, unjoined one of its group, the two ways back are the
// bridge. A region's search does not pass another's points (a piece of one
// part goes round another part). Stops when every group is one piece.
void bridge_regions(Lattice& lat, const Regions& r, UnionFind& groups, PartBridges& out) {
  std::vector<std::size_t> pieces(r.count, 0);
  for (std::uint32_t g = 0; g < r.count; ++g) ++pieces[groups.find(g)];
  std::size_t split = std::count_if(pieces.begin(), pieces.end(), [](auto n) { return n > 1; });
  std::vector<std::uint32_t> owner = r.of_exact;
  std::vector<std::size_t> from(owner.size(), kStart);
  std::vector<std::uint8_t> settled(owner.size(), 0);
  using Item = std::pair<float, std::size_t>;  // largest |distance| on the way, exact point
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  for (std::size_t e = 0; e < owner.size(); ++e)
    if (owner[e] != kNoRegion) open.push({0.0f, e});
  UnionFind joined(r.count);
  while (!open.empty() && split > 0) {
    // Named copies, not a structured binding: the lambda below captures them.
    const float key = open.top().first;
    const std::size_t e = open.top().second;
    open.pop();
    if (settled[e]) continue;
    settled[e] = 1;
    const std::uint32_t mine = owner[e];
    lattice_neighbours(lat, lat.distance[e].idx, [&](std::int64_t q) {
      if (!(lat.state[q] & kExact) || lat.on_border(q)) return;
      const std::size_t eq = exact_index(lat, q);
      const std::uint32_t theirs = owner[eq];
      if (theirs == kNoRegion) {
        owner[eq] = mine, from[eq] = e;
        open.push({std::max(key, std::abs(lat.distance[eq].distance)), eq});
      } else if (settled[eq] && groups.find(theirs) == groups.find(mine) &&
                 joined.find(theirs) != joined.find(mine)) {
        raise_path(lat, from, e, out);
        raise_path(lat, from, eq, out);
        joined.unite(theirs, mine);
        ++out.bridges;
        if (--pieces[groups.find(mine)] == 1) --split;
      }
    });
  }
}

}  // namespace

PartBridges bridge_mesh_parts(Lattice& lat, const SignedDistance& sd) {
  PartBridges out;
  Regions r = inside_regions(lat);
  out.regions = r.count;
  if (out.regions < 2) return out;
  UnionFind groups = group_by_part(lat, r, sd);
  bridge_regions(lat, r, groups, out);
  return out;
}

}  // namespace lodforge::detail
