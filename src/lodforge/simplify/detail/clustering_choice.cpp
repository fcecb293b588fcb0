#include "lodforge/simplify/detail/clustering_choice.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/enumerable_thread_specific.h>

#include "lodforge/simplify/detail/clustering_simd.h"

namespace lodforge::detail::clustering {
namespace {

/// A cell with more vertices than this (only when a level skips many
/// depths) scores the kMaxCandidates closest to its weighted mean, so a
/// level costs O(faces) and not O(vertices x faces) per cell.
constexpr std::size_t kMaxCandidates = 64;
/// Cells per task when choosing representatives: small enough that the small
/// levels of a chain (hundreds of cells) still run on every thread.
constexpr std::size_t kCellChunk = 128;

/// What every cell of a level reads.
struct LevelContext {
  const Cut& prev;
  /// The triangles around each cell of several vertices; null when neither
  /// area nor volume is weighted or the level has no triangle.
  const CellFaces* faces;
  Weights weights;
};

/// Scratch buffers reused over the cells (one per thread), in
/// structure-of-arrays layout, single precision, relative to the cell's
/// weighted mean (small numbers).
struct Scratch {
  Buffer<std::uint32_t> order;  ///< a large cell's vertices, nearest the mean first
  /// The candidates (the cell's vertices, then Lindstrom's point), their
  /// input vertices and scores (area, volume, mean, quadric); fixed arrays:
  /// no allocation or size bookkeeping per cell.
  std::size_t n = 0;
  std::array<Vec3, kMaxCandidates + 1> candidate;
  std::array<std::uint32_t, kMaxCandidates + 1> candidate_orig;
  std::array<std::array<double, 4>, kMaxCandidates + 1> score;
  std::size_t m = 0;                                        ///< contenders
  std::array<std::uint32_t, kMaxCandidates + 1> contender;  ///< candidates that can still win
  /// The contenders relative to the cell's mean and their area and volume
  /// sums (padded to a multiple of kLanes).
  static constexpr std::size_t kPadded = (kMaxCandidates + 1 + kLanes - 1) / kLanes * kLanes;
  std::array<float, kPadded> cx, cy, cz, area, volume;
};

/// Sums the area and volume heuristics of the first m contenders (relative
/// to `origin` in s.cx, s.cy, s.cz) over the triangles around cell `cell` of
/// the previous level into s.area and s.volume, straight from the triangles
/// (no intermediate arrays): for each triangle (a, b, c), relative to
/// `origin`, with n = (b - a) x (c - a) (twice the area normal),
/// 6 x volume(a, b, c, x) = |n . a - n . x|; for each with one corner inside
/// the cell and the two outside p, r, moving the inside corner to x gives
/// area 0.5 |p x r - x x (r - p)| (triangles with two or three corners inside
/// collapse; swapping p and r only flips signs, exactly). Returns the area of
/// the triangles before the move.
///
/// Four triangles at a time, one per lane: what depends on the triangle alone
/// (its corners, normal, p x r) is computed once per four triangles, not once
/// per triangle and group of four candidates. The sums stay in triangle order
/// per candidate (four candidates' sums side by side, the four triangles'
/// values transposed into them) in single precision, as one triangle per
/// step would give them; lanes past the last triangle and collapsing
/// triangles add +0.
template <bool kArea, bool kVolume>
double score_faces(const LevelContext& ctx, std::uint32_t cell, const Vec3& origin, Scratch& s,
                   std::size_t m) {
  const Cut& prev = ctx.prev;
  const CellFaces& faces = *ctx.faces;
  const std::uint32_t first = faces.start[cell], last = faces.start[cell + 1];
  assert(last > first && m > 0);
  const std::size_t padded = (m + kLanes - 1) / kLanes * kLanes;
  std::fill_n(s.area.begin(), padded, 0.0f);
  std::fill_n(s.volume.begin(), padded, 0.0f);
  double area_before = 0;
  for (std::uint32_t k0 = first; k0 < last; k0 += kLanes) {
    // The block's triangles, one per lane (the last one repeated past the end).
    const std::uint32_t lanes = std::min<std::uint32_t>(kLanes, last - k0);
    std::uint32_t code[kLanes];
    const Triangle* t[kLanes];
    for (std::uint32_t l = 0; l < kLanes; ++l) {
      code[l] = faces.entry[k0 + std::min(l, lanes - 1)];
      t[l] = &prev.tris[code[l] >> 2];
    }
    auto corner = [&](int i, int axis) {
      return F4::set(prev.pos[(*t[0])[i]][axis], prev.pos[(*t[1])[i]][axis],
                     prev.pos[(*t[2])[i]][axis], prev.pos[(*t[3])[i]][axis]) -
             F4::splat(origin[axis]);
    };
    const F4 ax = corner(0, 0), ay = corner(0, 1), az = corner(0, 2);
    const F4 bx = corner(1, 0), by = corner(1, 1), bz = corner(1, 2);
    const F4 cx = corner(2, 0), cy = corner(2, 1), cz = corner(2, 2);
    const F4 ux = bx - ax, uy = by - ay, uz = bz - az;
    const F4 wx = cx - ax, wy = cy - ay, wz = cz - az;
    const F4 nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    alignas(16) float length[kLanes];
    sqrt(nx * nx + ny * ny + nz * nz).store(length);
    for (std::uint32_t l = 0; l < lanes; ++l) area_before += 0.5 * double(length[l]);
    const F4 in_block = F4::lanes_below(lanes);
    const F4 d = nx * ax + ny * ay + nz * az;
    // The corners outside the cell (which corner is inside: code & 3; 3 when
    // the triangle collapses).
    const auto inside = [&](std::uint32_t which) {
      return F4::lanes_equal(code[0] & 3, code[1] & 3, code[2] & 3, code[3] & 3, which);
    };
    const F4 first_inside = inside(0), third_inside = inside(2);
    const F4 keep = and_not(inside(3), in_block);
    const F4 px = select(first_inside, bx, ax), py = select(first_inside, by, ay),
             pz = select(first_inside, bz, az);
    const F4 rx = select(third_inside, bx, cx), ry = select(third_inside, by, cy),
             rz = select(third_inside, bz, cz);
    const F4 qx = py * rz - pz * ry, qy = pz * rx - px * rz, qz = px * ry - py * rx;  // p x r
    const F4 dx = rx - px, dy = ry - py, dz = rz - pz;
    for (std::size_t g = 0; g < padded; g += kLanes) {
      // Rows: contenders g.. (past m: zeros, never read); columns: triangles.
      F4 volume[kLanes] = {F4::splat(0), F4::splat(0), F4::splat(0), F4::splat(0)};
      F4 area[kLanes] = {F4::splat(0), F4::splat(0), F4::splat(0), F4::splat(0)};
      const std::size_t rows = std::min(kLanes, m - g);
      for (std::size_t j = 0; j < rows; ++j) {
        const F4 x = F4::splat(s.cx[g + j]), y = F4::splat(s.cy[g + j]), z = F4::splat(s.cz[g + j]);
        if (kVolume) volume[j] = abs(d - (nx * x + ny * y + nz * z)) & in_block;
        if (kArea) {
          const F4 ex = qx - (y * dz - z * dy);
          const F4 ey = qy - (z * dx - x * dz);
          const F4 ez = qz - (x * dy - y * dx);
          area[j] = sqrt(ex * ex + ey * ey + ez * ez) & keep;
        }
      }
      if (kVolume) {
        transpose(volume[0], volume[1], volume[2], volume[3]);
        (F4::load(&s.volume[g]) + volume[0] + volume[1] + volume[2] + volume[3])
            .store(&s.volume[g]);
      }
      if (kArea) {
        transpose(area[0], area[1], area[2], area[3]);
        (F4::load(&s.area[g]) + area[0] + area[1] + area[2] + area[3]).store(&s.area[g]);
      }
    }
  }
  return area_before;
}

/// What choose_representative decided for a cell: its representative's
/// position and the input vertex whose attributes it takes.
struct Choice {
  Vec3 pos;
  std::uint32_t orig = kNone;
};

/// The weighted mean of a cell's vertices [begin, end) of `prev`: each
/// weighted by the input coordinates it stands for.
struct Mean {
  double x = 0, y = 0, z = 0;

