// Bounding volume hierarchy for closest-point queries on triangle meshes.
//
// Construction is the binned surface-area heuristic of I. Wald, "On fast
// Construction of SAH-based Bounding Volume Hierarchies", IEEE Symposium on
// Interactive Ray Tracing 2007: triangle centroids are binned along the widest axis
// and the split plane minimising
//     cost = area(left box) * #left + area(right box) * #right
// is taken. SAH is derived for ray casting, but it also suits nearest-point
// queries: it keeps boxes tight around the surface, which is what makes the
// box-distance lower bound prune well.
//
// Queries follow the branch-and-bound nearest-neighbour search of Larsen,
// Gottschalk, Lin, Manocha, "Fast proximity queries with swept sphere volumes"
// (UNC TR99-018, 1999): visit the nearer child first, keep the farther one on
// an explicit stack with its box distance, and drop every subtree whose box is
// farther than the best triangle found so far. The exact distance to a
// triangle comes from closest_point_on_triangle (Ericson's region method).
//
// The Morton build (BvhBuild::kMorton) is the LBVH of Lauterbach, Garland,
// Sengupta, Luebke, Manocha, "Fast BVH Construction on GPUs", Eurographics
// 2009: triangles sorted by the Morton code of their centroid, each node
// split where the highest bit in which its triangles' codes differ changes,
// so that a node's triangles lie in one octree cell and its children in two
// halves of it. (A complete binary tree over the Morton order, cut at fixed
// counts rather than at cell boundaries, has boxes spanning distant parts of
// the mesh.)
//
// Decision table for a node with n triangles (SAH build):
//   n <= leaf_size                         -> leaf
//   centroids all equal / depth > kMaxSah  -> split at the median index / coordinate
//   otherwise                              -> best SAH plane among the bins of the widest axis
#include "lodforge/metrics/triangle_bvh.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "lodforge/core/morton.h"
#include "lodforge/metrics/closest_point_on_triangle.h"
#include "lodforge/metrics/ray.h"

