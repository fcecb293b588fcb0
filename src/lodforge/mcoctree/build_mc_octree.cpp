// The marching-cube octree of a mesh.
//
// Paper: S.-H. Kim, "Level-of-detail mesh modeling using the marching cube
// octree" (thesis; chapters 4-6): leaves are marching cubes (corner signs and
// edge ratios from signed distances), parents are made bottom-up by the
// four-case corner rule with re-scaled ratios, every node gets a priority by
// repeatedly expanding the expandable node of largest LOD metric (area of the
// children's triangulation minus the node's own), and the accumulation table
// maps priorities to triangle counts. Choices where the thesis is vague:
//
//   * signs: the thesis uses the nearest range point and its normal; for a
//     mesh we use the exact closest surface point and the angle-weighted
//     pseudo-normal there, which is correct for any closed mesh (a face
//     normal alone is wrong near sharp edges and vertices). Only the lattice
//     points within a cell of the surface are measured (by scanning each
//     triangle over the lattice near it); the rest, and the points nearest
//     an open rim, are flood-filled. An open mesh's holes are left open
//     (McHoles::kOpen): nodes whose surface points the input is not near
//     get no triangles.
//   * metric: the magnitude of the thesis's area difference, and a node
//     inherits a descendant's when that exceeds a fifth of its own area
//     (see number()).
//   * parents: with a sign at every lattice point, case 1 of the corner rule
//     (the corresponding child corner) applies whenever that child exists; a
//     pruned (empty) child has one sign at all its corners, so cases 2-4 read
//     the same sign from its neighbours. Hence the sign of a lattice point is
//     the same at every level, which the crack-free triangulation relies on.
//   * ratios: the parent's point on an edge is the child's point on the half
//     whose ends differ in sign (Fig. 5.2: a/2(a+b) and (2a+b)/2(a+b)); we
//     store the point once and let both nodes refer to it.
//   * expandability: a node is expandable when no cell of the current cut that
//     touches it (26-neighbourhood: face, edge or corner) is coarser than it,
//     so that after expanding, neighbours differ by at most one level. A node
//     popped from the priority queue while a coarser neighbour blocks it waits
//     on that neighbour and re-enters the queue when it is expanded: every
//     pop either expands or parks a node, so the numbering is O(n log n).
//   * the accumulation table is exact: each expansion re-counts the node, its
//     children and the same-level cut cells around it whose faces or edges it
//     splits, with the same triangulation the extraction uses.
#include "lodforge/mcoctree/build_mc_octree.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/core/morton.h"
#include "lodforge/mcoctree/cell_mesh.h"
#include "lodforge/mcoctree/node_error.h"
#include "lodforge/mcoctree/range_scan.h"
#include "lodforge/mcoctree/sign_components.h"
#include "lodforge/mesh/adjacency.h"
#include "lodforge/mesh/coordinate_range.h"
#include "lodforge/mesh/weld.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/triangle_bvh.h"

namespace lodforge {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// kMeasured: a point nearest an open rim, measured without a sign.
constexpr std::uint8_t kInside = 1, kExact = 2, kAssigned = 4, kMeasured = 8;
// A surface point more than kRimGap cells beyond an open rim is invented.
constexpr float kRimGap = 0.25f;
constexpr float kHiddenDetail = 0.2f;  // see Builder::number
// Range scans: an inside region smaller than this many lattice points, or
// than this fraction of the largest, is a bubble (see clean_scan_signs).
constexpr std::size_t kMinScanPart = 64;
constexpr double kMinScanPartFraction = 0.01;

// Exact closest points for the few queries the triangle scan leaves (an
// open mesh's repairs, hole tests and edge points by a rim: a few thousand on
// the bunny, many cells away from the surface): a bounding volume hierarchy
// built the cheap way (Lauterbach et al. 2009, "LBVH"): triangles in Morton
// order of their centroids, each node split where the highest bit of the
// Morton code in which its triangles differ changes, so that a node's
// triangles lie in one octree cell of that code and its children in two
// halves of it; leaves of at most kLeaf triangles. Its queries visit a few
// more nodes than a surface-area-heuristic tree's, but it is built in a small
// fraction of the time (that build took ~20 % of the bunny's). (A complete
// binary tree over the Morton order, cut at fixed counts rather than at cell
// boundaries, had boxes spanning distant parts of the mesh: its queries
// visited about twice the nodes.) Among triangles at the same distance the lowest
// index wins (the answer depends neither on the tree nor on the hint).
class TriangleTree {
 public:
  explicit TriangleTree(const TriangleMesh& m) : m_(m) {
    const auto& P = m.positions;
    const std::size_t n = m.triangles.size();
    const Box3 box = m.bounds();
    const Vec3 size = box.size();
    std::vector<std::uint64_t> keyed(n);
    for (std::size_t t = 0; t < n; ++t) {
      const auto& f = m.triangles[t];
      const Vec3 c = (P[f[0]] + P[f[1]] + P[f[2]]) * (1.0f / 3);
      std::uint32_t q[3];
      for (int a = 0; a < 3; ++a) {
        float u = size[a] > 0 ? (c[a] - box.lo[a]) / size[a] : 0.0f;
        q[a] = static_cast<std::uint32_t>(std::clamp(u * 1023.0f, 0.0f, 1023.0f));
      }
      keyed[t] = morton_code(q[0], q[1], q[2]) << 32 | t;
    }
    std::sort(keyed.begin(), keyed.end());
    order_.resize(n);
    tri_lo_.resize(n);
    tri_hi_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      order_[i] = static_cast<std::uint32_t>(keyed[i]);
      const auto& f = m.triangles[order_[i]];
      tri_lo_[i] = min(P[f[0]], min(P[f[1]], P[f[2]]));
      tri_hi_[i] = max(P[f[0]], max(P[f[1]], P[f[2]]));
    }
    nodes_.reserve(2 * (n / kLeaf + 1));
    nodes_.emplace_back();
    build(0, 0, static_cast<std::uint32_t>(n), keyed);
  }

  ClosestPoint closest_point(const Vec3& p, std::uint32_t hint = ClosestPoint::kNone) const {
    ClosestPoint best;
    auto test = [&](std::uint32_t t) {
      const auto& f = m_.triangles[t];
      TrianglePoint tp =
          closest_point_on_triangle(p, m_.positions[f[0]], m_.positions[f[1]], m_.positions[f[2]]);
      if (tp.distance_squared < best.distance_squared ||
          (tp.distance_squared == best.distance_squared && t < best.triangle))
        best = {tp.point, t, tp.barycentric, tp.distance_squared};
    };
    if (hint < m_.triangles.size()) test(hint);
    auto distance2 = [&](const Vec3& lo, const Vec3& hi) {
      float d2 = 0;
      for (int a = 0; a < 3; ++a) {
        const float d = std::max({0.0f, lo[a] - p[a], p[a] - hi[a]});
        d2 += d * d;
      }
      return d2;
    };
    auto box_d2 = [&](std::uint32_t i) { return distance2(nodes_[i].lo, nodes_[i].hi); };
    struct Entry {
      std::uint32_t node;
      float d2;
    };
    Entry stack[96];  // the depth is at most 30 Morton bits + log2(n) equal-code halvings
    int top = 0;
    stack[top++] = {0, box_d2(0)};
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.d2 > best.distance_squared) continue;
      const Node& node = nodes_[e.node];
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
          if (distance2(tri_lo_[i], tri_hi_[i]) <= best.distance_squared) test(order_[i]);
        continue;
      }
      Entry a{node.first, box_d2(node.first)}, b{node.first + 1, box_d2(node.first + 1)};
      if (b.d2 < a.d2) std::swap(a, b);
      if (b.d2 <= best.distance_squared) stack[top++] = b;
      if (a.d2 <= best.distance_squared) stack[top++] = a;
    }
    return best;
  }

 private:
  static constexpr std::uint32_t kLeaf = 8;
  // A leaf: its triangles order_[first, first + count). An inner node
  // (count 0): its children nodes_[first] and nodes_[first + 1].
  struct Node {
    Vec3 lo, hi;
    std::uint32_t first = 0, count = 0;
  };
  // Node i over the triangles [b, e) of the Morton order.
  void build(std::uint32_t i, std::uint32_t b, std::uint32_t e,
             const std::vector<std::uint64_t>& keyed) {
    if (e - b <= kLeaf) {
      Vec3 lo = tri_lo_[b], hi = tri_hi_[b];
      for (std::uint32_t k = b + 1; k < e; ++k) lo = min(lo, tri_lo_[k]), hi = max(hi, tri_hi_[k]);
      nodes_[i] = {lo, hi, b, e - b};
      return;
    }
    const std::uint64_t first = keyed[b] >> 32, last = keyed[e - 1] >> 32;
    std::uint32_t split = b + (e - b) / 2;  // all codes equal: halve
    if (first != last) {
      const std::uint64_t bit = std::uint64_t{1} << (63 - __builtin_clzll(first ^ last));
      const std::uint64_t prefix = (last & ~(bit - 1)) << 32;  // the first key of the upper half
      split = static_cast<std::uint32_t>(
          std::lower_bound(keyed.begin() + b, keyed.begin() + e, prefix) - keyed.begin());
    }
    const auto children = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    build(children, b, split, keyed);
    build(children + 1, split, e, keyed);
    nodes_[i] = {min(nodes_[children].lo, nodes_[children + 1].lo),
                 max(nodes_[children].hi, nodes_[children + 1].hi), children, 0};
  }

  const TriangleMesh& m_;
  std::vector<std::uint32_t> order_;   // triangles in Morton order
  std::vector<Node> nodes_;            // [0]: the root
  std::vector<Vec3> tri_lo_, tri_hi_;  // per triangle, in Morton order: its box
};