  Mean(const Cut& prev, std::uint32_t begin, std::uint32_t end) {
    double total = 0;
    for (std::uint32_t i = begin; i < end; ++i) {
      const double wi = prev.weight[i];
      x += wi * prev.pos[i].x;
      y += wi * prev.pos[i].y;
      z += wi * prev.pos[i].z;
      total += wi;
    }
    x /= total;
    y /= total;
    z /= total;
  }
  double distance(const Vec3& p) const {
    const double dx = p.x - x, dy = p.y - y, dz = p.z - z;
    return sqrt_nonnegative(dx * dx + dy * dy + dz * dz);
  }
};

void add_candidate(Scratch& s, const Vec3& p, std::uint32_t orig) {
  s.candidate[s.n] = p;
  s.candidate_orig[s.n] = orig;
  ++s.n;
}

/// The cell's vertices [begin, end) as candidates: all of them, or the
/// kMaxCandidates nearest the mean (in vertex order).
void add_vertex_candidates(const Cut& prev, std::uint32_t begin, std::uint32_t end,
                           const Mean& mean, Scratch& s) {
  s.n = 0;
  if (end - begin <= kMaxCandidates) {
    for (std::uint32_t i = begin; i < end; ++i) add_candidate(s, prev.pos[i], prev.orig[i]);
    return;
  }
  s.order.resize(end - begin);
  std::iota(s.order.begin(), s.order.end(), begin);
  std::nth_element(s.order.begin(), s.order.begin() + kMaxCandidates, s.order.end(),
                   [&](std::uint32_t a, std::uint32_t b) {
                     const double da = mean.distance(prev.pos[a]);
                     const double db = mean.distance(prev.pos[b]);
                     return da < db || (da == db && a < b);
                   });
  s.order.resize(kMaxCandidates);
  std::sort(s.order.begin(), s.order.end());
  for (std::uint32_t i : s.order) add_candidate(s, prev.pos[i], prev.orig[i]);
}

/// Lindstrom's point as one more candidate: the minimum of the cell's
/// quadric, clamped to the cell [cell_lo, cell_lo + cell_size], with the
/// attributes of the nearest vertex of the cell; none where it is not finite.
void add_quadric_point(const Cut& prev, std::uint32_t begin, std::uint32_t end, const Quadric& q,
                       const Mean& mean, const Vec3& cell_lo, float cell_size, Scratch& s) {
  const auto x = quadric_minimum(q, {mean.x, mean.y, mean.z});
  Vec3 p{float(x[0]), float(x[1]), float(x[2])};
  if (!is_finite(p)) return;
  p = min(max(p, cell_lo), cell_lo + Vec3{cell_size, cell_size, cell_size});
  std::uint32_t nearest = begin;
  float best = std::numeric_limits<float>::infinity();
  for (std::uint32_t i = begin; i < end; ++i) {
    const float d = length_squared(prev.pos[i] - p);
    if (d < best) best = d, nearest = i;
  }
  add_candidate(s, p, prev.orig[nearest]);
}

/// The terms that need no triangle (mean and quadric) of every candidate,
/// their largest values in `largest`, and the contenders: the candidates
/// whose weighted quadric term is within the sum of the other weights of
/// the best one (all of them without the quadric heuristic).
void score_without_faces(const Weights& use, const Quadric& q, const Mean& mean, Scratch& s,
                         std::array<double, 4>& largest) {
  double least_quadric = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < s.n; ++k) {
    const Vec3& x = s.candidate[k];
    auto& h = s.score[k];
    h = {0, 0, 0, 0};
    if (use.mean > 0) h[2] = mean.distance(x);
    if (use.quadric > 0) h[3] = q(x.x, x.y, x.z);
    largest[2] = std::max(largest[2], h[2]);
    largest[3] = std::max(largest[3], h[3]);
    least_quadric = std::min(least_quadric, h[3]);
  }
  s.m = 0;
  if (use.quadric > 0 && largest[3] > 0) {
    const double slack = (use.area + use.volume + (largest[2] > 0 ? use.mean : 0)) * largest[3];
    for (std::size_t k = 0; k < s.n; ++k) {  // branch-free: the outcome is data
      s.contender[s.m] = static_cast<std::uint32_t>(k);
      s.m += use.quadric * (s.score[k][3] - least_quadric) <= slack;
    }
  } else {
    for (std::size_t k = 0; k < s.n; ++k) s.contender[s.m++] = static_cast<std::uint32_t>(k);
  }
}

/// The area and volume terms of the contenders (score_faces, relative to
/// `origin`), their largest values in `largest`.
void score_with_faces(const LevelContext& ctx, std::uint32_t cell, const Vec3& origin,
                      const Weights& use, Scratch& s, std::array<double, 4>& largest) {
  const std::size_t m = s.m;
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3 r = s.candidate[s.contender[k]] - origin;
    s.cx[k] = r.x, s.cy[k] = r.y, s.cz[k] = r.z;
  }
  const double area_before = use.area > 0 ? use.volume > 0
                                                ? score_faces<true, true>(ctx, cell, origin, s, m)
                                                : score_faces<true, false>(ctx, cell, origin, s, m)
                                          : score_faces<false, true>(ctx, cell, origin, s, m);
  for (std::size_t c = 0; c < m; ++c) {
    auto& h = s.score[s.contender[c]];
    if (use.area > 0) h[0] = std::abs(0.5 * double(s.area[c]) - area_before);
    if (use.volume > 0) h[1] = double(s.volume[c]) / 6;
    largest[0] = std::max(largest[0], h[0]);
    largest[1] = std::max(largest[1], h[1]);
  }
}

