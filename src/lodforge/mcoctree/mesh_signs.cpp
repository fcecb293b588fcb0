// Corner signs of the marching-cube octree from a triangle mesh.
//
// Kim's thesis ("Level-of-detail mesh modeling using the marching cube
// octree", ch. 4) takes a corner's sign from the nearest range point and its
// normal. For a mesh the exact closest surface point and the angle-weighted
// pseudo-normal there (Baerentzen & Aanaes 2005) give the side, which is
// correct for any closed mesh (a face normal alone is wrong near sharp edges
// and vertices). Only the lattice points within a cell of the surface are
// measured, by scanning each triangle over the lattice near it; the rest,
// and the points nearest an open rim, are flood-filled.
#include "lodforge/mcoctree/mesh_signs.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "lodforge/mcoctree/part_bridges.h"
#include "lodforge/metrics/closest_point_on_triangle.h"

namespace lodforge::detail {
namespace {

// A pseudo-normal shorter than this fraction of its weights' sum has
// cancelled (a fold): a regular vertex or edge keeps most of it, a needle
// of a 1-degree half-angle about 0.017.
constexpr float kFold = 0.01f;

}  // namespace

SignedDistance::SignedDistance(TriangleMesh mesh) : mesh_(std::move(mesh)) {
  const auto& P = mesh_.positions;
  face_normal_.resize(mesh_.triangles.size());
  std::vector<Vec3> vertex_normal(P.size());
  std::vector<float> vertex_angle(P.size(), 0.0f);
  for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
    const auto& f = mesh_.triangles[t];
    Vec3 n = normalized(cross(P[f[1]] - P[f[0]], P[f[2]] - P[f[0]]));
    face_normal_[t] = n;
    for (int k = 0; k < 3; ++k) {
      Vec3 a = normalized(P[f[(k + 1) % 3]] - P[f[k]]), b = normalized(P[f[(k + 2) % 3]] - P[f[k]]);
      float angle = std::acos(std::clamp(dot(a, b), -1.0f, 1.0f));
      vertex_normal[f[k]] += n * angle;
      vertex_angle[f[k]] += angle;
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
    open_edge_[e] = kRimFeature;
    open_vertex_[adjacency_.edges[e][0]] = open_vertex_[adjacency_.edges[e][1]] = kRimFeature;
  }
  // A fold (faces turned back onto each other: a fin of no volume) has
  // pseudo-normals that cancel, whose direction is rounding noise: a point
  // nearest it is outside (sample).
  for (std::size_t v = 0; v < P.size(); ++v)
    if (vertex_angle[v] > 0 && length(vertex_normal[v]) < kFold * vertex_angle[v])
      open_vertex_[v] |= kFoldFeature;
  for (std::size_t e = 0; e < adjacency_.edges.size(); ++e)
    if (adjacency_.edge_valence(static_cast<std::uint32_t>(e)) == 2 &&
        length(edge_normal_[e]) < 2 * kFold)
      open_edge_[e] |= kFoldFeature;
  if (!mesh_.has_normals()) {
    mesh_.normals.resize(P.size());
    for (std::size_t v = 0; v < P.size(); ++v) mesh_.normals[v] = normalized(vertex_normal[v]);
  }
}

SignedDistance::Sample SignedDistance::operator()(const Vec3& p, std::uint32_t hint) const {
  return sample(p, bvh().closest_point_lowest_index(p, hint));
}

SignedDistance::Sample SignedDistance::sample(const Vec3& p, const ClosestPoint& cp) const {
  auto [n, kind] = feature_kind(cp);
  float d = std::sqrt(cp.distance_squared);
  // Nearest to a hole's rim the pseudo-normal's side is a half-plane that
  // runs off to infinity: such points are left to the flood fill.
  if (kind & kRimFeature) return {d, cp, true};
  // Nearest a fold the side is outside: the fold's faces enclose no volume,
  // and a point inside the solid next to it is nearer one of its faces.
  if (kind & kFoldFeature) return {d, cp, false};
  return {dot(p - cp.point, n) < 0 ? -d : d, cp, false};
}

std::pair<Vec3, bool> SignedDistance::feature(const ClosestPoint& cp) const {
  auto [n, kind] = feature_kind(cp);
  return {n, (kind & kRimFeature) != 0};
}

std::pair<Vec3, std::uint8_t> SignedDistance::feature_kind(const ClosestPoint& cp) const {
  const auto& b = cp.barycentric;
  const auto& f = mesh_.triangles[cp.triangle];
  constexpr float kTol = 1e-5f;
  int zeros = (b[0] < kTol) + (b[1] < kTol) + (b[2] < kTol);
  if (zeros >= 2) {
    int k = b[0] >= b[1] && b[0] >= b[2] ? 0 : b[1] >= b[2] ? 1 : 2;
    return {vertex_normal_[f[k]], open_vertex_[f[k]]};
  }
  if (zeros == 1) {
    int side = b[2] < kTol ? 0 : b[0] < kTol ? 1 : 2;
    auto e = adjacency_.triangle_edges[cp.triangle][side];
    if (e != MeshAdjacency::kNoEdge) return {edge_normal_[e], open_edge_[e]};
  }
  return {face_normal_[cp.triangle], 0};
}

// The Morton build: the hierarchy answers a few thousand queries (an open
// mesh's repairs, hole tests and edge points by a rim), too few to repay a
// surface-area-heuristic build.
const TriangleBvh& SignedDistance::bvh() const {
  std::call_once(bvh_once_, [&] {
    bvh_ = std::make_unique<TriangleBvh>(mesh_,
                                         BvhOptions{.leaf_size = 8, .build = BvhBuild::kMorton});
  });
  return *bvh_;
}

ClosestPoint SignedDistance::on_triangle(const Vec3& p, std::uint32_t t) const {
  const auto& f = mesh_.triangles[t];
  TrianglePoint tp = closest_point_on_triangle(p, mesh_.positions[f[0]], mesh_.positions[f[1]],
                                               mesh_.positions[f[2]]);
  return {tp.point, t, tp.barycentric, tp.distance_squared};
}

Vec3 SignedDistance::normal_at(const ClosestPoint& cp) const {
  const auto& f = mesh_.triangles[cp.triangle];
  Vec3 n{};
  for (int k = 0; k < 3; ++k) n += mesh_.normals[f[k]] * cp.barycentric[k];
  return length_squared(n) > 0 ? normalized(n) : face_normal_[cp.triangle];
}

namespace {

// The band scan cuts the lattice into slabs of kSlab layers, each scanned by
// one task with the triangles that reach it.
constexpr std::int64_t kSlab = 4;

// The lattice points a triangle's scan visits: its bounding box grown by a
// cell (those points include every point within a cell of it).
struct TriangleRange {
  std::int64_t lo[3], hi[3];
};

// The nearest triangle found so far at a lattice point of a slab.
struct Nearest {
  float d2 = INFINITY;
  std::uint32_t triangle = 0;
  std::array<float, 3> barycentric{};
};

// A band point: its signed distance (NaN: nearest an open rim) and triangle.
struct BandPoint {
  std::int64_t idx;
  float distance;
  std::uint32_t triangle;
};

// Each triangle's range, and per slab the triangles whose range reaches it.
struct SlabBuckets {
  std::vector<TriangleRange> range;
  std::vector<std::vector<std::uint32_t>> bucket;
};

SlabBuckets bucket_triangles(const TriangleMesh& m, const Lattice& lat, std::int64_t slabs) {
  SlabBuckets out;
  out.range.resize(m.triangles.size());
  out.bucket.resize(static_cast<std::size_t>(slabs));
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    Box3 tb;
    for (int k = 0; k < 3; ++k) tb.add(m.positions[m.triangles[t][k]]);
    TriangleRange& r = out.range[t];
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = std::max<std::int64_t>(
          0, static_cast<std::int64_t>(std::ceil((tb.lo[a] - lat.origin[a]) / lat.h - 1)));
      r.hi[a] = std::min<std::int64_t>(
          lat.dim[a] - 1,
          static_cast<std::int64_t>(std::floor((tb.hi[a] - lat.origin[a]) / lat.h + 1)));
    }
    for (auto s = r.lo[2] / kSlab; s <= r.hi[2] / kSlab; ++s)
      out.bucket[static_cast<std::size_t>(s)].push_back(static_cast<std::uint32_t>(t));
  }
  return out;
}