// Signed distance to a mesh: exact closest point, side by pseudo-normal.
class SignedDistance {
 public:
  explicit SignedDistance(TriangleMesh mesh) : mesh_(std::move(mesh)) {
    const auto& P = mesh_.positions;
    face_normal_.resize(mesh_.triangles.size());
    std::vector<Vec3> vertex_normal(P.size());
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      const auto& f = mesh_.triangles[t];
      Vec3 n = normalized(cross(P[f[1]] - P[f[0]], P[f[2]] - P[f[0]]));
      face_normal_[t] = n;
      for (int k = 0; k < 3; ++k) {
        Vec3 a = normalized(P[f[(k + 1) % 3]] - P[f[k]]),
             b = normalized(P[f[(k + 2) % 3]] - P[f[k]]);
        float angle = std::acos(std::clamp(dot(a, b), -1.0f, 1.0f));
        vertex_normal[f[k]] += n * angle;
      }
    }
    adjacency_ = build_adjacency(mesh_);
    edge_normal_.assign(adjacency_.edges.size(), Vec3{});
    for (std::size_t e = 0; e < adjacency_.edges.size(); ++e)
      for (auto t : adjacency_.triangles_of_edge(static_cast<std::uint32_t>(e)))
        edge_normal_[e] += face_normal_[t];
    vertex_normal_ = vertex_normal;
    open_vertex_.assign(P.size(), 0);
    open_edge_.assign(adjacency_.edges.size(), 0);
    for (auto e : adjacency_.boundary_edges) {
      open_edge_[e] = 1;
      open_vertex_[adjacency_.edges[e][0]] = open_vertex_[adjacency_.edges[e][1]] = 1;
    }
    if (!mesh_.has_normals()) {
      mesh_.normals.resize(P.size());
      for (std::size_t v = 0; v < P.size(); ++v) mesh_.normals[v] = normalized(vertex_normal[v]);
    }
  }

  struct Sample {
    float distance;  // signed: negative inside
    ClosestPoint at;
    bool open;  // nearest an open rim: the side is unknown (distance >= 0)
  };
  Sample operator()(const Vec3& p, std::uint32_t hint = ClosestPoint::kNone) const {
    return sample(p, bvh().closest_point(p, hint));
  }
  // The signed distance of p whose closest surface point is cp.
  Sample sample(const Vec3& p, const ClosestPoint& cp) const {
    auto [n, open] = feature(cp);
    float d = std::sqrt(cp.distance_squared);
    // Nearest to a hole's rim the pseudo-normal's side is a half-plane that
    // runs off to infinity: such points are left to the flood fill.
    if (open) return {d, cp, true};
    return {dot(p - cp.point, n) < 0 ? -d : d, cp, false};
  }
  // The pseudo-normal at a closest point (face, edge or vertex normal by
  // where on the triangle it lies) and whether that feature is an open rim.
  std::pair<Vec3, bool> feature(const ClosestPoint& cp) const {
    const auto& b = cp.barycentric;
    const auto& f = mesh_.triangles[cp.triangle];
    constexpr float kTol = 1e-5f;
    int zeros = (b[0] < kTol) + (b[1] < kTol) + (b[2] < kTol);
    if (zeros >= 2) {
      int k = b[0] >= b[1] && b[0] >= b[2] ? 0 : b[1] >= b[2] ? 1 : 2;
      return {vertex_normal_[f[k]], open_vertex_[f[k]] != 0};
    }
    if (zeros == 1) {
      int side = b[2] < kTol ? 0 : b[0] < kTol ? 1 : 2;
      auto e = adjacency_.triangle_edges[cp.triangle][side];
      if (e != MeshAdjacency::kNoEdge) return {edge_normal_[e], open_edge_[e] != 0};
    }
    return {face_normal_[cp.triangle], false};
  }
  bool has_rims() const { return !adjacency_.boundary_edges.empty(); }
  const TriangleMesh& mesh() const { return mesh_; }
  // Built on first use (repairs and holes of open meshes need it; a closed
  // mesh's band and edge points come from the triangle scan alone).
  const TriangleTree& bvh() const {
    std::call_once(bvh_once_, [&] { bvh_ = std::make_unique<TriangleTree>(mesh_); });
    return *bvh_;
  }
  // The point of triangle t nearest to p, as a closest-point answer.
  ClosestPoint on_triangle(const Vec3& p, std::uint32_t t) const {
    const auto& f = mesh_.triangles[t];
    TrianglePoint tp = closest_point_on_triangle(p, mesh_.positions[f[0]], mesh_.positions[f[1]],
                                                 mesh_.positions[f[2]]);
    return {tp.point, t, tp.barycentric, tp.distance_squared};
  }
  // The unit normal at a closest point (vertex normals interpolated).
  Vec3 normal_at(const ClosestPoint& cp) const {
    const auto& f = mesh_.triangles[cp.triangle];
    Vec3 n{};
    for (int k = 0; k < 3; ++k) n += mesh_.normals[f[k]] * cp.barycentric[k];
    return length_squared(n) > 0 ? normalized(n) : face_normal_[cp.triangle];
  }

 private:
  TriangleMesh mesh_;
  MeshAdjacency adjacency_;
  std::vector<Vec3> face_normal_, vertex_normal_, edge_normal_;
  std::vector<std::uint8_t> open_vertex_, open_edge_;
  mutable std::unique_ptr<TriangleTree> bvh_;
  mutable std::once_flag bvh_once_;
};

// The finest lattice: the points of the root cube (2^depth cells a side,
// centred on the mesh's box) that the box, grown by a cell, spans (beyond it
// everything is empty), a sign for each, an exact signed distance for the
// band. Lattice point (i, j, k) is root-cube point (i, j, k) + offset.
struct Lattice {
  int depth = 0;
  std::array<std::int64_t, 3> dim{};     // points per axis
  std::array<std::int64_t, 3> offset{};  // of the first point, in cells of the root cube
  Vec3 root;                             // the root cube's lowest corner
  Vec3 origin;
  float h = 0;
  std::vector<std::uint8_t> state;
  struct Exact {
    std::int64_t idx;
    float distance;          // signed
    std::uint32_t triangle;  // the closest one (meshes), else ClosestPoint::kNone
    bool operator<(const Exact& o) const { return idx < o.idx; }
  };
  std::vector<Exact> distance;  // exact ones, sorted by index at the end

  const Exact* find_distance(std::int64_t idx) const {
    auto it = std::lower_bound(distance.begin(), distance.end(), Exact{idx, 0, 0});
    return it != distance.end() && it->idx == idx ? &*it : nullptr;
  }

  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return i + dim[0] * (j + dim[1] * k);
  }
  std::int64_t plane() const { return dim[0] * dim[1]; }
  std::array<std::int64_t, 3> coords(std::int64_t idx) const {
    return {idx % dim[0], (idx / dim[0]) % dim[1], idx / plane()};
  }
  Vec3 point(std::int64_t idx) const {
    auto c = coords(idx);
    return root + Vec3{static_cast<float>(c[0] + offset[0]), static_cast<float>(c[1] + offset[1]),
                       static_cast<float>(c[2] + offset[2])} *
                      h;
  }
  bool inside(std::int64_t idx) const { return state[idx] & kInside; }
  /// Calls fn(edge, x, y, z) for each cell of the lattice around the crossed
  /// lattice edge `key` (point * 3 + axis a): it is edge 4a + q of the cell
  /// whose lower corner is q's offsets (bit 0 on axis a + 1, bit 1 on a + 2)
  /// below it; x, y, z in root-cube cell coordinates.
  template <class Fn>
  void for_each_cell_around(std::int64_t key, Fn&& fn) const {
    const std::int64_t p = key / 3, a = key % 3;
    const auto c = coords(p);
    const int a1 = static_cast<int>((a + 1) % 3), a2 = static_cast<int>((a + 2) % 3);
    for (int q = 0; q < 4; ++q) {
      std::int64_t cell[3] = {c[0], c[1], c[2]};
      cell[a1] -= q & 1, cell[a2] -= q >> 1;
      if (cell[a1] < 0 || cell[a2] < 0 || cell[a1] + 1 >= dim[a1] || cell[a2] + 1 >= dim[a2])
        continue;
      fn(static_cast<int>(4 * a + q), cell[0] + offset[0], cell[1] + offset[1],
         cell[2] + offset[2]);
    }
  }
  bool on_border(std::int64_t idx) const {
    auto c = coords(idx);
    for (int a = 0; a < 3; ++a)
      if (c[a] == 0 || c[a] == dim[a] - 1) return true;
    return false;
  }
};

// Exact signed distances at `points`; a point nearest an open rim keeps the
// sign it has (none yet in the band: the flood fill gives it one). Returns
// the points whose sign changed.
std::vector<std::int64_t> measure(Lattice& lat, const SignedDistance& sd,
                                  const std::vector<std::int64_t>& points) {
  std::vector<float> d(points.size());
  std::vector<std::uint8_t> open(points.size());
  std::vector<std::uint32_t> tri(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::uint32_t hint = ClosestPoint::kNone;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        auto s = sd(lat.point(points[i]), hint);
                        hint = tri[i] = s.at.triangle;
                        open[i] = s.open;
                        // A point on the surface counts as outside, a hair away.
                        d[i] = s.distance == 0 ? 1e-6f * lat.h : s.distance;
                      }
                    });
  std::vector<std::int64_t> changed;
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto& st = lat.state[points[i]];
    if (open[i]) {
      st |= kMeasured;
      continue;
    }
    std::uint8_t next = kExact | kAssigned | (d[i] < 0 ? kInside : 0);
    if ((st & kInside) != (next & kInside)) changed.push_back(points[i]);
    st = next;
    lat.distance.push_back({points[i], d[i], tri[i]});
  }
  return changed;
}

// An empty lattice whose root cube holds `box` with a cell to spare on
// every side.
Lattice empty_lattice(const Box3& box, int resolution) {
  Vec3 size = box.size();
  float extent = std::max({size.x, size.y, size.z});
  if (!(extent > 0)) throw DataError("mcoctree: all vertices of the mesh are at one point");
  Lattice lat;
  lat.depth = 1;
  while ((1 << lat.depth) < resolution + 2) ++lat.depth;
  lat.h = extent / static_cast<float>(resolution);
  const std::int64_t side = std::int64_t{1} << lat.depth;
  lat.root = box.center() - Vec3{1, 1, 1} * (lat.h * static_cast<float>(side) * 0.5f);
  for (int a = 0; a < 3; ++a) {
    auto lo = static_cast<std::int64_t>(std::floor((box.lo[a] - lat.root[a]) / lat.h)) - 1;
    auto hi = static_cast<std::int64_t>(std::ceil((box.hi[a] - lat.root[a]) / lat.h)) + 1;
    lat.offset[a] = std::max<std::int64_t>(0, lo);
    lat.dim[a] = std::min(side, hi) - lat.offset[a] + 1;
  }
  lat.origin = lat.point(0);
  lat.state.assign(static_cast<std::size_t>(lat.plane() * lat.dim[2]), 0);
  return lat;
}

template <class Fn>
void lattice_neighbours(const Lattice& lat, std::int64_t idx, Fn&& fn) {
  const std::int64_t step[3] = {1, lat.dim[0], lat.plane()};
  auto c = lat.coords(idx);
  for (int a = 0; a < 3; ++a) {
    if (c[a] > 0) fn(idx - step[a]);
    if (c[a] + 1 < lat.dim[a]) fn(idx + step[a]);
  }
}

// Runs fn(k, out) for the layers k in [first, last) of the lattice in
// parallel, each appending to its own vector, and returns what they appended
// in layer order (what one loop over the layers would give).
template <class Fn>
std::vector<std::int64_t> collect_by_layer(std::int64_t first, std::int64_t last, Fn&& fn) {
  std::vector<std::vector<std::int64_t>> part(
      static_cast<std::size_t>(std::max<std::int64_t>(last - first, 0)));
  tbb::parallel_for(first, last,
                    [&](std::int64_t k) { fn(k, part[static_cast<std::size_t>(k - first)]); });
  std::size_t n = 0;
  for (const auto& p : part) n += p.size();
  std::vector<std::int64_t> out;
  out.reserve(n);
  for (const auto& p : part) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Breadth-first flood fill from the assigned points: every unassigned point
// takes the sign of the nearest assigned one (in lattice steps; a tie goes to
// the point first in the queue). Precondition: the lattice's border is all
// assigned, so that only the seeds' neighbours need a bounds check and the
// queue holds bare indices (the fill visits most of the lattice: its inner
// loop is a load, a test and a store per neighbour).
void flood_fill(Lattice& lat, const std::vector<std::int64_t>& seeds, McBuildStats& stats) {
  assert(lat.state.size() <= std::numeric_limits<std::uint32_t>::max());
  std::uint8_t* const st = lat.state.data();  // a byte store may alias a member: no reloads
  std::vector<std::uint32_t> queue;
  std::size_t flooded = 0;
  auto visit = [&](std::int64_t q, std::uint8_t inside) {
    const std::uint8_t s = st[q];
    if (s & kAssigned) return;
    assert(!lat.on_border(q));
    st[q] = (s & kMeasured) | kAssigned | inside;
    queue.push_back(static_cast<std::uint32_t>(q));
  };
  for (auto idx : seeds) {
    const std::uint8_t inside = st[idx] & kInside;
    lattice_neighbours(lat, idx, [&](std::int64_t q) { visit(q, inside); });
  }
  const std::int64_t step[6] = {-1, 1, -lat.dim[0], lat.dim[0], -lat.plane(), lat.plane()};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    if (head >= (1u << 20) && 2 * head >= queue.size()) {  // keep only the frontier
      flooded += head;
      queue.erase(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(head));
      head = 0;
    }
    const std::int64_t idx = queue[head];
    const std::uint8_t inside = st[idx] & kInside;
    for (auto d : step) visit(idx + d, inside);
  }
  stats.flooded_points += flooded + queue.size();
}