/// The contender with the smallest weighted sum of its terms, each divided
/// by its largest value (ties: the first).
std::size_t winner(const Weights& use, const std::array<double, 4>& largest, const Scratch& s) {
  const double weight[4] = {use.area, use.volume, use.mean, use.quadric};
  double factor[4];
  for (int i = 0; i < 4; ++i)
    factor[i] = weight[i] > 0 && largest[i] > 0 ? weight[i] / largest[i] : 0;
  std::size_t best = s.contender[0];
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < s.m; ++c) {
    const auto& h = s.score[s.contender[c]];
    const double score = factor[0] * h[0] + factor[1] * h[1] + factor[2] * h[2] + factor[3] * h[3];
    if (score < best_score) best_score = score, best = s.contender[c];
  }
  return best;
}

/// The representative of cell `cell` holding vertices [begin, end) of the
/// previous level. `has_faces`: a vertex of the cell is a corner of a
/// triangle. `cell_lo` and `cell_size` bound the cell (for clamping
/// Lindstrom's point).
///
/// The quadric term is cheap (one 4x4 form per candidate), the area and
/// volume terms cost a pass over the triangles around the cell per
/// candidate. Each normalised term lies in [0, 1], so a candidate whose
/// weighted quadric term exceeds the best one by more than the sum of the
/// other weights cannot win, whatever its area, volume and distance to the
/// mean: only the remaining candidates (the contenders) are scored by area
/// and volume, and those two terms are normalised over the contenders. When
/// one contender is left it wins without looking at a triangle.
///
/// | cell has triangles | quadric weight | heuristics used                         |
/// |--------------------|----------------|-----------------------------------------|
/// | no (line set)      | any            | weighted mean alone                     |
/// | yes                | 0              | area, volume, mean (the thesis)         |
/// | yes                | > 0            | all four, Lindstrom's point a candidate |
Choice choose_representative(const LevelContext& ctx, std::uint32_t cell, std::uint32_t begin,
                             std::uint32_t end, bool has_faces, const Vec3& cell_lo,
                             float cell_size, const Quadric& q, Scratch& s) {
  const Mean mean(ctx.prev, begin, end);
  add_vertex_candidates(ctx.prev, begin, end, mean, s);
  const Weights use = has_faces ? ctx.weights : Weights{0, 0, 1, 0};
  if (use.quadric > 0) add_quadric_point(ctx.prev, begin, end, q, mean, cell_lo, cell_size, s);
  std::array<double, 4> largest{0, 0, 0, 0};
  score_without_faces(use, q, mean, s, largest);
  const bool measure = ctx.faces != nullptr && (use.area > 0 || use.volume > 0);
  if (measure && s.m > 1) {
    const Vec3 origin{float(mean.x), float(mean.y), float(mean.z)};
    score_with_faces(ctx, cell, origin, use, s, largest);
  }
  const std::size_t best = s.m == 1 ? s.contender[0] : winner(use, largest, s);
  return {s.candidate[best], s.candidate_orig[best]};
}

}  // namespace