// Lattice coordinates per axis (the same values as Lattice::point's).
std::array<std::vector<float>, 3> lattice_coordinates(const Lattice& lat) {
  std::array<std::vector<float>, 3> coord;
  for (int a = 0; a < 3; ++a) {
    coord[a].resize(static_cast<std::size_t>(lat.dim[a]));
    for (std::int64_t i = 0; i < lat.dim[a]; ++i)
      coord[a][static_cast<std::size_t>(i)] =
          lat.root[a] + static_cast<float>(i + lat.offset[a]) * lat.h;
  }
  return coord;
}

// Scans triangle t over the points of its range in layers [z0, z1), keeping
// at each point of `nearest` (the slab's points from layer z0 on) the
// nearest triangle within a cell.
void scan_triangle(const TriangleMesh& m, std::uint32_t t, const TriangleRange& r,
                   const Lattice& lat, const std::array<std::vector<float>, 3>& coord,
                   std::int64_t z0, std::int64_t z1, std::vector<Nearest>& nearest) {
  const float h2 = lat.h * lat.h, margin = 1e-5f * h2;
  const auto& f = m.triangles[t];
  const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
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
      Nearest* row = &nearest[static_cast<std::size_t>(lat.index(0, j, k - z0))];
      for (auto i = i0; i <= i1; ++i) {
        const float x = coord[0][static_cast<std::size_t>(i)];
        auto along = [&](int q) { return ((x - from[q]->x) * dir[q]->x + dy[q]) + dz[q]; };
        const float off = along(0);
        if (off * off > h2) continue;
        // No nearer than its plane: skip when a nearer triangle is known.
        Nearest& bt = row[i];
        if (off * off >= bt.d2) continue;
        const float beyond = std::max({0.0f, -along(1), -along(2), -along(3)});
        if (off * off + beyond * beyond > std::min(h2, bt.d2) * 1.001f + margin) continue;
        TrianglePoint tp = closest_point_on_triangle({x, y, z}, a, b, c);
        if (tp.distance_squared < bt.d2) bt = {tp.distance_squared, t, tp.barycentric};
      }
    }
  }
}