Lattice make_lattice(const SignedDistance& sd, int resolution, McBuildStats& stats,
                     const ProgressCallback& progress) {
  const TriangleMesh& m = sd.mesh();
  Lattice lat = empty_lattice(m.bounds(), resolution);

  // Band: every lattice point within a cell of the surface gets its exact
  // closest point by scanning each triangle over the lattice points of its
  // bounding box grown by a cell (those points include every point within a
  // cell of it), keeping the nearest: a few dozen point-triangle tests per
  // triangle instead of a hierarchy query per point. Both ends of a lattice
  // edge the surface crosses are within a cell of it, so these points
  // separate the inside from the outside and the flood fill below cannot
  // carry a sign across the surface. The lattice is cut into slabs of
  // kSlab layers, each scanned by one task with the triangles that reach it.
  constexpr std::int64_t kSlab = 4;
  const std::int64_t nz = lat.dim[2], plane = lat.plane(), slabs = (nz + kSlab - 1) / kSlab;
  struct Range {
    std::int64_t lo[3], hi[3];
  };
  std::vector<Range> range(m.triangles.size());
  std::vector<std::vector<std::uint32_t>> bucket(static_cast<std::size_t>(slabs));
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    Box3 tb;
    for (int k = 0; k < 3; ++k) tb.add(m.positions[m.triangles[t][k]]);
    for (int a = 0; a < 3; ++a) {
      range[t].lo[a] = std::max<std::int64_t>(
          0, static_cast<std::int64_t>(std::ceil((tb.lo[a] - lat.origin[a]) / lat.h - 1)));
      range[t].hi[a] = std::min<std::int64_t>(
          lat.dim[a] - 1,
          static_cast<std::int64_t>(std::floor((tb.hi[a] - lat.origin[a]) / lat.h + 1)));
    }
    for (auto s = range[t].lo[2] / kSlab; s <= range[t].hi[2] / kSlab; ++s)
      bucket[static_cast<std::size_t>(s)].push_back(static_cast<std::uint32_t>(t));
  }
  struct Found {
    std::int64_t idx;
    float distance;  // signed; NaN: nearest an open rim
    std::uint32_t triangle;
  };
  std::vector<std::vector<Found>> found(static_cast<std::size_t>(slabs));
  const float h2 = lat.h * lat.h, margin = 1e-5f * h2;
  // Lattice coordinates per axis (the same values as lat.point's).
  std::array<std::vector<float>, 3> coord;
  for (int a = 0; a < 3; ++a) {
    coord[a].resize(static_cast<std::size_t>(lat.dim[a]));
    for (std::int64_t i = 0; i < lat.dim[a]; ++i)
      coord[a][static_cast<std::size_t>(i)] =
          lat.root[a] + static_cast<float>(i + lat.offset[a]) * lat.h;
  }
  ProgressCounter slabs_done(progress, "signs", static_cast<std::uint64_t>(slabs), 1);
  tbb::parallel_for(std::int64_t{0}, slabs, [&](std::int64_t s) {
    struct Best {
      float d2 = INFINITY;
      std::uint32_t triangle = 0;
      std::array<float, 3> barycentric{};
    };
    const std::int64_t z0 = s * kSlab, z1 = std::min(nz, z0 + kSlab);
    std::vector<Best> best(static_cast<std::size_t>((z1 - z0) * plane));
    for (auto t : bucket[static_cast<std::size_t>(s)]) {
      const auto& f = m.triangles[t];
      const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
      const Range& r = range[t];
      // Points farther than a cell from the triangle's plane are skipped
      // before the exact test (most of the box of a slanted triangle).
      Vec3 normal = cross(b - a, c - a);
      float scale = length(normal);
      if (scale > 0) normal = normal / scale;
      // In the plane, a point beyond an edge's line is at least that far
      // from the triangle: with the distance to the plane, a lower bound
      // that skips most of the rest (a margin above rounding, so that a
      // skipped triangle is one the exact test would not have taken).
      const Vec3* corner[3] = {&a, &b, &c};
      Vec3 inward[3];
      for (int e = 0; e < 3; ++e) {
        inward[e] = cross(normal, *corner[(e + 1) % 3] - *corner[e]);
        float l = length(inward[e]);
        inward[e] = l > 0 ? inward[e] / l : Vec3{};
      }
      // The dot products below, dot(x - from[q], dir[q]), with their z terms
      // taken once per layer and their y terms once per row (the same sums in
      // the same order).
      const Vec3* from[4] = {&a, &a, &b, &c};
      const Vec3* dir[4] = {&normal, &inward[0], &inward[1], &inward[2]};
      const std::int64_t i0 = r.lo[0], i1 = r.hi[0];
      for (auto k = std::max(r.lo[2], z0); k <= std::min(r.hi[2], z1 - 1); ++k) {
        const float z = coord[2][static_cast<std::size_t>(k)];
        float dz[4];
        for (int q = 0; q < 4; ++q) dz[q] = (z - from[q]->z) * dir[q]->z;
        for (auto j = r.lo[1]; j <= r.hi[1]; ++j) {
          const float y = coord[1][static_cast<std::size_t>(j)];
          float dy[4];
          for (int q = 0; q < 4; ++q) dy[q] = (y - from[q]->y) * dir[q]->y;
          Best* row = &best[static_cast<std::size_t>(lat.index(0, j, k - z0))];
          for (auto i = i0; i <= i1; ++i) {
            const float x = coord[0][static_cast<std::size_t>(i)];
            auto along = [&](int q) { return ((x - from[q]->x) * dir[q]->x + dy[q]) + dz[q]; };
            const float off = along(0);
            if (off * off > h2) continue;
            // No nearer than its plane: skip when a nearer triangle is known.
            Best& bt = row[i];
            if (off * off >= bt.d2) continue;
            const float beyond = std::max({0.0f, -along(1), -along(2), -along(3)});
            if (off * off + beyond * beyond > std::min(h2, bt.d2) * 1.001f + margin) continue;
            TrianglePoint tp = closest_point_on_triangle({x, y, z}, a, b, c);
            if (tp.distance_squared < bt.d2) bt = {tp.distance_squared, t, tp.barycentric};
          }
        }
      }
    }
    auto& out = found[static_cast<std::size_t>(s)];
    for (std::size_t p = 0; p < best.size(); ++p) {
      const Best& bt = best[p];
      if (!(bt.d2 <= h2)) continue;
      std::int64_t idx = z0 * plane + static_cast<std::int64_t>(p);
      ClosestPoint cp;
      cp.triangle = bt.triangle, cp.barycentric = bt.barycentric, cp.distance_squared = bt.d2;
      const auto& f = m.triangles[bt.triangle];
      for (int k = 0; k < 3; ++k) cp.point += m.positions[f[k]] * bt.barycentric[k];
      auto sample = sd.sample(lat.point(idx), cp);
      // A point on the surface counts as outside, a hair away; so does the
      // root cube's boundary (a cell or more from the mesh's box).
      float d = sample.distance == 0 ? 1e-6f * lat.h : sample.distance;
      if (lat.on_border(idx)) d = std::abs(d);
      out.push_back({idx, sample.open && !lat.on_border(idx) ? NAN : d, bt.triangle});
    }
    slabs_done.add(1);
  });
  std::vector<std::int64_t> seeds;
  for (const auto& slab : found)
    for (const auto& fd : slab) {
      ++stats.band_points;
      if (std::isnan(fd.distance)) {
        lat.state[fd.idx] = kMeasured;
        continue;
      }
      lat.state[fd.idx] = kExact | kAssigned | (fd.distance < 0 ? kInside : 0);
      lat.distance.push_back({fd.idx, fd.distance, fd.triangle});
      seeds.push_back(fd.idx);
    }

  // The rest of the root cube's boundary is outside and stays so: an open
  // mesh's inside could otherwise flood out to it, and the surface would
  // end there.
  const std::int64_t nx = lat.dim[0], ny = lat.dim[1];
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        if (!(k == 0 || k == nz - 1 || j == 0 || j == ny - 1) && i != 0) i = nx - 1;
        std::int64_t idx = lat.index(i, j, k);
        if (lat.state[idx] & kExact) continue;
        lat.state[idx] = kAssigned | kMeasured;
        seeds.push_back(idx);
      }

  // Flood fill the rest from the band, breadth first (nearest band sign
  // wins); band points nearest an open rim take their sign the same way, so
  // that a hole is closed about midway between the inside and the outside.
  flood_fill(lat, seeds, stats);
  auto neighbours = [&](std::int64_t idx, auto&& fn) { lattice_neighbours(lat, idx, fn); };
  auto unsure = [&](std::int64_t idx) { return !(lat.state[idx] & (kExact | kMeasured)); };
  // Repair: a flooded point that disagrees with a neighbour gets an exact sign
  // (the inside leaks through a gap narrower than the band), and so do the
  // unmeasured neighbours of each point whose sign that changes.
  // (The lattice's boundary is all measured or exact: only inner points.)
  const std::uint8_t* st = lat.state.data();
  std::vector<std::int64_t> work =
      collect_by_layer(1, nz - 1, [&](std::int64_t k, std::vector<std::int64_t>& out) {
        // Copies in locals: a push could alias what the lambda refers to.
        const std::uint8_t* const s = st;
        const std::int64_t row_step = nx, layer_step = plane, rows = ny, cols = nx;
        for (std::int64_t j = 1; j + 1 < rows; ++j) {
          const std::int64_t row = j * row_step + k * layer_step;
          for (std::int64_t i = 1; i + 1 < cols; ++i) {
            const std::int64_t idx = row + i;
            const std::uint8_t v = s[idx];
            const std::uint8_t differ = (s[idx - 1] ^ v) | (s[idx + 1] ^ v) |
                                        (s[idx - row_step] ^ v) | (s[idx + row_step] ^ v) |
                                        (s[idx - layer_step] ^ v) | (s[idx + layer_step] ^ v);
            if ((differ & kInside) && !(v & (kExact | kMeasured))) out.push_back(idx);
          }
        }
      });
  // The band's distances are in index order already (slabs in z order, each
  // in index order); only the repairs' are merged in.
  const auto banded = static_cast<std::ptrdiff_t>(lat.distance.size());
  while (!work.empty()) {
    stats.sign_repairs += work.size();
    auto changed = measure(lat, sd, work);
    std::vector<std::int64_t> next;
    for (auto idx : changed)
      neighbours(idx, [&](std::int64_t q) {
        if (unsure(q) && lat.inside(q) != lat.inside(idx)) next.push_back(q);
      });
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    work = std::move(next);
  }
  std::sort(lat.distance.begin() + banded, lat.distance.end());
  std::inplace_merge(lat.distance.begin(), lat.distance.begin() + banded, lat.distance.end());
  return lat;
}

