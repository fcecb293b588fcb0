// The marching-cube octree from its sign lattice (Kim, "Level-of-detail mesh
// modeling using the marching cube octree", ch. 5): leaves are marching
// cubes (corner signs and edge ratios from signed distances), parents are
// made bottom-up by the four-case corner rule with re-scaled ratios. Choices
// where the thesis is vague:
//
//   * parents: with a sign at every lattice point, case 1 of the corner rule
//     (the corresponding child corner) applies whenever that child exists; a
//     pruned (empty) child has one sign at all its corners, so cases 2-4 read
//     the same sign from its neighbours. Hence the sign of a lattice point is
//     the same at every level, which the crack-free triangulation relies on.
//   * ratios: the parent's point on an edge is the child's point on the half
//     whose ends differ in sign (Fig. 5.2: a/2(a+b) and (2a+b)/2(a+b)); the
//     point is stored once and both nodes refer to it.
#include "lodforge/mcoctree/octree_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "lodforge/core/error.h"
#include "lodforge/core/morton.h"
#include "lodforge/core/radix_sort.h"
#include "lodforge/mcoctree/cell_mesh.h"

namespace lodforge::detail {
namespace {

// A level's edge point keeps the finer level's vertex when the placement
// moves it by less than this many finest cells (see level_vertices).
constexpr double kMinMove = 0.05;

// The crossed lattice edges: one per finest lattice edge whose ends differ
// in sign, as point index * 3 + axis, ascending.
std::vector<std::int64_t> crossed_edges(const Lattice& lat) {
  const std::int64_t nx = lat.dim[0], ny = lat.dim[1], nz = lat.dim[2];
  const std::int64_t step[3] = {1, nx, lat.plane()};
  return collect_by_layer(0, nz, [&](std::int64_t k, std::vector<std::int64_t>& out) {
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

// Calls fn(a, b, c) for each triangle of node's own triangulation (no
// neighbour split), as vertex indices.
template <class Fn>
void own_triangles(const McOctree& t, const McNode& node, Fn&& fn) {
  triangulate_node(t, node, 0, 0, fn,
                   [](const std::uint8_t*, int, std::uint16_t) { return McNode::kNone; });
}

}  // namespace

void OctreeBuilder::build_tree(const Lattice& lat, bool colored, const EdgePointAttributes& attr) {
  t_.depth = lat.depth;
  t_.origin = lat.root;
  t_.cell_size = lat.h;
  const std::vector<std::int64_t> edge_keys = crossed_edges(lat);
  if (edge_keys.empty())
    throw DataError("mcoctree: the surface crosses no lattice edge (resolution too low?)");
  place_edge_points(lat, edge_keys, colored, attr);
  make_nodes(lat, edge_keys);
  make_leaves(lat, edge_keys);
  make_parents();
}

// Vertices: one per crossed lattice edge, where the signed distances at its
// ends interpolate to zero (the middle where one end has none).
void OctreeBuilder::place_edge_points(const Lattice& lat,
                                      const std::vector<std::int64_t>& edge_keys, bool colored,
                                      const EdgePointAttributes& attr) {
  const std::int64_t step[3] = {1, lat.dim[0], lat.plane()};
  t_.positions.resize(edge_keys.size());
  t_.normals.resize(edge_keys.size());
  if (colored) t_.colors.resize(edge_keys.size());
  gap_.assign(edge_keys.size(), Gap{});
  finest_count_ = edge_keys.size();
  ProgressCounter points(progress_, "surface points", edge_keys.size());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, edge_keys.size(), 256),
      [&](const tbb::blocked_range<std::size_t>& r) {
        std::uint32_t hint = kNone;
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
          std::array<std::uint32_t, 2> near{dp ? dp->triangle : kNone, dq ? dq->triangle : kNone};
          gap_[v] = attr(x, hint, near, t_.normals[v], colored ? &t_.colors[v] : nullptr);
        }
        points.add(r.size());
      });
}

// The nodes: leaves are the finest cells whose corners differ in sign, i.e.
// the (up to) four cells around each crossed lattice edge; each level above
// holds the parents of the level below. Nodes are stored level by level,
// each level in Morton order, with their coordinates, child links and the
// (level, coordinates) index.
void OctreeBuilder::make_nodes(const Lattice& lat, const std::vector<std::int64_t>& edge_keys) {
  const int D = lat.depth;
  std::vector<std::vector<std::uint64_t>> codes(D + 1);
  for (auto key : edge_keys)
    lat.for_each_cell_around(key, [&](int, std::int64_t x, std::int64_t y, std::int64_t z) {
      codes[D].push_back(morton_code(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                                     static_cast<std::uint32_t>(z)));
    });
  std::vector<std::uint64_t> scratch(codes[D].size());
  radix_sort(codes[D], scratch, 0, 3 * D);  // codes are below 2^(3 D)
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
}

// The leaves' corner signs from the lattice and their edge points.
void OctreeBuilder::make_leaves(const Lattice& lat, const std::vector<std::int64_t>& edge_keys) {
  const int D = lat.depth;
  const std::int64_t step[3] = {1, lat.dim[0], lat.plane()};
  tbb::parallel_for(level_offset_[D], level_offset_[D + 1], [&](std::size_t i) {
    McNode& leaf = t_.nodes[i];
    auto base = lat.index(leaf.coords[0] - lat.offset[0], leaf.coords[1] - lat.offset[1],
                          leaf.coords[2] - lat.offset[2]);
    for (int c = 0; c < 8; ++c)
      if (lat.inside(base + (c & 1) * step[0] + (c >> 1 & 1) * step[1] + (c >> 2) * step[2]))
        leaf.signs27 |= 1u << corner_point(c);
  });
  // Each crossed lattice edge is an edge of the (up to) four cells around
  // it (and each edge of a leaf is one lattice edge: no two writes meet).
  tbb::parallel_for(std::size_t{0}, edge_keys.size(), [&](std::size_t v) {
    lat.for_each_cell_around(
        edge_keys[v], [&](int edge, std::int64_t x, std::int64_t y, std::int64_t z) {
          t_.nodes[find(D, x, y, z)].edge_vertex[edge] = static_cast<std::uint32_t>(v);
        });
  });
}

// Parents bottom-up (each level's nodes only read the level below), with the
// coarse levels' own vertices when they are placed. Progress: the nodes made,
// level by level (the leaves' quadrics with the leaves).
void OctreeBuilder::make_parents() {
  const int D = t_.depth;
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
// curved surface; quadric collapse would place the point off the surface so
// that the triangles straddle it. Each level's edge points therefore are
// vertices of their own (a copy of the finest crossing the rescaled ratio
// picks, one per level and edge: every cell that uses a level-l edge uses the
// same copy, and a split face or halved edge uses the children's, so no
// crack opens), moved along their normal to the minimum of the quadric of the
// finest surface in the cells around the edge (Garland & Heckbert's quadric;
// its constant term does not take part), at most a quarter of the level's
// cell size. The finest level's points stay where they are.
//
// Per node: the area-weighted plane quadric of the finest triangles in it.
// Leaves' quadrics are summed into their parents as they are made, and only
// internal nodes keep one (a quarter of the nodes).
void OctreeBuilder::surface_quadrics(int D) {
  node_q_.assign(level_offset_[D], Quadric{});
  auto leaf_quadric = [&](const McNode& leaf, Quadric& q) {
    own_triangles(t_, leaf, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (a == McNode::kNone || b == McNode::kNone || c == McNode::kNone) return;
      const Vec3 &pa = t_.positions[a], &pb = t_.positions[b], &pc = t_.positions[c];
      Vec3 n = cross(pb - pa, pc - pa);
      double len = length(n);
      if (!(len > 0)) return;
      double nx = n.x / len, ny = n.y / len, nz = n.z / len, w = 0.5 * len;
      double d = -(nx * pa.x + ny * pa.y + nz * pa.z);
      q.add_plane(nx, ny, nz, d, w);
    });
  };
  for (int l = D - 1; l >= 0; --l)
    tbb::parallel_for(level_offset_[l], level_offset_[l + 1], [&](std::size_t i) {
      for (int o = 0; o < 8; ++o)
        if (std::uint32_t ci = t_.nodes[i].child(o); ci != McNode::kNone) {
          if (ci >= level_offset_[D])
            leaf_quadric(t_.nodes[ci], node_q_[i]);
          else
            node_q_[i] += node_q_[ci];
        }
    });
}

// Level l's nodes take level copies of the edge points make_parent gave them
// (serial, in node order: the copies' numbering and quadric sums do not
// depend on the threads).
void OctreeBuilder::level_vertices(int l) {
  // The quadric around each level edge: the sum over the nodes sharing it.
  std::vector<std::uint32_t> entry(t_.positions.size(), McNode::kNone);
  std::vector<std::uint32_t> sources;
  std::vector<Quadric> around;
  for (std::size_t i = level_offset_[l]; i < level_offset_[l + 1]; ++i)
    for (auto v : t_.nodes[i].edge_vertex) {
      if (v == McNode::kNone) continue;
      if (entry[v] == McNode::kNone) {
        entry[v] = static_cast<std::uint32_t>(sources.size());
        sources.push_back(v);
        around.push_back(Quadric{});
      }
      around[entry[v]] += node_q_[i];
    }
  // Where the placement moves a point by less than kMinMove finest cells,
  // the level keeps the finer level's vertex: a split next to it then
  // changes none of the cell's triangles (no new interval in the run-time
  // model) and the vertex table does not grow.
  const double limit = 0.25 * t_.cell_size * static_cast<double>(1u << (t_.depth - l));
  // Moves from the finest crossing (a finer level's vertex may have moved).
  std::vector<float> move(sources.size(), 0);
  tbb::parallel_for(std::size_t{0}, sources.size(), [&](std::size_t k) {
    const Quadric& q = around[k];
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

// A parent's signs by the four-case corner rule from its children's, and
// its edge points from the children's on the half of each edge whose ends
// differ in sign.
void OctreeBuilder::make_parent(McNode& node) {
  std::uint32_t signs = 0, known = 0;
  for (int o = 0; o < 8; ++o) {
    std::uint32_t ci = node.child(o);
    if (ci == McNode::kNone) continue;
    const McNode& ch = t_.nodes[ci];
    for (int c = 0; c < 8; ++c) {
      int p = lattice_point((o & 1) + (c & 1), (o >> 1 & 1) + (c >> 1 & 1), (o >> 2) + (c >> 2));
      known |= 1u << p;
      if (ch.signs27 >> corner_point(c) & 1) signs |= 1u << p;
    }
  }
  node.signs27 = fill_unknown(signs, known);
  // Per edge: the lattice points of its ends.
  static const std::array<std::array<int, 2>, 12> ends = [] {
    std::array<std::array<int, 2>, 12> p{};
    for (int e = 0; e < 12; ++e) {
      auto [lo, hi] = edge_corners(e);
      p[e] = {corner_point(lo), corner_point(hi)};
    }
    return p;
  }();
  for (int e = 0; e < 12; ++e) {
    const int plo = ends[e][0], phi = ends[e][1], pmid = (plo + phi) / 2;
    bool slo = node.signs27 >> plo & 1, shi = node.signs27 >> phi & 1,
         smid = node.signs27 >> pmid & 1;
    if (slo == shi) continue;
    int half = slo != smid ? 0 : 1;
    node.edge_vertex[e] = slot_vertex(t_, node, 2 * e + half, static_cast<std::uint16_t>(1u << e));
  }
}

// Holes of an open input. A node with a surface point (its own or, where a
// neighbour splits it, a child's on its boundary) farther from the input than
// the node's own cell edge lies on a cap over a hole and is a hole; so is a
// coarse node next to a rim one of whose triangles spans a hole between
// points on its rim (gap_at at the triangle's centroid), and a cell of the
// two finest levels most of whose points are invented (farther than a finest
// cell: coarser cells keep their real surface and cap at most their own
// size, rather than drop the real part). Its corner signs are cleared after
// all parents are made, so that it has no triangles at any budget; its
// neighbours keep theirs, so the model has a border where the input has one,
// within about a cell of the node's level. Only the node's own triangulation
// reads its signs (a parent's come from the true signs, and split faces take
// their points from the children).
void OctreeBuilder::mark_holes(const std::function<float(const Vec3&)>& gap_at) {
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
        for (int slot = 0; slot < kSlotCount; ++slot) visit(slot_vertex(t_, node, slot, 0xfff));
      if (2 * made_up > points && node.level + 1 >= t_.depth) worst = INFINITY;
      if (worst <= size && rim && !node.leaf())
        own_triangles(t_, node, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
          if (worst <= size)
            worst = std::max(
                worst, gap_at((t_.positions[a] + t_.positions[b] + t_.positions[c]) * (1.0f / 3)));
        });
      hole[i] = worst > size;
    }
  });
  for (std::size_t i = 0; i < hole.size(); ++i)
    if (hole[i]) t_.nodes[i].signs27 = 0, ++stats_.hole_nodes;
}

}  // namespace lodforge::detail