// The signed distances of the points of a slab (from layer z0 on) that have
// a triangle within a cell, in index order.
void slab_band_points(const SignedDistance& sd, const Lattice& lat, std::int64_t z0,
                      const std::vector<Nearest>& nearest, std::vector<BandPoint>& out) {
  const TriangleMesh& m = sd.mesh();
  const float h2 = lat.h * lat.h;
  for (std::size_t p = 0; p < nearest.size(); ++p) {
    const Nearest& bt = nearest[p];
    if (!(bt.d2 <= h2)) continue;
    std::int64_t idx = z0 * lat.plane() + static_cast<std::int64_t>(p);
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
}

// Band: every lattice point within a cell of the surface gets its exact
// closest point by scanning each triangle over the lattice points of its
// range, keeping the nearest: a few dozen point-triangle tests per triangle
// instead of a hierarchy query per point. Both ends of a lattice edge the
// surface crosses are within a cell of it, so these points separate the
// inside from the outside and the flood fill cannot carry a sign across the
// surface. Per slab, in index order.
std::vector<std::vector<BandPoint>> scan_band(const SignedDistance& sd, const Lattice& lat,
                                              const ProgressCallback& progress) {
  const TriangleMesh& m = sd.mesh();
  const std::int64_t nz = lat.dim[2], slabs = (nz + kSlab - 1) / kSlab;
  const SlabBuckets buckets = bucket_triangles(m, lat, slabs);
  const std::array<std::vector<float>, 3> coord = lattice_coordinates(lat);
  std::vector<std::vector<BandPoint>> found(static_cast<std::size_t>(slabs));
  ProgressCounter slabs_done(progress, "signs", static_cast<std::uint64_t>(slabs), 1);
  tbb::parallel_for(std::int64_t{0}, slabs, [&](std::int64_t s) {
    const std::int64_t z0 = s * kSlab, z1 = std::min(nz, z0 + kSlab);
    std::vector<Nearest> nearest(static_cast<std::size_t>((z1 - z0) * lat.plane()));
    for (auto t : buckets.bucket[static_cast<std::size_t>(s)])
      scan_triangle(m, t, buckets.range[t], lat, coord, z0, z1, nearest);
    slab_band_points(sd, lat, z0, nearest, found[static_cast<std::size_t>(s)]);
    slabs_done.add(1);
  });
  return found;
}

// Writes the band into the lattice (points nearest an open rim are measured
// but get no sign) and returns the points with a sign, the flood's seeds.
std::vector<std::int64_t> seed_band(Lattice& lat, const std::vector<std::vector<BandPoint>>& found,
                                    McBuildStats& stats) {
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
  return seeds;
}

// The rest of the root cube's boundary is outside and stays so: an open
// mesh's inside could otherwise flood out to it, and the surface would end
// there. Appends those points to `seeds`.
void seal_boundary(Lattice& lat, std::vector<std::int64_t>& seeds) {
  const std::int64_t nx = lat.dim[0], ny = lat.dim[1], nz = lat.dim[2];
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        if (!(k == 0 || k == nz - 1 || j == 0 || j == ny - 1) && i != 0) i = nx - 1;
        std::int64_t idx = lat.index(i, j, k);
        if (lat.state[idx] & kExact) continue;
        lat.state[idx] = kAssigned | kMeasured;
        seeds.push_back(idx);
      }
}