// Range points merged from several scans (no zippering) and the signed
// distance they define (Kim, sec. 4.2, after Hoppe et al. 1992): the distance
// of x to the tangent plane of the nearest range point, whose normal comes
// from its 4 lattice neighbours. One nearest point makes the sign flicker
// where two scans overlap slightly out of register, so the distance is the
// Gaussian-weighted mean over the nearby points whose normals agree with the
// nearest one's (same sheet), within two cells.
class ScanField {
 public:
  explicit ScanField(const std::vector<RangeScan>& scans) {
    for (const auto& s : scans) {
      if (s.grid.size() != static_cast<std::size_t>(s.cols) * s.rows)
        throw DataError("mcoctree: " + s.name + ": grid size is not num_cols x num_rows");
      std::vector<Vec3> n = s.normals();
      std::vector<std::uint8_t> used(s.points.size(), 0);
      for (auto g : s.grid)
        if (g >= 0) used[g] = 1;
      for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (!used[i]) continue;
        if (!is_finite(s.points[i]))
          throw DataError("mcoctree: " + s.name + ": a non-finite coordinate");
        points_.push_back(s.to_world(s.points[i]));
        normals_.push_back(normalized(s.rotate(n[i])));
        colored_ = colored_ || !s.colors.empty();
        colors_.push_back(s.colors.empty() ? Rgb8{200, 200, 200} : s.colors[i]);
      }
    }
    if (points_.empty()) throw DataError("mcoctree: the range scans hold no point");
    for (const auto& p : points_) bounds_.add(p);
  }
  const Box3& bounds() const { return bounds_; }
  bool colored() const { return colored_; }
  std::size_t size() const { return points_.size(); }
  const Vec3& point(std::size_t i) const { return points_[i]; }

  void index(const Vec3& origin, float h) {
    origin_ = origin, h_ = h;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points_.size());
    for (std::uint32_t i = 0; i < points_.size(); ++i) keyed[i] = {key(cell_of(points_[i])), i};
    std::sort(keyed.begin(), keyed.end());
    order_.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
      order_[i] = keyed[i].second;
      if (i == 0 || keyed[i].first != keyed[i - 1].first)
        cells_[keyed[i].first] = {static_cast<std::uint32_t>(i), 0};
      ++cells_[keyed[i].first].second;
    }
  }
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor((p.x - origin_.x) / h_)),
            static_cast<std::int64_t>(std::floor((p.y - origin_.y) / h_)),
            static_cast<std::int64_t>(std::floor((p.z - origin_.z) / h_))};
  }

  struct Estimate {
    bool found = false;
    float distance = 0;  // signed: negative inside
    Vec3 normal;
    Vec3 color;
  };
  // The weighted tangent-plane distance at x from the points within `reach`
  // cells (per axis) of x's cell.
  Estimate estimate(const Vec3& x, int reach) const {
    auto c = cell_of(x);
    float best = INFINITY;
    std::uint32_t nearest = 0;
    visit(c, reach, [&](std::uint32_t i) {
      float d = length_squared(points_[i] - x);
      if (d < best) best = d, nearest = i;
    });
    Estimate e;
    if (best == INFINITY) return e;
    e.found = true;
    const Vec3 n0 = normals_[nearest];
    double wsum = 0, dsum = 0;
    Vec3 nsum{}, csum{};
    const float inv = 1.0f / (h_ * h_);
    visit(c, reach, [&](std::uint32_t i) {
      if (dot(normals_[i], n0) <= 0.5f) return;
      float d2 = length_squared(points_[i] - x);
      if (d2 > best + 4 * h_ * h_) return;
      float w = std::exp(-(d2 - best) * inv);
      wsum += w;
      dsum += w * dot(x - points_[i], normals_[i]);
      nsum += normals_[i] * w;
      csum += Vec3{colors_[i][0] * 1.0f, colors_[i][1] * 1.0f, colors_[i][2] * 1.0f} * w;
    });
    e.distance = static_cast<float>(dsum / wsum);
    e.normal = normalized(nsum);
    e.color = csum / static_cast<float>(wsum);
    return e;
  }

 private:
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return static_cast<std::uint64_t>(c[0] & 0x1fffff) |
           static_cast<std::uint64_t>(c[1] & 0x1fffff) << 21 |
           static_cast<std::uint64_t>(c[2] & 0x1fffff) << 42;
  }
  template <class Fn>
  void visit(const std::array<std::int64_t, 3>& c, int reach, Fn&& fn) const {
    for (auto k = c[2] - reach; k <= c[2] + reach; ++k)
      for (auto j = c[1] - reach; j <= c[1] + reach; ++j)
        for (auto i = c[0] - reach; i <= c[0] + reach; ++i) {
          if (i < 0 || j < 0 || k < 0) continue;
          auto it = cells_.find(key({i, j, k}));
          if (it == cells_.end()) continue;
          for (std::uint32_t a = 0; a < it->second.second; ++a) fn(order_[it->second.first + a]);
        }
  }
  std::vector<Vec3> points_, normals_;
  std::vector<Rgb8> colors_;
  bool colored_ = false;
  Box3 bounds_;
  Vec3 origin_;
  float h_ = 1;
  std::vector<std::uint32_t> order_;
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> cells_;
};

// Line-of-sight carving (Curless & Levoy 1996's space carving, reduced to
// signs): each scan is resampled as a depth image in its own frame (the
// sensor looks down -z, lines of sight parallel: the Stanford Cyberware
// scans and mco scan's are), from its grid triangles without the depth
// jumps. What the scans say of a point (seen_at):
//
// | the scans' lines through it                                 | the point is      |
// |-------------------------------------------------------------|-------------------|
// | one reaches its surface behind the point (by > `margin`)    | empty (outside)   |
// | else more meet a surface before it than pass beyond the     | occluded (inside) |
// |   scan's data (background: farther than `margin` from every |                   |
// |   pixel with data, or outside the scan's window)            |                   |
// | else                                                        | unseen (outside)  |
//
// Only measured depth carves for sure. A pixel without data inside the
// silhouette (a gap at a grazing angle) says nothing: carving along those
// lines made the bunny a shell, an inner wall wherever one scan had a gap.
// Background lines only vote: the Cyberware scans are partial (a limited
// window; the chin and ear scans are close-ups), so beyond one scan's data
// may lie the object that eight others see behind their surfaces, while
// space that one scan sees behind an ear and the others beyond their data
// is air (with "occluded" alone, such space made blobs 2 cm across).
class SightCarver {
 public:
  enum class Seen { kUnseen, kEmpty, kOccluded };
  SightCarver(const std::vector<RangeScan>& scans, float margin) : margin_(margin) {
    for (const auto& s : scans) add(s);
  }
  Seen seen_at(const Vec3& world) const {
    int occluded = 0, background = 0;
    for (const auto& im : images_) {
      Vec3 q = im.scan->to_scan(world);
      auto i = static_cast<std::int64_t>(std::floor((q.x - im.x0) / im.s));
      auto j = static_cast<std::int64_t>(std::floor((q.y - im.y0) / im.s));
      if (i < 0 || j < 0 || i >= im.w || j >= im.h) {
        ++background;  // beyond the scan's window
        continue;
      }
      const std::size_t px = static_cast<std::size_t>(j) * im.w + i;
      const float depth = im.depth[px];
      if (!std::isfinite(depth)) {
        background += im.background[px];
        continue;
      }
      if (q.z > depth + margin_) return Seen::kEmpty;
      occluded += q.z < depth - margin_;
    }
    return occluded > background ? Seen::kOccluded : Seen::kUnseen;
  }

 private:
  struct Image {
    const RangeScan* scan;
    float x0, y0, s;
    int w, h;
    std::vector<float> depth;              // nearest surface (largest z); -inf: none
    std::vector<std::uint8_t> background;  // no data within margin of the line
  };
  void add(const RangeScan& scan) {
    float s = scan.spacing();
    if (!(s > 0)) return;
    Box3 box;
    for (auto g : scan.grid)
      if (g >= 0) box.add(scan.points[g]);
    Vec3 size = box.size();
    // At most 4096 pixels a side: coarser pixels for a very wide scan.
    s = std::max(s, std::max(size.x, size.y) / 4090.0f);
    Image im{&scan, box.lo.x - 2 * s, box.lo.y - 2 * s, s, 0, 0, {}, {}};
    im.w = static_cast<int>(std::ceil(size.x / s)) + 5;
    im.h = static_cast<int>(std::ceil(size.y / s)) + 5;
    im.depth.assign(static_cast<std::size_t>(im.w) * im.h, -INFINITY);
    const float limit2 = 16 * scan.spacing() * scan.spacing();
    auto at = [&](int r, int c) { return scan.grid[static_cast<std::size_t>(r) * scan.cols + c]; };
    auto raster = [&](std::int32_t ia, std::int32_t ib, std::int32_t ic) {
      if (ia < 0 || ib < 0 || ic < 0) return;
      const Vec3 &a = scan.points[ia], &b = scan.points[ib], &c = scan.points[ic];
      if (length_squared(a - b) > limit2 || length_squared(b - c) > limit2 ||
          length_squared(c - a) > limit2)
        return;
      float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (!(std::abs(area) > 0)) return;
      auto px = [&](float v, float o) { return (v - o) / im.s - 0.5f; };
      int c0 = std::max(0, static_cast<int>(std::ceil(px(std::min({a.x, b.x, c.x}), im.x0))));
      int c1 =
          std::min(im.w - 1, static_cast<int>(std::floor(px(std::max({a.x, b.x, c.x}), im.x0))));
      int r0 = std::max(0, static_cast<int>(std::ceil(px(std::min({a.y, b.y, c.y}), im.y0))));
      int r1 =
          std::min(im.h - 1, static_cast<int>(std::floor(px(std::max({a.y, b.y, c.y}), im.y0))));
      for (int r = r0; r <= r1; ++r)
        for (int cc = c0; cc <= c1; ++cc) {
          float x = im.x0 + (static_cast<float>(cc) + 0.5f) * im.s;
          float y = im.y0 + (static_cast<float>(r) + 0.5f) * im.s;
          float l1 = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
          float l2 = ((a.x - x) * (b.y - y) - (b.x - x) * (a.y - y)) / area;
          float l0 = 1 - l1 - l2;
          if (l0 < -1e-4f || l1 < -1e-4f || l2 < -1e-4f) continue;
          float z = l0 * a.z + l1 * b.z + l2 * c.z;
          auto& d = im.depth[static_cast<std::size_t>(r) * im.w + cc];
          d = std::max(d, z);
        }
    };
    for (int r = 0; r + 1 < scan.rows; ++r)
      for (int c = 0; c + 1 < scan.cols; ++c) {
        raster(at(r, c), at(r, c + 1), at(r + 1, c + 1));
        raster(at(r, c), at(r + 1, c + 1), at(r + 1, c));
      }
    // Background: pixels farther than the margin from every pixel with
    // data (chamfer distance, two passes), the outside of the silhouette;
    // nearer ones may be a gap in the object's surface.
    const int reach = std::max(1, static_cast<int>(std::ceil(margin_ / im.s)));
    std::vector<int> dist(im.depth.size());
    for (std::size_t k = 0; k < dist.size(); ++k)
      dist[k] = std::isfinite(im.depth[k]) ? 0 : reach + 1;
    auto relax = [&](int r, int c, int dr, int dc) {
      const int rr = r + dr, cc = c + dc;
      if (rr < 0 || cc < 0 || rr >= im.h || cc >= im.w) return;
      int& d = dist[static_cast<std::size_t>(r) * im.w + c];
      d = std::min(d, dist[static_cast<std::size_t>(rr) * im.w + cc] + 1);
    };
    for (int r = 0; r < im.h; ++r)
      for (int c = 0; c < im.w; ++c) {
        relax(r, c, -1, -1);
        relax(r, c, -1, 0);
        relax(r, c, -1, 1);
        relax(r, c, 0, -1);
      }
    for (int r = im.h - 1; r >= 0; --r)
      for (int c = im.w - 1; c >= 0; --c) {
        relax(r, c, 1, 1);
        relax(r, c, 1, 0);
        relax(r, c, 1, -1);
        relax(r, c, 0, 1);
      }
    im.background.resize(dist.size());
    for (std::size_t k = 0; k < dist.size(); ++k) im.background[k] = dist[k] > reach;
    images_.push_back(std::move(im));
  }
  float margin_;
  std::vector<Image> images_;
};