/// Adds the area-weighted quadric of the plane of each triangle (p, q, r)
/// (area x the squared distance to the plane; zero for a degenerate
/// triangle) to the quadrics of the cells its corners map to (`mapped`, in
/// triangle order). With n = (q - p) x (r - p) unnormalised, area = |n| / 2
/// and the unit normal n / |n|, every coefficient is a product of n and n.p
/// over 2 |n|: one square root and one division. In blocks, one pass each
/// for the normals, the square roots and divisions (two at a time) and the
/// quadrics: one triangle's chain of latencies (gathers, cross product,
/// square root, division, the sums into its cells) no longer holds the next
/// triangle back.
void add_plane_quadrics(std::span<const Vec3> pos, std::span<const Triangle> tris,
                        std::span<const Triangle> mapped, Buffer<Quadric>& quadric) {
  constexpr std::size_t kBlock = 64;
  alignas(16) double nx[kBlock], ny[kBlock], nz[kBlock], len2[kBlock], d[kBlock], s[kBlock];
  for (std::size_t f0 = 0; f0 < tris.size(); f0 += kBlock) {
    const std::size_t n = std::min(kBlock, tris.size() - f0);
    for (std::size_t i = 0; i < n; ++i) {
      const Triangle& t = tris[f0 + i];
      const Vec3 &p = pos[t[0]], &q = pos[t[1]], &r = pos[t[2]];
      double ux = double(q.x) - p.x, uy = double(q.y) - p.y, uz = double(q.z) - p.z;
      double vx = double(r.x) - p.x, vy = double(r.y) - p.y, vz = double(r.z) - p.z;
      nx[i] = uy * vz - uz * vy, ny[i] = uz * vx - ux * vz, nz[i] = ux * vy - uy * vx;
      len2[i] = nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i];
      d[i] = -(nx[i] * p.x + ny[i] * p.y + nz[i] * p.z);  // |n| x the plane's offset
    }
    std::size_t i = 0;
#if defined(__SSE2__)
    for (; i + 1 < n; i += 2)  // a degenerate triangle's (inf or NaN) is not used below
      _mm_store_pd(&s[i], _mm_div_pd(_mm_set1_pd(0.5), _mm_sqrt_pd(_mm_load_pd(&len2[i]))));
#endif
    for (; i < n; ++i) s[i] = 0.5 / sqrt_nonnegative(len2[i]);
    for (i = 0; i < n; ++i) {
      Quadric k{};
      if (len2[i] > 0) {
        const double sx = s[i] * nx[i], sy = s[i] * ny[i], sz = s[i] * nz[i];
        k.a00 = sx * nx[i];
        k.a01 = sx * ny[i];
        k.a02 = sx * nz[i];
        k.a11 = sy * ny[i];
        k.a12 = sy * nz[i];
        k.a22 = sz * nz[i];
        k.b0 = d[i] * sx;
        k.b1 = d[i] * sy;
        k.b2 = d[i] * sz;
        k.c = s[i] * d[i] * d[i];
      }
      for (std::uint32_t c : mapped[f0 + i]) quadric[c] += k;
    }
  }
}