namespace lodforge {
namespace {

// Beyond this depth splits are median splits, which bounds the total depth by
// kMaxSah + log2(#F) and so the traversal stack below.
constexpr int kMaxSah = 48;
constexpr int kStackSize = 128;
constexpr int kMaxBins = 64;  // BvhOptions::bins is clamped to it
// Two triangles count as equally close (for the normal tie rule) when their
// squared distances differ by at most kTie relative plus the square of
// kTieUlps float steps at the mesh's largest coordinate: a point on a shared
// edge is 0 from one triangle and rounding noise from the other.
constexpr float kTie = 1e-5f;
constexpr float kTieUlps = 16;

float half_area(const Vec3& lo, const Vec3& hi) {
  Vec3 d = hi - lo;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

inline float box_distance_squared(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  const float dx = std::max(std::max(lo.x - p.x, p.x - hi.x), 0.f);
  const float dy = std::max(std::max(lo.y - p.y, p.y - hi.y), 0.f);
  const float dz = std::max(std::max(lo.z - p.z, p.z - hi.z), 0.f);
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

TriangleBvh::TriangleBvh(const TriangleMesh& mesh, const BvhOptions& options)
    : mesh_(&mesh), options_(options) {
  options_.leaf_size = std::clamp(options_.leaf_size, 1, 32);
  options_.bins = std::clamp(options_.bins, 2, kMaxBins);
  const auto& p = mesh.positions;
  std::size_t n = mesh.triangles.size();
  face_normals_.resize(n);
  std::vector<Vec3> centroid(n), lo(n), hi(n);
  for (std::size_t f = 0; f < n; ++f) {
    const auto& t = mesh.triangles[f];
    assert(t[0] < p.size() && t[1] < p.size() && t[2] < p.size());
    const Vec3 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    face_normals_[f] = normalized(cross(b - a, c - a));
    lo[f] = min(a, min(b, c));
    hi[f] = max(a, max(b, c));
    centroid[f] = (a + b + c) * (1.f / 3);
  }
  if (n == 0) return;
  float extent = 0;
  for (std::size_t f = 0; f < n; ++f) {
    for (int k = 0; k < 3; ++k) extent = std::max({extent, std::abs(lo[f][k]), std::abs(hi[f][k])});
  }
  tie_floor_ = kTieUlps * std::numeric_limits<float>::epsilon() * extent;
  tie_floor_ *= tie_floor_;
  order_.resize(n);
  for (std::uint32_t f = 0; f < n; ++f) order_[f] = f;
  nodes_.reserve(2 * n / options_.leaf_size + 1);
  if (options_.build == BvhBuild::kMorton)
    build_morton(centroid, lo, hi);
  else
    build(0, std::uint32_t(n), 1, centroid, lo, hi);
  parent_.assign(nodes_.size(), 0);
  leaf_of_.resize(n);
  for (std::uint32_t i = 0; i < nodes_.size(); ++i) {
    const Node& node = nodes_[i];
    if (node.count) {
      for (std::uint32_t k = node.index; k < node.index + node.count; ++k) leaf_of_[k] = i;
    } else {
      parent_[i + 1] = parent_[node.index] = i;
    }
  }
  corners_.resize(n);
  slot_.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    slot_[order_[i]] = i;
    const auto& t = mesh.triangles[order_[i]];
    corners_[i] = PreparedTriangle::of(p[t[0]], p[t[1]], p[t[2]]);
  }
}

std::uint32_t TriangleBvh::build(std::uint32_t begin, std::uint32_t end, int depth,
                                 std::vector<Vec3>& centroid, std::vector<Vec3>& lo,
                                 std::vector<Vec3>& hi) {
  depth_ = std::max(depth_, depth);
  auto index = std::uint32_t(nodes_.size());
  nodes_.push_back({});
  Box3 box, cbox;
  for (std::uint32_t i = begin; i < end; ++i) {
    std::uint32_t f = order_[i];
    box.add(lo[f]);
    box.add(hi[f]);
    cbox.add(centroid[f]);
  }
  nodes_[index].lo = box.lo;
  nodes_[index].hi = box.hi;
  std::uint32_t count = end - begin;
  if (count <= std::uint32_t(options_.leaf_size)) {
    nodes_[index].index = begin;
    nodes_[index].count = count;
    return index;
  }

  std::uint32_t mid = begin + count / 2;
  Vec3 extent = cbox.size();
  int wide = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  bool split = false;
  if (depth <= kMaxSah && extent[wide] > 0) {
    // Binned SAH along the widest axis of the centroids (binning all three
    // costs three times as much to build and, measured on the bunny and its
    // levels, gave no faster queries).
    const int bins = options_.bins;
    struct Bin {
      Box3 box;
      std::uint32_t count = 0;
    };
    std::array<Bin, kMaxBins> bin{};
    const float scale = float(bins) / extent[wide];
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t f = order_[i];
      const int b = std::min(bins - 1, int((centroid[f][wide] - cbox.lo[wide]) * scale));
      bin[b].box.add(lo[f]);
      bin[b].box.add(hi[f]);
      ++bin[b].count;
    }
    // right_cost[k]: cost of bins k..bins-1 as one child.
    std::array<float, kMaxBins> right_cost{};
    Box3 acc;
    std::uint32_t n = 0;
    for (int k = bins - 1; k > 0; --k) {
      acc.add(bin[k].box);
      n += bin[k].count;
      right_cost[k] = n ? half_area(acc.lo, acc.hi) * float(n) : 0.f;
    }
    float best_cost = std::numeric_limits<float>::infinity();
    int best_plane = -1;
    acc = Box3{};
    n = 0;
    for (int k = 0; k < bins - 1; ++k) {
      acc.add(bin[k].box);
      n += bin[k].count;
      float cost = (n ? half_area(acc.lo, acc.hi) * float(n) : 0.f) + right_cost[k + 1];
      if (n > 0 && n < count && cost < best_cost) {
        best_cost = cost;
        best_plane = k + 1;
      }
    }
    if (best_plane >= 0) {
      const float origin = cbox.lo[wide];
      auto it = std::partition(order_.begin() + begin, order_.begin() + end, [&](std::uint32_t f) {
        return std::min(bins - 1, int((centroid[f][wide] - origin) * scale)) < best_plane;
      });
      mid = std::uint32_t(it - order_.begin());
      split = mid > begin && mid < end;
    }
  }
  if (!split) {
    mid = begin + count / 2;
    std::nth_element(
        order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
        [&](std::uint32_t x, std::uint32_t y) { return centroid[x][wide] < centroid[y][wide]; });
  }
  build(begin, mid, depth + 1, centroid, lo, hi);
  nodes_[index].index = build(mid, end, depth + 1, centroid, lo, hi);
  nodes_[index].count = 0;
  return index;
}

void TriangleBvh::build_morton(const std::vector<Vec3>& centroid, const std::vector<Vec3>& lo,
                               const std::vector<Vec3>& hi) {
  // Keys: the centroid's code above the triangle index, in Morton order.
  const std::vector<std::uint64_t> keyed = morton_sorted_keys(centroid);
  const auto n = std::uint32_t(centroid.size());
  for (std::uint32_t i = 0; i < n; ++i) order_[i] = std::uint32_t(keyed[i]);
  build_morton(0, n, 1, keyed, lo, hi);
}

// Node over keyed[begin, end): a leaf of at most leaf_size triangles, else
// split at the first key whose code has the highest differing bit set (all
// codes equal: halved). The depth is at most 30 code bits plus log2(#F)
// halvings, within the query's stack.
std::uint32_t TriangleBvh::build_morton(std::uint32_t begin, std::uint32_t end, int depth,
                                        const std::vector<std::uint64_t>& keyed,
                                        const std::vector<Vec3>& lo, const std::vector<Vec3>& hi) {
  depth_ = std::max(depth_, depth);
  const auto index = std::uint32_t(nodes_.size());
  nodes_.push_back({});
  if (end - begin <= std::uint32_t(options_.leaf_size)) {
    Box3 box;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.add(lo[order_[i]]);
      box.add(hi[order_[i]]);
    }
    nodes_[index] = {box.lo, box.hi, begin, end - begin};
    return index;
  }
  const std::uint64_t first = keyed[begin] >> 32, last = keyed[end - 1] >> 32;
  std::uint32_t split = begin + (end - begin) / 2;
  if (first != last) {
    const std::uint64_t bit = std::uint64_t{1} << (63 - __builtin_clzll(first ^ last));
    const std::uint64_t prefix = (last & ~(bit - 1)) << 32;  // the first key of the upper half
    split = std::uint32_t(std::lower_bound(keyed.begin() + begin, keyed.begin() + end, prefix) -
                          keyed.begin());
  }
  build_morton(begin, split, depth + 1, keyed, lo, hi);
  const std::uint32_t right = build_morton(split, end, depth + 1, keyed, lo, hi);
  const Node &a = nodes_[index + 1], &b = nodes_[right];
  nodes_[index] = {min(a.lo, b.lo), max(a.hi, b.hi), right, 0};
  return index;
}

template <TriangleBvh::Tie kRule>
ClosestPoint TriangleBvh::query(const Vec3& p, const Vec3& normal, std::uint32_t hint,
                                float stop_squared) const {
  constexpr bool kPreferNormal = kRule == Tie::kNormal;
  ClosestPoint best;
  if (nodes_.empty()) return best;
  float best_score = 0;
  bool score_known = false;
  // With the tie rule, `best` may be a tied triangle slightly farther than the
  // nearest one seen; `nearest` keeps the exact minimum distance.
  float nearest = std::numeric_limits<float>::infinity();
  auto limit = [&] {
    return kPreferNormal ? nearest + kTie * nearest + tie_floor_ : best.distance_squared;
  };

  auto visit = [&](std::uint32_t i) {
    TrianglePoint tp = closest_point_on_triangle(p, corners_[i]);
    if constexpr (kPreferNormal) {
      float tolerance = kTie * nearest + tie_floor_;
      if (!best.found() || tp.distance_squared < nearest - tolerance) {
        best = {tp.point, order_[i], tp.barycentric, tp.distance_squared};
        score_known = false;
      } else if (tp.distance_squared <= nearest + tolerance) {
        ClosestPoint candidate{tp.point, order_[i], tp.barycentric, tp.distance_squared};
        if (!score_known) best_score = dot(normal_at(best), normal);
        score_known = true;
        float score = dot(normal_at(candidate), normal);
        if (score > best_score) {
          best = candidate;
          best_score = score;
        }
      }
      nearest = std::min(nearest, tp.distance_squared);
    } else if (tp.distance_squared < best.distance_squared ||
               (kRule == Tie::kLowestIndex && tp.distance_squared == best.distance_squared &&
                order_[i] < best.triangle)) {
      best = {tp.point, order_[i], tp.barycentric, tp.distance_squared};
    }
  };
  // Without the tie rule, a triangle within stop_squared ends the search.
  auto done = [&] { return !kPreferNormal && best.distance_squared <= stop_squared; };
  // Searches the subtree at `root`, nearer child first, pruning subtrees
  // farther than the best so far; true when done().
  auto descend = [&](std::uint32_t root) {
    struct Entry {
      std::uint32_t node;
      float distance_squared;
    };
    Entry stack[kStackSize];
    int top = 0;
    stack[top++] = {root, box_distance_squared(nodes_[root].lo, nodes_[root].hi, p)};
    while (top > 0) {
      Entry e = stack[--top];
      if (e.distance_squared > limit()) continue;
      std::uint32_t ni = e.node;
      for (;;) {
        const Node& node = nodes_[ni];
        if (node.count) {
          for (std::uint32_t i = node.index, last = node.index + node.count; i < last; ++i) {
            visit(i);
          }
          if (done()) return true;
          break;
        }
        std::uint32_t near = ni + 1, far = node.index;
        float dn = box_distance_squared(nodes_[near].lo, nodes_[near].hi, p);
        float df = box_distance_squared(nodes_[far].lo, nodes_[far].hi, p);
        if (df < dn) {
          std::swap(near, far);
          std::swap(dn, df);
        }
        float bound = limit();
        if (dn > bound) break;
        if (df <= bound) {
          assert(top < kStackSize);
          stack[top++] = {far, df};
        }
        ni = near;
      }
    }
    return false;
  };
  if (hint >= slot_.size()) {
    descend(0);
  } else {
    // From the hint outwards: its leaf, then the other child of each of the
    // leaf's ancestors up to the root. Together they hold every triangle, so
    // the answer is the one a search from the root finds; a search that may
    // end at the first triangle within stop_squared mostly ends near the hint.
    const std::uint32_t first = slot_[hint];
    visit(first);
    if (done()) return best;
    std::uint32_t ni = leaf_of_[first];
    const Node& leaf = nodes_[ni];
    for (std::uint32_t i = leaf.index, last = leaf.index + leaf.count; i < last; ++i) {
      if (i != first) visit(i);
    }
    if (done()) return best;
    while (ni != 0) {
      const std::uint32_t up = parent_[ni];
      if (descend(ni == up + 1 ? nodes_[up].index : up + 1)) return best;
      ni = up;
    }
  }
  if constexpr (kPreferNormal) best.distance_squared = nearest;
  return best;
}

ClosestPoint TriangleBvh::closest_point(const Vec3& p, std::uint32_t hint) const {
  return query<Tie::kFirst>(p, {}, hint);
}

ClosestPoint TriangleBvh::closest_point_unless_within(const Vec3& p, float stop_squared,
                                                      std::uint32_t hint) const {
  return query<Tie::kFirst>(p, {}, hint, stop_squared);
}

ClosestPoint TriangleBvh::closest_point(const Vec3& p, const Vec3& normal,
                                        std::uint32_t hint) const {
  return query<Tie::kNormal>(p, normal, hint);
}

ClosestPoint TriangleBvh::closest_point_lowest_index(const Vec3& p, std::uint32_t hint) const {
  return query<Tie::kLowestIndex>(p, {}, hint);
}

RayHit TriangleBvh::first_hit(const Vec3& origin, const Vec3& direction, float max_distance) const {
  RayHit hit;
  const Vec3 unit = normalized(direction);
  if (nodes_.empty() || length_squared(unit) == 0) return hit;
  const Ray ray(origin, unit);
  struct Entry {
    std::uint32_t node;
    float t;
  };
  Entry stack[kStackSize];
  int top = 0;
  float best = max_distance;
  if (float t = ray.enter(nodes_[0].lo, nodes_[0].hi, best); t >= 0) stack[top++] = {0, t};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.t > best) continue;
    const Node& node = nodes_[e.node];
    if (node.count) {
      for (std::uint32_t i = node.index, last = node.index + node.count; i < last; ++i) {
        const double s = ray.hit(corners_[i].a, corners_[i].b, corners_[i].c);
        // Compared as floats, the distance reported: equal floats are a tie.
        const auto sf = static_cast<float>(s);
        if (s < 0 || sf > best) continue;
        if (sf < best || order_[i] < hit.triangle) best = sf, hit.triangle = order_[i];
      }
      continue;
    }
    // The nearer child is popped first.
    Entry a{e.node + 1, ray.enter(nodes_[e.node + 1].lo, nodes_[e.node + 1].hi, best)};
    Entry b{node.index, ray.enter(nodes_[node.index].lo, nodes_[node.index].hi, best)};
    if (a.t >= 0 && b.t >= 0 && a.t < b.t) std::swap(a, b);
    if (a.t >= 0) stack[top++] = a;
    if (b.t >= 0) stack[top++] = b;
  }
  if (hit.hit()) hit.distance = best;
  return hit;
}

Vec3 TriangleBvh::normal_at(const ClosestPoint& at) const {
  assert(at.found());
  if (options_.vertex_normals && mesh_->has_normals()) {
    const auto& t = mesh_->triangles[at.triangle];
    const auto& n = mesh_->normals;
    const auto& w = at.barycentric;
    Vec3 s = normalized(n[t[0]] * w[0] + n[t[1]] * w[1] + n[t[2]] * w[2]);
    if (length_squared(s) > 0) return s;
  }
  return face_normals_[at.triangle];
}

}  // namespace lodforge