// The sign lattice of range scans. Band: the lattice points within two cells
// of a range point get the weighted tangent-plane distance. Outside: the
// box's outer faces (the root cube has a free cell all round) and every point
// a line of sight shows empty (SightCarver, 2 cells of margin). Every other
// point (inside the object, in a gap of the data, or seen by no scan: under
// the Stanford bunny, which stood on the turntable) by the scans' vote
// (SightCarver::seen_at), which closes the unseen region with a cap where
// the vote changes.
Lattice make_scan_lattice(ScanField& field, const std::vector<RangeScan>& scans, int resolution,
                          McBuildStats& stats, const ProgressCallback& progress) {
  Lattice lat = empty_lattice(field.bounds(), resolution);
  field.index(lat.origin, lat.h);
  std::vector<std::int64_t> band;
  for (std::size_t i = 0; i < field.size(); ++i) {
    auto c = field.cell_of(field.point(i));
    for (auto k = c[2] - 1; k <= c[2] + 2; ++k)
      for (auto j = c[1] - 1; j <= c[1] + 2; ++j)
        for (auto a = c[0] - 1; a <= c[0] + 2; ++a) {
          if (a < 0 || j < 0 || k < 0 || a >= lat.dim[0] || j >= lat.dim[1] || k >= lat.dim[2])
            continue;
          auto idx = lat.index(a, j, k);
          if (lat.state[idx] & kAssigned) continue;
          lat.state[idx] = kAssigned;
          band.push_back(idx);
        }
  }
  std::sort(band.begin(), band.end());
  std::vector<ScanField::Estimate> est(band.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        est[i] = field.estimate(lat.point(band[i]), 2);
                    });
  std::size_t measured = 0;
  for (std::size_t i = 0; i < band.size(); ++i) {
    if (!est[i].found) {
      lat.state[band[i]] = 0;
      continue;
    }
    float d = est[i].distance == 0 ? 1e-6f * lat.h : est[i].distance;
    // The lattice's boundary (a cell beyond the points) is outside: a
    // parent reaching past it would give the empty region beyond a sign
    // change its children cannot carry.
    if (lat.on_border(band[i])) d = std::abs(d);
    lat.state[band[i]] = kExact | kAssigned | (d < 0 ? kInside : 0);
    lat.distance.push_back({band[i], d, ClosestPoint::kNone});
    ++measured;
  }
  stats.band_points = measured;
  // Every other point from what the lines of sight say (SightCarver):
  // empty or unseen is outside, occluded inside. No flood fill: a flood from
  // the carved space under the unseen bottom rose into the body (nearer to
  // it than the walls' band), hollowing it from below.
  SightCarver carver(scans, 2 * lat.h);
  std::vector<std::uint8_t> seen(lat.state.size(), 0);
  ProgressCounter layers(progress, "signs", static_cast<std::uint64_t>(lat.dim[2]), 1);
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, lat.dim[2]), [&](const auto& r) {
    for (std::int64_t k = r.begin(); k != r.end(); ++k)
      for (std::int64_t j = 0; j < lat.dim[1]; ++j)
        for (std::int64_t i = 0; i < lat.dim[0]; ++i) {
          auto idx = lat.index(i, j, k);
          if (lat.state[idx] & kAssigned) continue;
          seen[idx] = static_cast<std::uint8_t>(
              lat.on_border(idx) ? SightCarver::Seen::kEmpty : carver.seen_at(lat.point(idx)));
        }
    layers.add(static_cast<std::uint64_t>(r.size()));
  });
  for (std::size_t idx = 0; idx < seen.size(); ++idx) {
    if (lat.state[idx] & kAssigned) continue;
    const auto how = static_cast<SightCarver::Seen>(seen[idx]);
    lat.state[idx] = kAssigned | (how == SightCarver::Seen::kOccluded ? kInside : 0);
    stats.carved_points += how == SightCarver::Seen::kEmpty;
    stats.flooded_points += how != SightCarver::Seen::kEmpty;
  }
  // Voids inside the object and bubbles around stray points (sign_components.h).
  const detail::SignCleanup cleanup =
      detail::clean_scan_signs(lat.state, lat.dim, kInside, kMinScanPart, kMinScanPartFraction);
  stats.filled_voids = cleanup.filled_voids;
  stats.dropped_parts = cleanup.dropped_parts;
  for (auto& e : lat.distance)  // a flipped point's distance keeps its magnitude
    if ((e.distance < 0) != lat.inside(e.idx)) e.distance = -e.distance;
  std::sort(lat.distance.begin(), lat.distance.end());
  return lat;
}

// Sorts keys below 2^bits (least significant digit first, 11 bits a pass).
void radix_sort(std::vector<std::uint64_t>& v, int bits) {
  std::vector<std::uint64_t> tmp(v.size());
  for (int shift = 0; shift < bits; shift += 11) {
    std::vector<std::size_t> start(2049, 0);
    for (auto x : v) ++start[((x >> shift) & 2047) + 1];
    for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
    for (auto x : v) tmp[start[(x >> shift) & 2047]++] = x;
    v.swap(tmp);
  }
}
std::uint64_t coord_key(int level, std::int64_t x, std::int64_t y, std::int64_t z) {
  return static_cast<std::uint64_t>(x) | static_cast<std::uint64_t>(y) << 20 |
         static_cast<std::uint64_t>(z) << 40 | static_cast<std::uint64_t>(level) << 60;
}

// The four-case corner rule on a 27-point lattice: a point no present child
// has takes the sign of an adjacent point, else of a diagonal one, else of the
// centre (Fig. 5.2). `known` marks the points some present child has.
std::uint32_t fill_unknown(std::uint32_t signs, std::uint32_t known) {
  // For each point, the points 1, 2, then 3 steps away (Manhattan), each
  // distance in index order: the first one known gives the sign.
  struct Order {
    std::int8_t q[27];
    int n = 0;
  };
  static const std::array<Order, 27> order = [] {
    std::array<Order, 27> o{};
    for (int p = 0; p < 27; ++p) {
      int c[3] = {p % 3, (p / 3) % 3, p / 9};
      for (int dist = 1; dist <= 3; ++dist)
        for (int q = 0; q < 27; ++q) {
          int d = std::abs(q % 3 - c[0]) + std::abs((q / 3) % 3 - c[1]) + std::abs(q / 9 - c[2]);
          if (d == dist) o[p].q[o[p].n++] = static_cast<std::int8_t>(q);
        }
    }
    return o;
  }();
  std::uint32_t out = signs & known;
  for (int p = 0; p < 27; ++p) {
    if (known >> p & 1) continue;
    int found = 13;  // the centre, which every child has
    for (int k = 0; k < order[p].n; ++k)
      if (known >> order[p].q[k] & 1) {
        found = order[p].q[k];
        break;
      }
    if (signs >> found & 1) out |= 1u << p;
  }
  return out;
}

// How far a surface point is from the input: the distance, over kRimGap
// when the closest point is on an open rim (a crossing of a true sign change
// lies within a cell edge of the surface; beyond a rim a quarter of that is
// already a cap).
struct Gap {
  float gap = 0;
  bool rim = false;
};

// Node by (level, coordinates), or a count by configuration: open
// addressing, linear probing (std::unordered_map's chained buckets were
// several times slower for the numbering's look-ups). Holds at most half
// its capacity.
class NodeIndex {
 public:
  void reserve(std::size_t n) {
    std::size_t size = 16;
    shift_ = 60;
    while (size < 2 * n) size *= 2, --shift_;
    keys_.assign(size, kEmpty);
    values_.assign(size, McNode::kNone);
    mask_ = size - 1;
    size_ = 0;
  }
  void insert(std::uint64_t key, std::uint32_t value) {
    std::size_t i = slot(key);
    while (keys_[i] != kEmpty) i = (i + 1) & mask_;
    keys_[i] = key, values_[i] = value;
    ++size_;
  }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return keys_.size(); }
  std::uint32_t find(std::uint64_t key) const {
    for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == kEmpty) return McNode::kNone;
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t slot(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift_);
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t mask_ = 0, size_ = 0;
  int shift_ = 60;
};

class Builder {
 public:
  Builder(McOctree& t, McBuildStats& stats, bool place_coarse, const ProgressCallback& progress)
      : t_(t), stats_(stats), place_coarse_(place_coarse), progress_(progress) {}