void CellFaces::count(std::span<const Triangle> mapped, std::span<const char> wanted) {
  start.assign(wanted.size() + 1, 0);
  std::uint32_t* counts = start.data() + 1;
  for (const Triangle& t : mapped) {
    const auto add = adds(t[0], t[1], t[2], wanted);
    counts[t[0]] += add[0];
    counts[t[1]] += add[1];
    counts[t[2]] += add[2];
  }
}

void CellFaces::fill(std::span<const Triangle> mapped, std::span<const char> wanted) {
  const std::size_t cells = wanted.size();
  for (std::size_t j = 0; j < cells; ++j) start[j + 1] += start[j];
  // A corner that adds nothing writes to a spare last slot.
  const std::uint32_t spare = start[cells];
  entry.resize(spare + 1);
  std::uint32_t* next = start.data();
  std::uint32_t* out = entry.data();
  for (std::size_t f = 0; f < mapped.size(); ++f) {
    const std::uint32_t a = mapped[f][0], b = mapped[f][1], c = mapped[f][2];
    const auto add = adds(a, b, c, wanted);
    // The inside corner's index, or 3 when another corner shares the cell.
    const auto g = static_cast<std::uint32_t>(4 * f);
    const std::uint32_t code[3] = {g + (a == b || a == c ? 3u : 0u),
                                   g + (a == b || b == c ? 3u : 1u),
                                   g + (a == c || b == c ? 3u : 2u)};
    const std::uint32_t cell[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t at = next[cell[i]];
      out[add[i] ? at : spare] = code[i];
      next[cell[i]] = at + add[i];
    }
  }
  entry.pop_back();
  std::copy_backward(start.begin(), start.end() - 1, start.end());
  start[0] = 0;
}