// Breadth-first flood fill from the assigned points: every unassigned point
// takes the sign of the nearest assigned one (in lattice steps; a tie goes to
// the point first in the queue), so that a hole is closed about midway
// between the inside and the outside. Precondition: the lattice's border is
// all assigned, so that only the seeds' neighbours need a bounds check and
// the queue holds bare indices (the fill visits most of the lattice: its
// inner loop is a load, a test and a store per neighbour).
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
                      std::uint32_t hint = kNone;
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

// The inner points whose sign came from the flood and differs from a
// neighbour's, in index order. (The lattice's boundary is all measured or
// exact: only inner points.)
std::vector<std::int64_t> disagreeing_flooded_points(const Lattice& lat) {
  const std::uint8_t* st = lat.state.data();
  const std::int64_t nx = lat.dim[0], ny = lat.dim[1], nz = lat.dim[2], plane = lat.plane();
  return collect_by_layer(1, nz - 1, [&](std::int64_t k, std::vector<std::int64_t>& out) {
    // Copies in locals: a push could alias what the lambda refers to.
    const std::uint8_t* const s = st;
    const std::int64_t row_step = nx, layer_step = plane, rows = ny, cols = nx;
    for (std::int64_t j = 1; j + 1 < rows; ++j) {
      const std::int64_t row = j * row_step + k * layer_step;
      for (std::int64_t i = 1; i + 1 < cols; ++i) {
        const std::int64_t idx = row + i;
        const std::uint8_t v = s[idx];
        const std::uint8_t differ = (s[idx - 1] ^ v) | (s[idx + 1] ^ v) | (s[idx - row_step] ^ v) |
                                    (s[idx + row_step] ^ v) | (s[idx - layer_step] ^ v) |
                                    (s[idx + layer_step] ^ v);
        if ((differ & kInside) && !(v & (kExact | kMeasured))) out.push_back(idx);
      }
    }
  });
}

// Repair: a flooded point that disagrees with a neighbour gets an exact sign
// (the inside leaks through a gap narrower than the band), and so do the
// unmeasured neighbours of each point whose sign that changes, until no sign
// changes. Leaves lat.distance sorted by index.
void repair_signs(Lattice& lat, const SignedDistance& sd, McBuildStats& stats) {
  auto unsure = [&](std::int64_t idx) { return !(lat.state[idx] & (kExact | kMeasured)); };
  std::vector<std::int64_t> work = disagreeing_flooded_points(lat);
  // The band's distances are in index order already (slabs in z order, each
  // in index order); only the repairs' are merged in.
  const auto banded = static_cast<std::ptrdiff_t>(lat.distance.size());
  while (!work.empty()) {
    stats.sign_repairs += work.size();
    auto changed = measure(lat, sd, work);
    std::vector<std::int64_t> next;
    for (auto idx : changed)
      lattice_neighbours(lat, idx, [&](std::int64_t q) {
        if (unsure(q) && lat.inside(q) != lat.inside(idx)) next.push_back(q);
      });
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    work = std::move(next);
  }
  std::sort(lat.distance.begin() + banded, lat.distance.end());
  std::inplace_merge(lat.distance.begin(), lat.distance.begin() + banded, lat.distance.end());
}

// Marching cubes make about kTrianglesPerCellFace triangles per h x h of
// surface (measured on the bunny, a sphere and a torus).
constexpr double kTrianglesPerCellFace = 2.9;

}  // namespace

Lattice make_mesh_lattice(const SignedDistance& sd, int resolution, McBuildStats& stats,
                          const ProgressCallback& progress) {
  Lattice lat = empty_lattice(sd.mesh().bounds(), resolution);
  std::vector<std::int64_t> seeds = seed_band(lat, scan_band(sd, lat, progress), stats);
  seal_boundary(lat, seeds);
  // The rest, and the band points nearest an open rim, from the band's and
  // the boundary's signs (nearest sign wins).
  flood_fill(lat, seeds, stats);
  repair_signs(lat, sd, stats);
  // A closed mesh's parts stay whole across places thinner than a cell.
  if (!sd.has_rims()) stats.part_bridges = bridge_mesh_parts(lat, sd).bridges;
  return lat;
}

// h = sqrt(kTrianglesPerCellFace x area / triangles) gives the input's
// triangle count at full resolution.
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

}  // namespace lodforge::detail