  // attr(x, hint, near, normal, colour) gives the normal (and the colour when
  // `colored`) of the surface point x and returns how far x is from the
  // input (a Gap, see mark_holes; {} for range scans); hint is per-thread
  // scratch, near the triangles closest to the edge's ends (or kNone).
  template <class Attr>
  void build_tree(const Lattice& lat, bool colored, Attr&& attr) {
    const int D = lat.depth;
    t_.depth = D;
    t_.origin = lat.root;
    t_.cell_size = lat.h;
    const std::int64_t nx = lat.dim[0], ny = lat.dim[1], nz = lat.dim[2];

    // Vertices: one per finest lattice edge whose ends differ in sign.
    const std::int64_t step[3] = {1, nx, lat.plane()};
    const std::vector<std::int64_t> edge_keys =  // point index * 3 + axis, ascending
        collect_by_layer(0, nz, [&](std::int64_t k, std::vector<std::int64_t>& out) {
          // Copies in locals: a push could alias what the lambda refers to.
          const std::uint8_t* const st = lat.state.data();
          const std::int64_t sx = nx, sy = ny, sz = nz, row_step = step[1], layer_step = step[2];
          auto inside = [&](std::int64_t idx) { return (st[idx] & kInside) != 0; };
          for (std::int64_t j = 0; j < sy; ++j) {
            const std::int64_t row = j * row_step + k * layer_step;
            const bool inner = j + 1 < sy && k + 1 < sz;
            for (std::int64_t i = 0; i < sx; ++i) {
              const std::int64_t idx = row + i;
              // Most points have no crossed edge: one test for the three.
              if (inner && i + 1 < sx &&
                  !(((st[idx + 1] ^ st[idx]) | (st[idx + row_step] ^ st[idx]) |
                     (st[idx + layer_step] ^ st[idx])) &
                    kInside))
                continue;
              const bool in = inside(idx);
              if (i + 1 < sx && in != inside(idx + 1)) out.push_back(idx * 3);
              if (j + 1 < sy && in != inside(idx + row_step)) out.push_back(idx * 3 + 1);
              if (k + 1 < sz && in != inside(idx + layer_step)) out.push_back(idx * 3 + 2);
            }
          }
        });
    if (edge_keys.empty())
      throw DataError("mcoctree: the surface crosses no lattice edge (resolution too low?)");
    t_.positions.resize(edge_keys.size());
    t_.normals.resize(edge_keys.size());
    if (colored) t_.colors.resize(edge_keys.size());
    gap_.assign(edge_keys.size(), Gap{});
    finest_count_ = edge_keys.size();
    ProgressCounter points(progress_, "surface points", edge_keys.size());
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, edge_keys.size(), 256),
        [&](const tbb::blocked_range<std::size_t>& r) {
          std::uint32_t hint = ClosestPoint::kNone;
          for (std::size_t v = r.begin(); v != r.end(); ++v) {
            std::int64_t p = edge_keys[v] / 3, q = p + step[edge_keys[v] % 3];
            const auto* dp = lat.find_distance(p);
            const auto* dq = lat.find_distance(q);
            float ratio = 0.5f;
            if (dp && dq) ratio = dp->distance / (dp->distance - dq->distance);
            ratio = std::clamp(ratio, 0.01f, 0.99f);
            Vec3 a = lat.point(p), b = lat.point(q);
            Vec3 x = a + (b - a) * ratio;
            t_.positions[v] = x;
            // Fallback normal: along the edge, from inside to outside.
            t_.normals[v] = normalized(lat.inside(p) ? b - a : a - b);
            std::array<std::uint32_t, 2> near{dp ? dp->triangle : ClosestPoint::kNone,
                                              dq ? dq->triangle : ClosestPoint::kNone};
            gap_[v] = attr(x, hint, near, t_.normals[v], colored ? &t_.colors[v] : nullptr);
          }
          points.add(r.size());
        });
    // Leaves: finest cells whose corners differ in sign, i.e. the (up to)
    // four cells around each crossed lattice edge.
    std::vector<std::vector<std::uint64_t>> codes(D + 1);
    for (auto key : edge_keys)
      lat.for_each_cell_around(key, [&](int, std::int64_t x, std::int64_t y, std::int64_t z) {
        codes[D].push_back(morton_code(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                                       static_cast<std::uint32_t>(z)));
      });
    radix_sort(codes[D], 3 * D);
    codes[D].erase(std::unique(codes[D].begin(), codes[D].end()), codes[D].end());
    stats_.leaves = codes[D].size();
    for (int l = D - 1; l >= 0; --l) {
      for (auto c : codes[l + 1]) codes[l].push_back(c >> 3);
      codes[l].erase(std::unique(codes[l].begin(), codes[l].end()), codes[l].end());
    }
    level_offset_.assign(D + 2, 0);
    for (int l = 0; l <= D; ++l) level_offset_[l + 1] = level_offset_[l] + codes[l].size();
    t_.nodes.assign(level_offset_[D + 1], McNode{});
    for (int l = 0; l <= D; ++l)
      tbb::parallel_for(std::size_t{0}, codes[l].size(), [&](std::size_t i) {
        McNode& node = t_.nodes[level_offset_[l] + i];
        node.level = static_cast<std::uint8_t>(l);
        std::uint64_t c = codes[l][i];
        std::uint32_t xyz[3] = {0, 0, 0};
        for (int b = 0; b < l; ++b)
          for (int a = 0; a < 3; ++a)
            xyz[a] |= static_cast<std::uint32_t>((c >> (3 * b + a)) & 1) << b;
        node.coords = {xyz[0], xyz[1], xyz[2]};
        if (l < D) {
          auto first = std::lower_bound(codes[l + 1].begin(), codes[l + 1].end(), c << 3);
          node.first_child =
              static_cast<std::uint32_t>(level_offset_[l + 1] + (first - codes[l + 1].begin()));
          for (auto it = first; it != codes[l + 1].end() && (*it >> 3) == c; ++it)
            node.child_mask |= static_cast<std::uint8_t>(1u << (*it & 7));
        }
      });
    index_.reserve(t_.nodes.size());
    for (std::size_t i = 0; i < t_.nodes.size(); ++i) {
      const McNode& node = t_.nodes[i];
      index_.insert(coord_key(node.level, node.coords[0], node.coords[1], node.coords[2]),
                    static_cast<std::uint32_t>(i));
    }
    // Leaves from the lattice, then parents bottom-up (each level's nodes
    // only read the level below).
    tbb::parallel_for(level_offset_[D], level_offset_[D + 1], [&](std::size_t i) {
      McNode& leaf = t_.nodes[i];
      auto base = lat.index(leaf.coords[0] - lat.offset[0], leaf.coords[1] - lat.offset[1],
                            leaf.coords[2] - lat.offset[2]);
      for (int c = 0; c < 8; ++c)
        if (lat.inside(base + (c & 1) * step[0] + (c >> 1 & 1) * step[1] + (c >> 2) * step[2]))
          leaf.signs27 |= 1u << detail::corner_point(c);
    });
    // Each crossed lattice edge is an edge of the (up to) four cells around
    // it (and each edge of a leaf is one lattice edge: no two writes meet).
    tbb::parallel_for(std::size_t{0}, edge_keys.size(), [&](std::size_t v) {
      lat.for_each_cell_around(
          edge_keys[v], [&](int edge, std::int64_t x, std::int64_t y, std::int64_t z) {
            t_.nodes[find(D, x, y, z)].edge_vertex[edge] = static_cast<std::uint32_t>(v);
          });
    });
    // Progress: the nodes made, level by level (the leaves' quadrics with
    // the leaves).
    ProgressCounter nodes_done(progress_, "tree", t_.nodes.size(), 1);
    if (place_coarse_) surface_quadrics(D);
    nodes_done.add(level_offset_[D + 1] - level_offset_[D]);
    for (int l = D - 1; l >= 0; --l) {
      tbb::parallel_for(level_offset_[l], level_offset_[l + 1],
                        [&](std::size_t i) { make_parent(t_.nodes[i]); });
      if (place_coarse_) level_vertices(l);
      nodes_done.add(level_offset_[l + 1] - level_offset_[l]);
    }
  }

  // Coarse levels' own vertices. A coarse cell's edge point is a finest
  // crossing, on the surface, so its triangles are chords on one side of a
  // curved surface; quadric collapse would place the point off the surface
  // so that the triangles straddle it. Each level's edge points therefore
  // are vertices of their own (a copy of the finest crossing the rescaled
  // ratio picks, one per level and edge: every cell that uses a level-l
  // edge uses the same copy, and a split face or halved edge uses the
  // children's, so no crack opens), moved along their normal to the
  // minimum of the quadric of the finest surface in the cells around the
  // edge, at most a quarter of the level's cell size. The finest level's
  // points stay where they are.
  struct SurfaceQuadric {
    double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0;
    void add(const SurfaceQuadric& o) {
      a00 += o.a00, a01 += o.a01, a02 += o.a02, a11 += o.a11, a12 += o.a12, a22 += o.a22;
      b0 += o.b0, b1 += o.b1, b2 += o.b2;
    }
  };
  // Per node: the area-weighted plane quadric of the finest triangles in it.
  // Leaves' quadrics are summed into their parents as they are made, and
  // only internal nodes keep one (a quarter of the nodes).
  void surface_quadrics(int D) {
    node_q_.assign(level_offset_[D], SurfaceQuadric{});
    auto leaf_quadric = [&](const McNode& leaf, SurfaceQuadric& q) {
      detail::triangulate_node(
          t_, leaf, 0, 0,
          [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
            if (a == McNode::kNone || b == McNode::kNone || c == McNode::kNone) return;
            const Vec3 &pa = t_.positions[a], &pb = t_.positions[b], &pc = t_.positions[c];
            Vec3 n = cross(pb - pa, pc - pa);
            double len = length(n);
            if (!(len > 0)) return;
            double nx = n.x / len, ny = n.y / len, nz = n.z / len, w = 0.5 * len;
            double d = -(nx * pa.x + ny * pa.y + nz * pa.z);
            q.a00 += w * nx * nx, q.a01 += w * nx * ny, q.a02 += w * nx * nz;
            q.a11 += w * ny * ny, q.a12 += w * ny * nz, q.a22 += w * nz * nz;
            q.b0 += w * nx * d, q.b1 += w * ny * d, q.b2 += w * nz * d;
          },
          [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
    };
    for (int l = D - 1; l >= 0; --l)
      tbb::parallel_for(level_offset_[l], level_offset_[l + 1], [&](std::size_t i) {
        for (int o = 0; o < 8; ++o)
          if (std::uint32_t ci = t_.nodes[i].child(o); ci != McNode::kNone) {
            if (ci >= level_offset_[D])
              leaf_quadric(t_.nodes[ci], node_q_[i]);
            else
              node_q_[i].add(node_q_[ci]);
          }
      });
  }
  // Level l's nodes take level copies of the edge points make_parent gave
  // them (serial, in node order: the copies' numbering and quadric sums do
  // not depend on the threads).
  static constexpr double kMinMove = 0.05;
  void level_vertices(int l) {
    // The quadric around each level edge: the sum over the nodes sharing it.
    std::vector<std::uint32_t> entry(t_.positions.size(), McNode::kNone);
    std::vector<std::uint32_t> sources;
    std::vector<SurfaceQuadric> around;
    for (std::size_t i = level_offset_[l]; i < level_offset_[l + 1]; ++i)
      for (auto v : t_.nodes[i].edge_vertex) {
        if (v == McNode::kNone) continue;
        if (entry[v] == McNode::kNone) {
          entry[v] = static_cast<std::uint32_t>(sources.size());
          sources.push_back(v);
          around.emplace_back();
        }
        around[entry[v]].add(node_q_[i]);
      }
    // Where the placement moves a point by less than kMinMove finest cells,
    // the level keeps the finer level's vertex: a split next to it then
    // changes none of the cell's triangles (no new interval in the run-time
    // model) and the vertex table does not grow.
    const double limit = 0.25 * t_.cell_size * static_cast<double>(1u << (t_.depth - l));
    // Moves from the finest crossing (a finer level's vertex may have moved).
    std::vector<float> move(sources.size(), 0);
    tbb::parallel_for(std::size_t{0}, sources.size(), [&](std::size_t k) {
      const SurfaceQuadric& q = around[k];
      const Vec3 p = t_.positions[finest_of(sources[k])], n = t_.normals[sources[k]];
      const double an0 = q.a00 * n.x + q.a01 * n.y + q.a02 * n.z;
      const double an1 = q.a01 * n.x + q.a11 * n.y + q.a12 * n.z;
      const double an2 = q.a02 * n.x + q.a12 * n.y + q.a22 * n.z;
      const double nan = n.x * an0 + n.y * an1 + n.z * an2;
      if (!(nan > 0)) return;
      // d/dt Q(p + t n) = 2 (n.(A p + b) + t n.A n) = 0.
      const double slope = an0 * p.x + an1 * p.y + an2 * p.z + q.b0 * n.x + q.b1 * n.y + q.b2 * n.z;
      move[k] = static_cast<float>(std::clamp(-slope / nan, -limit, limit));
    });
    std::vector<std::uint32_t> target(sources);
    for (std::size_t k = 0; k < sources.size(); ++k) {
      const std::uint32_t v = sources[k], f = finest_of(v);
      const Vec3 x = t_.positions[f] + t_.normals[v] * move[k];
      if (!(length(x - t_.positions[v]) >= kMinMove * t_.cell_size)) continue;
      target[k] = static_cast<std::uint32_t>(t_.positions.size());
      t_.positions.push_back(x);
      t_.normals.push_back(t_.normals[v]);
      if (!t_.colors.empty()) t_.colors.push_back(t_.colors[v]);
      gap_.push_back(gap_[v]);
      finest_.push_back(f);
    }
    for (std::size_t i = level_offset_[l]; i < level_offset_[l + 1]; ++i)
      for (auto& v : t_.nodes[i].edge_vertex)
        if (v != McNode::kNone) v = target[entry[v]];
    if (l == 0) node_q_ = {};
  }

  // Holes of an open input. A node with a surface point (its own or, where
  // a neighbour splits it, a child's on its boundary) farther from the
  // input than the node's own cell edge lies on a cap over a hole and is a
  // hole; so is a coarse node next to a rim one of whose triangles spans a
  // hole between points on its rim (gap(x) at the triangle's centroid), and
  // a cell of the two finest levels most of whose points are invented
  // (farther than a finest cell: coarser cells keep their real surface and
  // cap at most their own size, rather than drop the real part). Its
  // corner signs are cleared after all parents are made, so that it has no
  // triangles at any budget; its neighbours keep theirs, so the model has a
  // border where the input has one, within about a cell of the node's level.
  // Only the node's own triangulation reads its signs (a parent's come from
  // the true signs, and split faces take their points from the children).
  template <class GapAt>
  void mark_holes(GapAt&& gap_at) {
    std::vector<std::uint8_t> hole(t_.nodes.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, t_.nodes.size(), 64), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const McNode& node = t_.nodes[i];
        float size = t_.cell_size * static_cast<float>(1u << (t_.depth - node.level)), worst = 0;
        bool rim = false;
        int points = 0, made_up = 0;
        // Every point the node's triangulation may use: its edge points and,
        // where neighbours split its faces, its children's on its boundary.
        auto visit = [&](std::uint32_t v) {
          if (v == McNode::kNone) return;
          worst = std::max(worst, gap_[v].gap), rim |= gap_[v].rim;
          ++points, made_up += gap_[v].gap > t_.cell_size;
        };
        for (auto v : node.edge_vertex) visit(v);
        if (!node.leaf())
          for (int slot = 0; slot < detail::kSlotCount; ++slot)
            visit(detail::slot_vertex(t_, node, slot, 0xfff));
        if (2 * made_up > points && node.level + 1 >= t_.depth) worst = INFINITY;
        if (worst <= size && rim && !node.leaf())
          detail::triangulate_node(
              t_, node, 0, 0,
              [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
                if (worst <= size)
                  worst = std::max(
                      worst,
                      gap_at((t_.positions[a] + t_.positions[b] + t_.positions[c]) * (1.0f / 3)));
              },
              [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
        hole[i] = worst > size;
      }
    });
    for (std::size_t i = 0; i < hole.size(); ++i)
      if (hole[i]) t_.nodes[i].signs27 = 0, ++stats_.hole_nodes;
  }

  void make_parent(McNode& node) {
    std::uint32_t signs = 0, known = 0;
    for (int o = 0; o < 8; ++o) {
      std::uint32_t ci = node.child(o);
      if (ci == McNode::kNone) continue;
      const McNode& ch = t_.nodes[ci];
      for (int c = 0; c < 8; ++c) {
        int p = detail::lattice_point((o & 1) + (c & 1), (o >> 1 & 1) + (c >> 1 & 1),
                                      (o >> 2) + (c >> 2));
        known |= 1u << p;
        if (ch.signs27 >> detail::corner_point(c) & 1) signs |= 1u << p;
      }
    }
    node.signs27 = fill_unknown(signs, known);
    // Per edge: the lattice points of its ends.
    static const std::array<std::array<int, 2>, 12> ends = [] {
      std::array<std::array<int, 2>, 12> p{};
      for (int e = 0; e < 12; ++e) {
        auto [lo, hi] = detail::edge_corners(e);
        p[e] = {detail::corner_point(lo), detail::corner_point(hi)};
      }
      return p;
    }();
    for (int e = 0; e < 12; ++e) {
      const int plo = ends[e][0], phi = ends[e][1], pmid = (plo + phi) / 2;
      bool slo = node.signs27 >> plo & 1, shi = node.signs27 >> phi & 1,
           smid = node.signs27 >> pmid & 1;
      if (slo == shi) continue;
      int half = slo != smid ? 0 : 1;
      node.edge_vertex[e] =
          detail::slot_vertex(t_, node, 2 * e + half, static_cast<std::uint16_t>(1u << e));
    }
  }

  std::uint32_t find(int level, std::int64_t x, std::int64_t y, std::int64_t z) const {
    std::int64_t size = std::int64_t{1} << level;
    if (x < 0 || y < 0 || z < 0 || x >= size || y >= size || z >= size) return McNode::kNone;
    return index_.find(coord_key(level, x, y, z));
  }
  std::uint32_t neighbour(const McNode& n, int dx, int dy, int dz) const {
    return find(n.level, std::int64_t{n.coords[0]} + dx, std::int64_t{n.coords[1]} + dy,
                std::int64_t{n.coords[2]} + dz);
  }
  // The same-level node at offset (dx, dy, dz) from node i, from the table
  // of internal nodes' neighbours; kNone for a leaf's (leaves are never
  // expanded, so nothing a leaf's neighbours do splits a leaf or a cell).
  std::uint32_t near(std::uint32_t i, int dx, int dy, int dz) const {
    if (i >= internal_) return McNode::kNone;
    return near_[27 * static_cast<std::size_t>(i) + (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1)];
  }
  void make_near() {
    internal_ = static_cast<std::uint32_t>(level_offset_[t_.depth]);
    near_.resize(27 * static_cast<std::size_t>(internal_));
    tbb::parallel_for(std::uint32_t{0}, internal_, [&](std::uint32_t i) {
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            near_[27 * static_cast<std::size_t>(i) + (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1)] =
                neighbour(t_.nodes[i], dx, dy, dz);
    });
  }
  // The same-level nodes sharing face f / edge e with node i.
  template <class Fn>
  void face_neighbour(std::uint32_t i, int f, Fn&& fn) const {
    fn(i < internal_ ? near_[27 * static_cast<std::size_t>(i) + kFaceSlot[f]] : McNode::kNone);
  }
  template <class Fn>
  void edge_neighbours(std::uint32_t i, int e, Fn&& fn) const {
    if (i >= internal_) {
      for (int k = 0; k < 3; ++k) fn(McNode::kNone);
      return;
    }
    const std::uint32_t* row = &near_[27 * static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) fn(row[kEdgeSlots[e][k]]);
  }
  // Slots (dx + 1) + 3 (dy + 1) + 9 (dz + 1) of the neighbour table: across
  // face f, and around edge e = 4a + b (offsets on a + 1 and a + 2 by b's
  // bits: one, the other, both).
  static constexpr std::array<std::uint8_t, 6> kFaceSlot = [] {
    std::array<std::uint8_t, 6> slot{};
    for (int f = 0; f < 6; ++f) {
      int d[3] = {0, 0, 0};
      d[f / 2] = f % 2 ? 1 : -1;
      slot[f] = static_cast<std::uint8_t>((d[0] + 1) + 3 * (d[1] + 1) + 9 * (d[2] + 1));
    }
    return slot;
  }();
  static constexpr std::array<std::array<std::uint8_t, 3>, 12> kEdgeSlots = [] {
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
  std::pair<std::uint16_t, std::uint8_t> context(std::uint32_t i) const {
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
  int count_now(std::uint32_t i) {
    auto [halved, split] = context(i);
    const McNode& n = t_.nodes[i];
    if (!halved && !split) return detail::node_triangle_count(n, 0, 0);
    // A halved edge or split face without a sign change on it changes
    // nothing (polygonize_cell contours only crossings): left out of the key,
    // so that more configurations share a count.
    static const auto masks = [] {
      std::array<std::uint32_t, 18> m{};  // 12 edges' 3 points, 6 faces' 9
      for (int e = 0; e < 12; ++e) {
        auto [lo, hi] = detail::edge_corners(e);
        int plo = detail::corner_point(lo), phi = detail::corner_point(hi);
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
      for (int c = 0; c < 8; ++c) m |= 1u << detail::corner_point(c);
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
    int c = detail::node_triangle_count(n, halved, split);
    if (counts_.size() < counts_.capacity() / 2) counts_.insert(key, static_cast<std::uint32_t>(c));
    return c;
  }
  double own_area(const McNode& n) const {
    double area = 0;
    detail::triangulate_node(
        t_, n, 0, 0,
        [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
          area += 0.5 * length(cross(t_.positions[b] - t_.positions[a],
                                     t_.positions[c] - t_.positions[a]));
        },
        [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
    return area;
  }
  // The coarsest unexpanded cut cell touching n that is coarser than n, or kNone.
  // The first level up is read from the parent's neighbour table (the cell
  // one level coarser around n is the parent or one of its neighbours).
  std::uint32_t blocker(std::uint32_t i) const {
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

  // The thesis's metric (SPEC §5): |area of the children's triangulation -
  // area of the node's own|, raised to a descendant's where that hides detail.
  std::vector<float> area_metric() const {
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
    // the parent's area) keep the thesis's order. 0.2 measured on the bunny:
    // 0 (always) is better at 5-20 % but worse at 60-80 % and coarsens the
    // budget steps of small models.
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
  std::vector<float> distance_metric() const {
    const std::vector<double> distance = detail::node_distance_sums(t_);
    std::vector<float> metric(distance.begin(), distance.end());
    for (std::size_t i = metric.size(); i-- > 0;) {
      const McNode& n = t_.nodes[i];
      for (int o = 0; o < 8; ++o)
        if (auto c = n.child(o); c != McNode::kNone && !t_.nodes[c].leaf())
          metric[i] = std::max(metric[i], metric[c]);
    }
    return metric;
  }

  void number(McPriorityMetric which) {
    const auto count = static_cast<std::uint32_t>(t_.nodes.size());
    make_near();
    parent_.assign(count, McNode::kNone);
    for (std::uint32_t i = 0; i < internal_; ++i)
      for (int o = 0; o < 8; ++o)
        if (auto c = t_.nodes[i].child(o); c != McNode::kNone) parent_[c] = i;
    counts_.reserve(count);
    expanded_.assign(count, 0);
    std::vector<float> metric =
        which == McPriorityMetric::kArea ? area_metric() : distance_metric();
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
        // expanded as early as the detail it holds back needs): without
        // this, detail next to a flat coarse cell waits for the flat cell's
        // own turn near the end (the bunny's bottom rim: 4.7 cells off at
        // 20 %, Hausdorff 2.9 % of the diagonal instead of 1.1 %).
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
    // Split priorities for extraction.
    tbb::parallel_for(std::uint32_t{0}, count, [&](std::uint32_t i) {
      McNode& n = t_.nodes[i];
      for (int f = 0; f < 6; ++f) {
        n.face_split[f] = McNode::kNone;
        face_neighbour(i, f, [&](std::uint32_t m) {
          if (m != McNode::kNone) n.face_split[f] = std::min(n.face_split[f], t_.nodes[m].priority);
        });
      }
      for (int e = 0; e < 12; ++e) {
        n.edge_split[e] = McNode::kNone;
        edge_neighbours(i, e, [&](std::uint32_t m) {
          if (m != McNode::kNone) n.edge_split[e] = std::min(n.edge_split[e], t_.nodes[m].priority);
        });
      }
    });
  }

 private:
  McOctree& t_;
  McBuildStats& stats_;
  bool place_coarse_;
  const ProgressCallback& progress_;
  std::vector<std::size_t> level_offset_;
  NodeIndex index_;
  std::vector<std::uint8_t> expanded_;
  NodeIndex counts_;  // see count_now
  std::vector<std::uint32_t> parent_;
  std::vector<Gap> gap_;                // per vertex
  std::vector<SurfaceQuadric> node_q_;  // per node, while the tree is built
  std::size_t finest_count_ = 0;        // vertices [0, finest_count_) are finest crossings
  std::vector<std::uint32_t> finest_;   // per later (level) vertex: its finest crossing
  std::uint32_t finest_of(std::uint32_t v) const {
    return v < finest_count_ ? v : finest_[v - finest_count_];
  }
  std::uint32_t internal_ = 0;       // nodes [0, internal_) are internal, the rest leaves
  std::vector<std::uint32_t> near_;  // 27 per internal node: its same-level neighbours
};

// The resolution at which the full-resolution model has about as many
// triangles as the input: marching cubes make about kTrianglesPerCellFace
// triangles per h x h of surface (2.9 measured on the bunny, a sphere and a
// torus), so h = sqrt(kTrianglesPerCellFace x area / triangles).
constexpr double kTrianglesPerCellFace = 2.9;
int mesh_resolution(const TriangleMesh& m) {
  double area = 0;
  for (const auto& f : m.triangles)
    area += 0.5 * length(cross(m.positions[f[1]] - m.positions[f[0]],
                               m.positions[f[2]] - m.positions[f[0]]));
  Vec3 size = m.bounds().size();
  double extent = std::max({size.x, size.y, size.z});
  double h = std::sqrt(kTrianglesPerCellFace * area / static_cast<double>(m.triangles.size()));
  if (!(h > 0)) return 2;
  return static_cast<int>(std::clamp(std::lround(extent / h), 2L, 1000L));
}

// Range scans: cells twice the median point spacing (Kim sec. 4.4: finer
// cells leave holes between the range points).
int scan_resolution(const std::vector<RangeScan>& scans, const Box3& bounds) {
  std::vector<float> spacing;
  for (const auto& s : scans)
    if (float d = s.spacing(); d > 0) spacing.push_back(d);
  if (spacing.empty()) return 64;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  Vec3 size = bounds.size();
  double extent = std::max({size.x, size.y, size.z});
  // Clamped before rounding: a stray point far from its row can make the
  // ratio huge.
  const double cells = extent / (2.0 * spacing[spacing.size() / 2]);
  return cells >= 2 ? static_cast<int>(std::lround(std::min(cells, 1000.0))) : 2;
}

// The options both builders share: throws std::invalid_argument for a
// resolution out of range; the returned object (null for all cores) limits
// TBB's threads while it lives.
std::unique_ptr<tbb::global_control> checked_thread_limit(const McBuildOptions& options) {
  if (options.resolution != 0 && (options.resolution < 2 || options.resolution > 1000))
    throw std::invalid_argument("mcoctree: resolution must be 0 or in 2..1000");
  if (options.threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(options.threads));
}

void check_build_budget(const Box3& box, int resolution, const McBuildOptions& options) {
  check_memory_budget(mc_build_bytes(box, resolution), options.max_memory,
                      fmt::format("mcoctree: the lattice at resolution {}", resolution),
                      "use a lower resolution");
}

}  // namespace

double mc_build_bytes(const Box3& box, int resolution) {
  constexpr double kBytesPerPoint = 5;
  const Vec3 size = box.size();
  const double extent = std::max({size.x, size.y, size.z});
  if (!(extent > 0) || resolution <= 0) return 0;
  double points = 1;
  for (int a = 0; a < 3; ++a) points *= double(size[a]) / extent * resolution + 3;
  return kBytesPerPoint * points;
}

McBuildResult build_mc_octree(const TriangleMesh& mesh, const McBuildOptions& options) {
  auto limit = checked_thread_limit(options);
  if (mesh.triangles.empty()) throw DataError("mcoctree: the mesh has no triangles");
  check_coordinate_range(mesh, "mcoctree: the mesh");
  McBuildResult result;
  auto t0 = Clock::now();
  // Pseudo-normals need shared vertices: weld exact duplicates (OBJ seams, STL soup).
  TriangleMesh source;
  source.positions = mesh.positions;
  source.triangles = mesh.triangles;
  source.colors = mesh.colors;
  // Inside is where the triangles face away from: a mesh wound inwards
  // (negative signed volume: horse.ply) is turned round, or every sign would
  // be the wrong way and the root cube's boundary, outside, would fight it.
  TriangleMesh welded = weld(source).mesh;
  double volume = 0;
  for (const auto& f : welded.triangles)
    volume += dot(welded.positions[f[0]], cross(welded.positions[f[1]], welded.positions[f[2]]));
  if (volume < 0)
    for (auto& f : welded.triangles) std::swap(f[1], f[2]);
  SignedDistance sd(std::move(welded));
  if (sd.mesh().triangles.empty())
    throw DataError("mcoctree: the mesh has only degenerate triangles");
  result.stats.resolution = options.resolution ? options.resolution : mesh_resolution(sd.mesh());
  // An open mesh's repairs and holes need the hierarchy: build it on another
  // worker while the triangle scan runs. (Safe while TriangleTree's build
  // runs no TBB tasks: a thread waiting inside it could steal a task that
  // calls bvh() and re-enter the call_once.)
  tbb::task_group hierarchy;
  if (sd.has_rims()) hierarchy.run([&] { sd.bvh(); });
  check_build_budget(sd.mesh().bounds(), result.stats.resolution, options);
  Lattice lat = make_lattice(sd, result.stats.resolution, result.stats, options.progress);
  hierarchy.wait();
  result.stats.seconds_signs = since(t0);
  auto t1 = Clock::now();
  Builder builder(result.tree, result.stats, options.place_coarse_vertices, options.progress);
  // Closed inputs invent nothing (every sign change is a crossing of the
  // surface); not testing them keeps them closed whatever the rounding.
  const bool holes = options.holes == McHoles::kOpen && sd.has_rims();
  auto gap = [&](const ClosestPoint& cp) {
    float d = std::sqrt(cp.distance_squared);
    bool rim = sd.feature(cp).second;
    return Gap{rim ? d / kRimGap : d, rim};
  };
  builder.build_tree(
      lat, sd.mesh().has_colors(),
      [&](const Vec3& x, std::uint32_t& hint, const std::array<std::uint32_t, 2>& near,
          Vec3& normal, Rgb8* color) {
        // The nearer of the triangles closest to the edge's
        // ends: the closest point, or near it, which is all
        // a normal and a colour need; the exact one where
        // the distance may decide a hole (the nearer
        // triangle's distance is an upper bound).
        ClosestPoint cp;
        for (auto t : near)
          if (t != ClosestPoint::kNone) {
            ClosestPoint c = sd.on_triangle(x, t);
            if (c.distance_squared < cp.distance_squared) cp = c;
          }
        const float sure = kRimGap * lat.h;
        if (!cp.found() || (holes && (cp.distance_squared > sure * sure || sd.feature(cp).second)))
          cp = sd.bvh().closest_point(x, cp.found() ? cp.triangle : hint);
        hint = cp.triangle;
        normal = sd.normal_at(cp);
        if (color) {
          const auto& f = sd.mesh().triangles[cp.triangle];
          Vec3 col{};
          for (int k = 0; k < 3; ++k) col += sd.mesh().colors[f[k]] * cp.barycentric[k];
          for (int k = 0; k < 3; ++k)
            (*color)[k] =
                static_cast<std::uint8_t>(std::lround(std::clamp(col[k], 0.0f, 1.0f) * 255.0f));
        }
        return holes ? gap(cp) : Gap{};
      });
  result.stats.seconds_tree = since(t1);
  auto t2 = Clock::now();
  if (holes) builder.mark_holes([&](const Vec3& x) { return gap(sd.bvh().closest_point(x)).gap; });
  builder.number(options.metric);
  result.stats.seconds_priorities = since(t2);
  return result;
}

McBuildResult build_mc_octree(const std::vector<RangeScan>& scans, const McBuildOptions& options) {
  auto limit = checked_thread_limit(options);
  if (scans.empty()) throw DataError("mcoctree: no range scans");
  for (const auto& s : scans) {
    std::vector<Vec3> world;
    world.reserve(s.points.size());
    for (const auto& p : s.points) world.push_back(s.to_world(p));
    check_coordinate_range(world, s.name);
  }
  McBuildResult result;
  auto t0 = Clock::now();
  ScanField field(scans);
  result.stats.resolution =
      options.resolution ? options.resolution : scan_resolution(scans, field.bounds());
  check_build_budget(field.bounds(), result.stats.resolution, options);
  Lattice lat =
      make_scan_lattice(field, scans, result.stats.resolution, result.stats, options.progress);
  result.stats.seconds_signs = since(t0);
  auto t1 = Clock::now();
  Builder builder(result.tree, result.stats, options.place_coarse_vertices, options.progress);
  builder.build_tree(lat, field.colored(),
                     [&](const Vec3& x, std::uint32_t&, const std::array<std::uint32_t, 2>&,
                         Vec3& normal, Rgb8* color) {
                       auto e = field.estimate(x, 2);
                       if (!e.found) e = field.estimate(x, 4);
                       if (!e.found) return Gap{};  // a cap far from the data: the edge's direction
                       normal = e.normal;
                       if (color)
                         for (int k = 0; k < 3; ++k)
                           (*color)[k] = static_cast<std::uint8_t>(
                               std::lround(std::clamp(e.color[k], 0.0f, 255.0f)));
                       return Gap{};
                     });
  result.stats.seconds_tree = since(t1);
  auto t2 = Clock::now();
  builder.number(options.metric);
  result.stats.seconds_priorities = since(t2);
  return result;
}

std::size_t McOctree::memory_bytes() const {
  return positions.size() * sizeof(Vec3) + normals.size() * sizeof(Vec3) +
         colors.size() * sizeof(Rgb8) + nodes.size() * sizeof(McNode) +
         lod.size() * sizeof(std::uint32_t) + accumulated.size() * sizeof(std::uint64_t);
}

}  // namespace lodforge