struct RepresentativePicker::PerThread {
  tbb::enumerable_thread_specific<Scratch> scratch;
};

RepresentativePicker::RepresentativePicker() : per_thread_(std::make_unique<PerThread>()) {}
RepresentativePicker::~RepresentativePicker() = default;

void RepresentativePicker::pick(const Cut& prev, const Cells& cells, const CellFaces* faces,
                                const Weights& weights, std::span<const char> corner,
                                const Octree& octree, Cut& next) {
  const bool quadrics = weights.quadric > 0;
  const bool summed = quadrics && prev.quadric.empty();  // by add_plane_quadrics
  const int depth = cells.depth;
  const float cell_size = static_cast<float>(octree.cell_side(depth));
  const LevelContext ctx{prev, faces, weights};
  const Buffer<std::uint32_t>& cell_begin = cells.begin;
  // Cells are independent: each reads the previous level and writes its own slot.
  for_chunks<kCellChunk>(cells.count(), [&](std::size_t lo, std::size_t hi) {
    Scratch& scratch = per_thread_->scratch.local();
    for (auto j = static_cast<std::uint32_t>(lo); j < hi; ++j) {
      const std::uint32_t b = cell_begin[j], e = cell_begin[j + 1];
      next.code[j] = prev.code[b];
      std::uint32_t weight = 0;
      for (std::uint32_t i = b; i < e; ++i) weight += prev.weight[i];
      next.weight[j] = weight;
      if (e - b == 1) {
        next.pos[j] = prev.pos[b];
        next.orig[j] = prev.orig[b];
        if (quadrics && !summed) next.quadric[j] = prev.quadric[b];
        continue;
      }
      if (quadrics && !summed) {
        Quadric sum{};
        for (std::uint32_t i = b; i < e; ++i) sum += prev.quadric[i];
        next.quadric[j] = sum;
      }
      const Quadric& q = quadrics ? next.quadric[j] : Quadric{};
      bool has_faces = corner.empty();
      for (std::uint32_t i = b; i < e && !has_faces; ++i) has_faces = corner[i] != 0;
      const Choice c = choose_representative(
          ctx, j, b, e, has_faces, octree.cell_lo(prev.code[b], depth), cell_size, q, scratch);
      next.pos[j] = c.pos;
      next.orig[j] = c.orig;
    }
  });
}

}  // namespace lodforge::detail::clustering
