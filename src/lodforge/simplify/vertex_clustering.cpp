// Vertex clustering by octree quantisation.
//
// Implements seed 000 §4.1.1 (the LODCreator's vertex clustering): the
// octree of Gervautz & Purgathofer's colour quantisation ("A simple method for
// color quantization: octree quantization", 1988) applied to vertex positions,
// in the spirit of Rossignac & Borrel's "Multi-resolution 3D approximations
// for rendering complex scenes" (1993), with the thesis' three representative
// heuristics (error area, error volume, weighted mean). To these it adds the
// representative of P. Lindstrom, "Out-of-core simplification of large
// polygonal models" (SIGGRAPH 2000): the point minimising the sum of the
// plane quadrics of the triangles around the cell (Garland & Heckbert 1997),
// found with a regularised 3x3 solve and clamped to the cell.
//
// The octree is implicit. A used coordinate is quantised to 21 bits per axis
// in the cube that bounds the input and its bits interleaved into a 63-bit
// Morton code; sorted by code, the vertices are the octree's leaves in
// depth-first order, and two vertices share their cell at depth c exactly when
// their codes agree on the top 3c bits. The thesis' tree (one coordinate per
// leaf, subdivided only where two coordinates meet) therefore has depth
// max(common depth of neighbours in code order) + 1, and "merge the deepest
// leaves into their parents until min diff is met" is a cut of the tree at
// one depth c: a level's vertices are the cells at depth c, each represented
// by one of the previous level's vertices in it (or Lindstrom's point).
// Coordinates closer than side / 2^21 (about float resolution) share the
// finest cell and merge at the first level.
//
// Deviations from the thesis, each a superset or a tightening of it:
// * When min diff needs several depths merged at once, the thesis merges depth
//   by depth and picks a representative at each; here the representative is
//   picked once among all the previous level's vertices in the cell (the
//   thesis' final candidates are among them).
// * The heuristics' values are divided by their largest value over the
//   cell's candidates before they are weighted: the thesis gives weights
//   (8, 1, 0) but no units, and an area, a volume and a distance cannot be
//   added otherwise.
// * A cell with more than kMaxCandidates vertices (only when a level skips
//   many depths) scores the kMaxCandidates closest to the weighted mean, so a
//   level costs O(faces) and not O(vertices x faces) per cell.
//
// Why a quadric heuristic: the thesis' heuristics choose among existing
// vertices, which on a curved surface leaves the new triangles on one side
// of the cell's surface; Lindstrom's point lies in the middle of it. On the
// Stanford bunny the thesis' method misses its own published figures at 50 %
// and 99 % reduction; with the quadric point as a candidate every figure is
// met (measurements and the choice of the default weight: see the header).
#include "lodforge/simplify/vertex_clustering.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

#include <fmt/core.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/scalable_allocator.h>
#include <tbb/task_group.h>

#include "lodforge/core/error.h"
#include "lodforge/core/morton.h"

namespace lodforge {
namespace {

/// The allocator of the call's working arrays: TBB's scalable allocator,
/// which keeps freed large blocks for the next call where glibc's malloc
/// hands them back to the system, so that every call faulted their pages in
/// again (igea: ~5 000 page faults a call, a sixth of its time); and resize()
/// leaves elements without a default member initialiser (indices, codes)
/// uninitialised: every array resized here is written in full before it is
/// read, and zeroing it first was a serial pass over memory.
template <class T>
struct BufferAllocator : tbb::scalable_allocator<T> {
  using value_type = T;
  // The name the standard gives it; it hides the base's, which would rebind
  // to tbb::scalable_allocator and lose construct() below.
  template <class U>
  struct rebind {  // NOLINT(readability-identifier-naming)
    using other = BufferAllocator<U>;
  };
  BufferAllocator() = default;
  template <class U>
  BufferAllocator(const BufferAllocator<U>& /*other*/) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const BufferAllocator<U>& /*other*/) const noexcept {
    return true;
  }
};
template <class T>
using Buffer = std::vector<T, BufferAllocator<T>>;

constexpr int kMaxDepth = 21;  // bits per axis of the Morton code (3 x 21 = 63)
constexpr std::size_t kMaxCandidates = 64;
// Regularisation of a cell's quadric, as a fraction of its trace: directions
// in which the cell's surface is flat or straight (Lindstrom 2000 drops
// eigenvalues below 1e-3 of the largest) keep the weighted mean.
constexpr double kRankTolerance = 1e-3;

// ---------------------------------------------------------------- Morton codes

std::uint32_t compact_bits(std::uint64_t x) {
  x &= 0x1249249249249249ull;
  x = (x ^ (x >> 2)) & 0x10c30c30c30c30c3ull;
  x = (x ^ (x >> 4)) & 0x100f00f00f00f00full;
  x = (x ^ (x >> 8)) & 0x1f0000ff0000ffull;
  x = (x ^ (x >> 16)) & 0x1f00000000ffffull;
  x = (x ^ (x >> 32)) & 0x1fffffull;
  return static_cast<std::uint32_t>(x);
}

/// Arrays from this size on are processed in two parts side by side (level
/// 0's passes over the input, a level's passes over its vertices; below it,
/// a task costs more than it saves). A part writes memory of its own: where
/// both parts' writes meet in cache lines (the radix sort's buckets, the runs
/// of a counting sort split by triangles), two threads were slower than one.
constexpr std::size_t kTwoParts = 4096;

/// How many parts an array of n items is processed in: 1 or 2.
std::size_t parts_of(std::size_t n) {
  return n >= kTwoParts ? 2 : 1;
}

/// The parts of [0, n): part q is [bound[q], bound[q + 1]).
std::array<std::size_t, 3> halves(std::size_t n, std::size_t parts) {
  return {0, parts == 2 ? n / 2 : n, n};
}

/// Runs body(0) and, when parts is 2, body(1) beside it.
template <class Body>
void for_parts(std::size_t parts, const Body& body) {
  if (parts == 1) return body(std::size_t(0));
  tbb::parallel_invoke([&] { body(std::size_t(0)); }, [&] { body(std::size_t(1)); });
}

/// An unused vertex's code: above every 63-bit code, so it sorts last.
constexpr std::uint64_t kUnused = ~std::uint64_t(0);

/// Sorts `keys` (a vertex's top 32 code bits above its index) by the whole
/// comparison of sort_vertices below, on the calling thread, with `tmp` (as
/// long) as scratch: an LSD radix sort of the top 32 bits (three passes of
/// 11, 11 and 10 bits, counted in one pass; a pass where one bucket holds
/// every key is skipped), then each run of equal top bits sorted by the
/// whole comparison.
void sort_range(std::span<std::uint64_t> keys, std::span<std::uint64_t> tmp,
                std::span<const std::uint64_t> code, std::span<const Vec3> positions) {
  constexpr int kPasses = 3, kBits[kPasses] = {11, 11, 10};
  constexpr std::size_t kBuckets = std::size_t(1) << 11;
  const std::size_t n = keys.size();
  auto digit = [&](std::uint64_t key, int p) {
    return static_cast<std::size_t>((key >> (32 + 11 * p)) & ((1u << kBits[p]) - 1));
  };
  std::array<std::array<std::uint32_t, kBuckets>, kPasses> count{};
  for (std::uint64_t key : keys)
    for (int p = 0; p < kPasses; ++p) ++count[p][digit(key, p)];
  std::uint64_t* from = keys.data();
  std::uint64_t* to = tmp.data();
  for (int p = 0; p < kPasses; ++p) {
    auto& c = count[p];
    if (std::find(c.begin(), c.end(), n) != c.end()) continue;  // one digit: no-op
    std::uint32_t sum = 0;
    for (auto& k : c) sum += std::exchange(k, sum);
    for (std::size_t i = 0; i < n; ++i) to[c[digit(from[i], p)]++] = from[i];
    std::swap(from, to);
  }
  if (from != keys.data()) std::copy_n(from, n, keys.data());
  // The runs are those of equal sorted bits exactly: a code with bit 63 set
  // (an unused vertex's ~0) shares its top 32 bits with the cube's far corner.
  auto top = [](std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); };
  auto less = [&](std::uint64_t a, std::uint64_t b) {
    const auto va = static_cast<std::uint32_t>(a), vb = static_cast<std::uint32_t>(b);
    if (code[va] != code[vb]) return code[va] < code[vb];
    if (code[va] == kUnused) return va < vb;
    const Vec3& pa = positions[va];
    const Vec3& pb = positions[vb];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    if (pa.z != pb.z) return pa.z < pb.z;
    return va < vb;
  };
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && top(keys[j]) == top(keys[i])) ++j;
    if (j - i > 1) std::sort(keys.begin() + i, keys.begin() + j, less);
    i = j;
  }
}

/// Sorts the used vertices into octree order: by Morton code, then by
/// position (so that equal coordinates are neighbours), then by index;
/// unused ones (code kUnused) last, by index, their positions unread.
/// `keys[i]` is a vertex's top 32 code bits above its index (8 bytes an
/// item: what is moved), `code[v]` its whole code. The top 32 bits are the
/// octree down to depth 10 and a bit; runs of equal top bits are vertices in
/// one cell of side 1/1024 of the bounding cube's or less, rarely more than
/// one, so a radix sort of 32 bits and a sort of those runs give the order of
/// a sort by the whole code at half the passes (sort_range). From kTwoParts
/// keys on, the keys are first split (stably, each thread scattering its half
/// of them) into the two ranges of the top 10 bits below and from the value
/// that halves them, and each range is sorted on a thread of its own: each
/// writes only its own memory (two threads scattering into the same buckets
/// shared the cache lines where their parts of a bucket meet and were slower
/// than one).
void sort_vertices(Buffer<std::uint64_t>& keys, std::span<const std::uint64_t> code,
                   std::span<const Vec3> positions) {
  const std::size_t n = keys.size();
  Buffer<std::uint64_t> tmp(n);
  if (parts_of(n) == 1) return sort_range(keys, tmp, code, positions);
  constexpr std::size_t kTop = 1024;
  auto top_digit = [](std::uint64_t key) { return static_cast<std::size_t>(key >> 54); };
  const std::array<std::size_t, 3> half = halves(n, 2);
  std::array<std::array<std::uint32_t, kTop>, 2> count;
  for_parts(2, [&](std::size_t q) {
    count[q].fill(0);
    for (std::size_t i = half[q]; i < half[q + 1]; ++i) ++count[q][top_digit(keys[i])];
  });
  // The split: the first top value at which the keys below reach half.
  std::size_t split = 0, below = 0;
  while (split < kTop && 2 * below < n) below += count[0][split] + count[1][split], ++split;
  if (below == 0 || below == n) return sort_range(keys, tmp, code, positions);
  // Where each half's keys go in each range: the first half's first (stable).
  std::array<std::array<std::size_t, 2>, 2> at;  // [half][range]
  std::size_t low0 = 0;
  for (std::size_t d = 0; d < split; ++d) low0 += count[0][d];
  at[0] = {0, below};
  at[1] = {low0, below + (half[1] - low0)};
  for_parts(2, [&](std::size_t q) {
    std::size_t low = at[q][0], high = at[q][1];
    for (std::size_t i = half[q]; i < half[q + 1]; ++i) {
      const std::uint64_t key = keys[i];
      if (top_digit(key) < split) {
        tmp[low++] = key;
      } else {
        tmp[high++] = key;
      }
    }
  });
  keys.swap(tmp);
  const std::array<std::size_t, 3> range{0, below, n};
  for_parts(2, [&](std::size_t r) {
    const std::size_t size = range[r + 1] - range[r];
    sort_range(std::span(keys).subspan(range[r], size), std::span(tmp).subspan(range[r], size),
               code, positions);
  });
}

/// Depth of the deepest octree cell two codes share (kMaxDepth if equal).
int common_depth(std::uint64_t a, std::uint64_t b) {
  std::uint64_t x = a ^ b;
  if (x == 0) return kMaxDepth;
  int highest = 63 - std::countl_zero(x);
  return kMaxDepth - 1 - highest / 3;
}

// -------------------------------------------------------------------- quadrics

/// Q(x) = x^T A x - 2 b.x + c, A symmetric (a00 a01 a02 a11 a12 a22).
/// Without member initialisers, so that a Buffer of them resizes without
/// writing (a level's quadrics are written in parallel passes): Quadric{} is
/// the zero quadric.
struct Quadric {
  double a00, a01, a02, a11, a12, a22;
  double b0, b1, b2, c;

  Quadric& operator+=(const Quadric& o) {
    a00 += o.a00;
    a01 += o.a01;
    a02 += o.a02;
    a11 += o.a11;
    a12 += o.a12;
    a22 += o.a22;
    b0 += o.b0;
    b1 += o.b1;
    b2 += o.b2;
    c += o.c;
    return *this;
  }
  double operator()(double x, double y, double z) const {
    double ax = a00 * x + a01 * y + a02 * z;
    double ay = a01 * x + a11 * y + a12 * z;
    double az = a02 * x + a12 * y + a22 * z;
    return std::max(0.0, x * ax + y * ay + z * az - 2 * (b0 * x + b1 * y + b2 * z) + c);
  }
};

/// sqrt(x) for x >= 0, without std::sqrt's errno path (a possible library
/// call on the hot path of a loop keeps its values in memory).
inline double sqrt_nonnegative(double x) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_sqrt_sd(_mm_setzero_pd(), _mm_set_sd(x)));
#else
  return std::sqrt(x);
#endif
}
inline float sqrt_nonnegative(float x) {
#if defined(__SSE2__)
  return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x)));
#else
  return std::sqrt(x);
#endif
}

/// Adds the area-weighted quadric of the plane of each triangle (p, q, r)
/// (area x the squared distance to the plane; zero for a degenerate
/// triangle) to the quadrics of the cells its corners map to (`mapped`, in
/// triangle order). With n = (q - p) x (r - p) unnormalised, area = |n| / 2
/// and the unit normal n / |n|, every coefficient is a product of n and n.p
/// over 2 |n|: one square root and one division. In blocks, one pass each
/// for the normals, the square roots and divisions (two at a time) and the
/// quadrics: one triangle's chain of latencies (gathers, cross product,
/// square root, division, the sums into its cells) no longer holds the next
/// triangle back (~7 % of the bunny chain).
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
        k.b0 = -d[i] * sx;
        k.b1 = -d[i] * sy;
        k.b2 = -d[i] * sz;
        k.c = s[i] * d[i] * d[i];
      }
      for (std::uint32_t c : mapped[f0 + i]) quadric[c] += k;
    }
  }
}

/// Minimum of q, regularised towards x0: the minimum of
/// Q(x) + lambda |x - x0|^2 with lambda = kRankTolerance x trace(A), one 3x3
/// solve. Along directions where A is strong (eigenvalue >> lambda) this is
/// the quadric's optimum; along weak ones (a flat or straight cell, where Q
/// has no unique minimum) it stays at x0, like Lindstrom's truncated
/// pseudo-inverse, without its eigen-decomposition.
std::array<double, 3> quadric_minimum(const Quadric& q, const std::array<double, 3>& x0) {
  double lambda = kRankTolerance * (q.a00 + q.a11 + q.a22);
  if (!(lambda > 0)) return x0;
  double m00 = q.a00 + lambda, m11 = q.a11 + lambda, m22 = q.a22 + lambda;
  double m01 = q.a01, m02 = q.a02, m12 = q.a12;
  // Solve M d = b - A x0 for the step d from x0 (Cramer; M is positive definite).
  double r0 = q.b0 - (q.a00 * x0[0] + q.a01 * x0[1] + q.a02 * x0[2]);
  double r1 = q.b1 - (q.a01 * x0[0] + q.a11 * x0[1] + q.a12 * x0[2]);
  double r2 = q.b2 - (q.a02 * x0[0] + q.a12 * x0[1] + q.a22 * x0[2]);
  double c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22, c02 = m01 * m12 - m02 * m11;
  double c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
  double det = m00 * c00 + m01 * c01 + m02 * c02;
  if (!(det > 0)) return x0;
  return {x0[0] + (c00 * r0 + c01 * r1 + c02 * r2) / det,
          x0[1] + (c01 * r0 + c11 * r1 + c12 * r2) / det,
          x0[2] + (c02 * r0 + c12 * r1 + c22 * r2) / det};
}

// ------------------------------------------------------------------- the cut

/// One cut of the octree: the vertices of a level (in Morton order) and the
/// triangles and lines over them.
struct Cut {
  Buffer<Vec3> pos;
  Buffer<std::uint32_t> weight;  ///< distinct input coordinates represented
  Buffer<std::uint32_t> orig;    ///< input vertex giving attributes / vertex_map
  Buffer<std::uint64_t> code;    ///< Morton code of an input coordinate in the cell
  Buffer<Quadric> quadric;       ///< empty unless the quadric heuristic is on
  Buffer<Triangle> tris;
  Buffer<std::uint32_t> tri_origin;  ///< input triangle of each triangle
  Buffer<Segment> lines;
  int depth = kMaxDepth + 1;  ///< cut depth (level 0: below the finest cell)

  std::size_t size() const { return pos.size(); }
};

/// Open-addressing set of line segments ({lo, hi}); insert() says whether
/// the segment was new.
class SegmentSet {
 public:
  /// Empties the set, sized for `expected` segments (keeps its memory).
  void reset(std::size_t expected) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, {kNone, kNone});
    mask_ = cap - 1;
  }
  bool insert(const Segment& key) {
    std::uint64_t h = 0;
    for (std::uint32_t k : key) h = (h ^ k) * 0x9e3779b97f4a7c15ull;
    std::size_t i = (h ^ (h >> 29)) & mask_;
    while (true) {
      auto& s = slots_[i];
      if (s[0] == kNone) {
        s = key;
        return true;
      }
      if (s == key) return false;
      i = (i + 1) & mask_;
    }
  }

 private:
  Buffer<Segment> slots_;
  std::size_t mask_ = 0;
};

/// The buffers of remap_faces, kept over the levels of one call: allocating
/// them afresh per level costs page faults (freed large blocks go back to
/// the system) more than the work in them.
struct RemapScratch {
  struct Entry {
    std::uint32_t k1, k2, index;  // the canonical rotation's last corners; position in the run
  };
  Buffer<Entry> run;
  Buffer<Triangle> run_tris;
  Buffer<std::uint32_t> run_origin;
  Buffer<std::uint32_t> run_start;   // vertex -> its run of kept triangles (when there are lines)
  Buffer<std::uint32_t> off, upper;  // vertex -> the larger ends of the third edges at it
  Buffer<Segment> not_edges;
  SegmentSet seen_lines;
  Buffer<std::uint32_t> keep;  ///< the result: new vertex -> kept index or kNone
};

/// The last two corners of triangle t's rotation that starts at its corner
/// `vertex` (orientation kept), as one 64-bit key (compared
/// lexicographically); selects, not branches: which corner is `vertex` is
/// data.
inline std::uint64_t rotation_key(const Triangle& t, std::uint32_t vertex) {
  const bool first = t[0] == vertex, second = t[1] == vertex;
  const std::uint32_t k1 = first ? t[1] : second ? t[2] : t[0];
  const std::uint32_t k2 = first ? t[2] : second ? t[0] : t[1];
  return std::uint64_t(k1) << 32 | k2;
}

/// dedupe_run (below) for any n: out of line, for the runs of more than
/// three triangles and those with doublets.
[[gnu::noinline]] std::size_t dedupe_long_run(Triangle* tris, std::uint32_t* origin, std::size_t n,
                                              std::uint32_t vertex, RemapScratch& scratch) {
  using Entry = RemapScratch::Entry;
  auto key = [&](const Triangle& t) { return rotation_key(t, vertex); };
  if (n < 2) return n;
  // Up to 8 without doublets (nearly every run): each triangle goes to its
  // rank among the keys, counted without branches (an insertion sort's
  // swaps are data the branch predictor cannot learn).
  constexpr std::size_t kRanked = 8;
  if (n <= kRanked) {
    std::uint64_t k[kRanked];
    for (std::size_t i = 0; i < n; ++i) k[i] = key(tris[i]);
    bool doublet = false;
    for (std::size_t i = 1; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j) doublet |= k[j] == k[i];
    if (!doublet) {
      Triangle t[kRanked];
      std::uint32_t o[kRanked];
      std::copy_n(tris, n, t);
      std::copy_n(origin, n, o);
      for (std::size_t i = 0; i < n; ++i) {
        std::size_t rank = 0;
        for (std::size_t j = 0; j < n; ++j) rank += k[j] < k[i];
        tris[rank] = t[i];
        origin[rank] = o[i];
      }
      return n;
    }
  }
  constexpr std::size_t kSmall = 16;
  if (n <= kSmall) {
    // On the stack, each triangle as its key, origin and rotation (which
    // corner is `vertex`): the kept ones are rebuilt from these. (Copying
    // the triangles aside instead compiles to a block copy whose start-up
    // cost exceeds the copy: the largest single cost of the first level.)
    struct Item {
      std::uint64_t key;
      std::uint32_t origin;
      std::uint32_t rotation;
    };
    Item e[kSmall];
    for (std::size_t i = 0; i < n; ++i) {
      const Triangle& t = tris[i];
      const std::uint32_t rotation = t[0] == vertex ? 0 : t[1] == vertex ? 1 : 2;
      e[i] = {key(t), origin[i], rotation};
    }
    for (std::size_t i = 1; i < n; ++i)  // insertion sort, stable
      for (std::size_t j = i; j > 0 && e[j].key < e[j - 1].key; --j) std::swap(e[j], e[j - 1]);
    std::size_t out = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0 && e[i].key == e[i - 1].key) continue;
      const auto k1 = static_cast<std::uint32_t>(e[i].key >> 32);
      const auto k2 = static_cast<std::uint32_t>(e[i].key);
      tris[out] = e[i].rotation == 0   ? Triangle{vertex, k1, k2}
                  : e[i].rotation == 1 ? Triangle{k2, vertex, k1}
                                       : Triangle{k1, k2, vertex};
      origin[out] = e[i].origin;
      ++out;
    }
    return out;
  }
  auto& run = scratch.run;
  run.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = key(tris[i]);
    run[i] = {std::uint32_t(k >> 32), std::uint32_t(k), static_cast<std::uint32_t>(i)};
  }
  std::sort(run.begin(), run.end(), [](const Entry& a, const Entry& b) {
    if (a.k1 != b.k1) return a.k1 < b.k1;
    if (a.k2 != b.k2) return a.k2 < b.k2;
    return a.index < b.index;
  });
  scratch.run_tris.assign(tris, tris + n);
  scratch.run_origin.assign(origin, origin + n);
  std::size_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && run[i].k1 == run[i - 1].k1 && run[i].k2 == run[i - 1].k2) continue;
    tris[out] = scratch.run_tris[run[i].index];
    origin[out] = scratch.run_origin[run[i].index];
    ++out;
  }
  return out;
}

/// Sorts the run [tris, tris + n) of triangles whose smallest corner is
/// `vertex` (and their origins) by canonical rotation (`vertex` first,
/// orientation kept; ties in run order) and squeezes out the doublets (equal
/// rotations: the first stays); returns how many are left, at the front.
/// Runs of two and three (nine in ten) are inlined into the callers.
inline std::size_t dedupe_run(Triangle* tris, std::uint32_t* origin, std::size_t n,
                              std::uint32_t vertex, RemapScratch& scratch) {
  auto key = [&](const Triangle& t) { return rotation_key(t, vertex); };
  if (n < 2) return n;
  if (n == 2) {  // the commonest run: its order by stores to computed slots, not a branch
    const std::uint64_t k0 = key(tris[0]), k1 = key(tris[1]);
    if (k0 == k1) return 1;
    const std::size_t second = k1 < k0;  // where the first goes
    const Triangle t0 = tris[0], t1 = tris[1];
    const std::uint32_t o0 = origin[0], o1 = origin[1];
    tris[second] = t0;
    tris[1 - second] = t1;
    origin[second] = o0;
    origin[1 - second] = o1;
    return 2;
  }
  if (n == 3) {  // each to its rank among the keys
    const std::uint64_t k0 = key(tris[0]), k1 = key(tris[1]), k2 = key(tris[2]);
    if (k0 != k1 && k0 != k2 && k1 != k2) {
      const std::size_t r0 = (k1 < k0) + (k2 < k0), r1 = (k0 < k1) + (k2 < k1),
                        r2 = (k0 < k2) + (k1 < k2);
      const Triangle t0 = tris[0], t1 = tris[1], t2 = tris[2];
      const std::uint32_t o0 = origin[0], o1 = origin[1], o2 = origin[2];
      tris[r0] = t0;
      tris[r1] = t1;
      tris[r2] = t2;
      origin[r0] = o0;
      origin[r1] = o1;
      origin[r2] = o2;
      return 3;
    }
  }
  return dedupe_long_run(tris, origin, n, vertex, scratch);
}

void finish_faces(std::span<const Segment> lines, std::span<const std::uint32_t> vertex_map,
                  std::size_t new_count, Buffer<Segment>& line_candidates, Cut& to,
                  RemapScratch& scratch);

/// Builds the faces of `to` (which holds the new vertices, new_count of them)
/// from the previous level's faces: `mapped(i)` for i < count is the i-th
/// triangle with its corners already mapped to new vertices, and the triangles
/// with three distinct corners must come sorted by their smallest corner (they
/// do: the previous level's triangles are sorted by smallest vertex and the
/// map to cells is monotone); `origin(i)` is its input triangle. Applies the
/// face rules; reads nothing of `to` but its faces, so that it can run beside
/// the choice of the new vertices (number_used_vertices and compact_vertices then drop those
/// nothing uses). `line_candidates` holds the lines found before (they come
/// first); the remapped `lines` follow.
///
/// | remapped triangle          | becomes                                    |
/// |----------------------------|--------------------------------------------|
/// | 3 distinct vertices        | kept, unless an equal rotation was kept    |
/// | 2 distinct vertices        | a line (dropped if no_lines)               |
/// | 1 vertex                   | dropped                                    |
/// | remapped line, 2 vertices  | a line                                     |
/// | line, 1 vertex             | dropped                                    |
/// | line equal to a kept line or to an edge of a kept triangle | dropped    |
///
/// A doublet has the same smallest corner, so it lies in the same run of
/// consecutive triangles: each run is sorted by its canonical rotation (the
/// smallest corner first, orientation kept) and the first of equal keys kept.
/// The output stays sorted by smallest vertex, so that neighbours in memory
/// are neighbours in space for the levels to come.
template <class Mapped, class Origin>
void remap_faces(std::size_t count, const Mapped& mapped, const Origin& origin,
                 std::span<const Segment> lines, std::span<const std::uint32_t> vertex_map,
                 std::size_t new_count, bool no_lines, Buffer<Segment>& line_candidates, Cut& to,
                 RemapScratch& scratch) {
  // Triangles go straight to the output; a run of more than one (same
  // smallest corner) is then sorted in place by its canonical rotation and
  // the doublets squeezed out. Every triangle is written at the next free
  // slot of the triangles and of the line candidates, and each count moves
  // on by 0 or 1 (whether a triangle collapses, and to what, is data the
  // branch predictor cannot learn); the arrays are sized for every triangle
  // (uninitialised) and cut back after.
  to.lines.clear();
  to.tris.resize(count);
  to.tri_origin.resize(count);
  const std::size_t lines_before = line_candidates.size();
  line_candidates.resize(lines_before + count);
  Triangle* tris = to.tris.data();
  std::uint32_t* tri_origin = to.tri_origin.data();
  Segment* candidate = line_candidates.data() + lines_before;
  std::size_t kept = 0, candidates = 0, run_begin = 0;
  std::uint32_t run_vertex = kNone;
  auto flush = [&] {
    kept = run_begin + dedupe_run(tris + run_begin, tri_origin + run_begin, kept - run_begin,
                                  run_vertex, scratch);
  };
  for (std::size_t f = 0; f < count; ++f) {
    const Triangle t = mapped(f);
    const std::uint32_t a = t[0], b = t[1], c = t[2];
    const bool ab = a == b, bc = b == c, ca = c == a;
    const bool keep = !(ab | bc | ca);
    const std::uint32_t other = a != b ? b : c;
    candidate[candidates] = {std::min(a, other), std::max(a, other)};
    candidates += !keep & !no_lines & !(ab & bc);
    const std::uint32_t lo = std::min({a, b, c});
    if (keep & (lo != run_vertex)) {
      assert(run_vertex == kNone || lo > run_vertex);
      if (kept - run_begin > 1) flush();  // most runs are one triangle
      run_vertex = lo;
      run_begin = kept;
    }
    tris[kept] = t;
    tri_origin[kept] = origin(f);
    kept += keep;
  }
  if (kept - run_begin > 1) flush();
  to.tris.resize(kept);
  to.tri_origin.resize(kept);
  line_candidates.resize(lines_before + candidates);
  finish_faces(lines, vertex_map, new_count, line_candidates, to, scratch);
}

/// The second half of remap_faces, once `to.tris` holds the kept triangles:
/// appends the previous level's lines, mapped, to `line_candidates` and
/// keeps in `to.lines` those that are neither an edge of a kept triangle nor
/// a line seen before.
void finish_faces(std::span<const Segment> lines, std::span<const std::uint32_t> vertex_map,
                  std::size_t new_count, Buffer<Segment>& line_candidates, Cut& to,
                  RemapScratch& scratch) {
  for (const Segment& s : lines) {
    std::uint32_t a = vertex_map[s[0]], b = vertex_map[s[1]];
    if (a != b) line_candidates.push_back({std::min(a, b), std::max(a, b)});
  }

  if (!line_candidates.empty()) {
    // For "a line equal to an edge of a triangle": the kept triangles come
    // sorted by smallest corner, so a line (lo, hi) is an edge of one of
    // them exactly when hi is a corner of one in lo's run (those whose
    // smallest corner is lo) or (lo, hi) is the third edge of one (the edge
    // away from its smallest corner, of a triangle whose smallest corner is
    // below lo). The runs: run_start[v + 1] is first set to one past the
    // last triangle whose smallest corner is v (0 when there is none), then
    // to the largest such value up to v. The third edges: each listed at its
    // smaller end as its larger one (counts into off[v + 1], starts, fill
    // with off[v]++, shift back).
    auto& run_start = scratch.run_start;
    auto& off = scratch.off;
    auto& upper = scratch.upper;
    run_start.assign(new_count + 1, 0);
    off.assign(new_count + 1, 0);
    const auto nt = static_cast<std::uint32_t>(to.tris.size());
    for (std::uint32_t f = 0; f < nt; ++f) {
      const Triangle& t = to.tris[f];
      const std::uint32_t lo = std::min({t[0], t[1], t[2]});
      assert(f == 0 || lo >= std::min({to.tris[f - 1][0], to.tris[f - 1][1], to.tris[f - 1][2]}));
      run_start[lo + 1] = f + 1;
      // The third edge's smaller end: the middle corner.
      ++off[std::max(std::min(t[0], t[1]), std::min(std::max(t[0], t[1]), t[2])) + 1];
    }
    for (std::size_t v = 0; v < new_count; ++v) {
      run_start[v + 1] = std::max(run_start[v + 1], run_start[v]);
      off[v + 1] += off[v];
    }
    upper.resize(off[new_count]);
    for (const Triangle& t : to.tris) {
      const std::uint32_t hi = std::max({t[0], t[1], t[2]});
      const std::uint32_t mid =
          std::max(std::min(t[0], t[1]), std::min(std::max(t[0], t[1]), t[2]));
      upper[off[mid]++] = hi;
    }
    std::copy_backward(off.begin(), off.end() - 1, off.end());
    off[0] = 0;
    // Most candidates are edges of kept triangles: the set of lines seen is
    // sized for the others.
    auto& not_edges = scratch.not_edges;
    not_edges.clear();
    for (const Segment& s : line_candidates) {
      bool is_edge = false;
      for (std::uint32_t f = run_start[s[0]]; f < run_start[s[0] + 1]; ++f) {
        const Triangle& t = to.tris[f];
        is_edge |= (t[0] == s[1]) | (t[1] == s[1]) | (t[2] == s[1]);
      }
      for (std::uint32_t k = off[s[0]]; k < off[s[0] + 1]; ++k) is_edge |= upper[k] == s[1];
      if (!is_edge) not_edges.push_back(s);
    }
    scratch.seen_lines.reset(not_edges.size());
    for (const Segment& s : not_edges)
      if (scratch.seen_lines.insert(s)) to.lines.push_back(s);
  }
}

/// Dropping the vertices no triangle or line uses, keeping the order, in two
/// steps: once `to` has its faces (remap_faces), of new_count vertices,
/// number_used_vertices leaves the map (new vertex -> kept index or kNone) in
/// `scratch.keep`, renumbers the faces and returns how many are kept (it reads
/// nothing but the faces, so it can run beside the choice of the vertices);
/// once the vertices are there too, compact_vertices drops the others.
std::size_t number_used_vertices(std::size_t new_count, Cut& to, RemapScratch& scratch) {
  auto& keep = scratch.keep;
  keep.assign(new_count, kNone);
  for (const Triangle& t : to.tris) keep[t[0]] = keep[t[1]] = keep[t[2]] = 0;
  for (const Segment& s : to.lines) keep[s[0]] = keep[s[1]] = 0;
  std::uint32_t kept = 0;
  for (std::size_t v = 0; v < new_count; ++v)
    if (keep[v] != kNone) keep[v] = kept++;
  if (kept == new_count) return kept;  // every vertex used: the identity
  for (Triangle& t : to.tris)
    for (std::uint32_t& v : t) v = keep[v];
  for (Segment& s : to.lines)
    for (std::uint32_t& v : s) v = keep[v];
  return kept;
}

void compact_vertices(std::size_t new_count, std::size_t kept, Cut& to,
                      const RemapScratch& scratch) {
  if (kept == new_count) return;
  const auto& keep = scratch.keep;
  auto compact = [&](auto& array) {
    if (array.empty()) return;
    for (std::size_t v = 0; v < new_count; ++v)
      if (keep[v] != kNone) array[keep[v]] = array[v];
    array.resize(kept);
  };
  compact(to.pos);
  compact(to.weight);
  compact(to.orig);
  compact(to.code);
  compact(to.quadric);
}

// ------------------------------------------------------ choosing representatives

struct Weights {
  double area = 0, volume = 0, mean = 0, quadric = 0;
};

/// The triangles of a level around each cell of the next: for cell j, the
/// entries [start[j], start[j + 1]) of `entry`, each 4 x triangle + the index
/// of its one corner inside the cell (0, 1, 2), or + 3 when two or three
/// corners are inside (it collapses). One pass over the triangles, in
/// triangle order, so each cell's list is sorted.
struct CellFaces {
  Buffer<std::uint32_t> start;
  Buffer<std::uint32_t> entry;

  /// `mapped`: the triangles with their corners replaced by their cells.
  /// Lists only the cells with `wanted[cell]` (the others get empty lists).
  void build(std::span<const Triangle> mapped, std::span<const char> wanted) {
    count(mapped, wanted);
    fill(mapped, wanted);
  }

  /// build in two passes over the triangles, which may run on different
  /// threads, one after the other: count into start[cell + 1]; then turn
  /// the counts into starts, fill with start[cell]++ (which leaves the
  /// starts shifted down by one cell) and shift them back.
  void count(std::span<const Triangle> mapped, std::span<const char> wanted) {
    start.assign(wanted.size() + 1, 0);
    std::uint32_t* counts = start.data() + 1;
    for (const Triangle& t : mapped) {
      const auto add = adds(t[0], t[1], t[2], wanted);
      counts[t[0]] += add[0];
      counts[t[1]] += add[1];
      counts[t[2]] += add[2];
    }
  }
  void fill(std::span<const Triangle> mapped, std::span<const char> wanted) {
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

 private:
  /// Whether each corner starts an entry: its cell is wanted and no earlier
  /// corner of the triangle is in it (0 or 1, for adding). Branch-free:
  /// whether corners share a cell is data the branch predictor cannot learn
  /// (about half the triangles collapse at a level), so each corner adds 0
  /// or 1 (an entry only at a cell's first corner).
  static std::array<std::uint32_t, 3> adds(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                           std::span<const char> wanted) {
    const std::uint32_t ab = a != b, ac = a != c, bc = b != c;
    return {std::uint32_t(wanted[a]), ab & std::uint32_t(wanted[b]),
            ac & bc & std::uint32_t(wanted[c])};
  }
};

/// What every cell of a level reads.
struct LevelContext {
  const Cut& prev;
  /// The triangles around each cell of several vertices; null when neither
  /// area nor volume is weighted or the level has no triangle.
  const CellFaces* faces;
  Weights weights;
};

/// Four floats, one per triangle or per candidate: the unit of the scoring
/// loops (SSE where the target has it; the library sqrt may set errno, which
/// keeps compilers from vectorising it in plain loops). A mask has all bits
/// of a lane set or none.
struct F4 {
#if defined(__SSE2__)
  __m128 v;
  static F4 load(const float* p) {
    return {_mm_loadu_ps(p)};
  }
  static F4 set(float a, float b, float c, float d) {
    return {_mm_setr_ps(a, b, c, d)};
  }
  /// The mask of the lanes whose integer equals `value`.
  static F4 lanes_equal(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                        std::uint32_t value) {
    const __m128i x = _mm_setr_epi32(int(a), int(b), int(c), int(d));
    return {_mm_castsi128_ps(_mm_cmpeq_epi32(x, _mm_set1_epi32(int(value))))};
  }
  /// The mask of the first n lanes.
  static F4 lanes_below(std::uint32_t n) {
    return {_mm_castsi128_ps(_mm_cmplt_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(int(n))))};
  }
  /// The lanes set in b but not in a.
  friend F4 and_not(F4 a, F4 b) {
    return {_mm_andnot_ps(a.v, b.v)};
  }
  /// a where the mask is set, else b.
  friend F4 select(F4 mask, F4 a, F4 b) {
    return {_mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v))};
  }
  /// a where the mask is set, else +0.
  friend F4 operator&(F4 a, F4 mask) {
    return {_mm_and_ps(a.v, mask.v)};
  }
  /// Rows to columns.
  friend void transpose(F4& a, F4& b, F4& c, F4& d) {
    _MM_TRANSPOSE4_PS(a.v, b.v, c.v, d.v);
  }
  static F4 splat(float x) {
    return {_mm_set1_ps(x)};
  }
  void store(float* p) const {
    _mm_storeu_ps(p, v);
  }
  friend F4 operator+(F4 a, F4 b) {
    return {_mm_add_ps(a.v, b.v)};
  }
  friend F4 operator-(F4 a, F4 b) {
    return {_mm_sub_ps(a.v, b.v)};
  }
  friend F4 operator*(F4 a, F4 b) {
    return {_mm_mul_ps(a.v, b.v)};
  }
  friend F4 sqrt(F4 a) {
    return {_mm_sqrt_ps(a.v)};
  }
  friend F4 abs(F4 a) {
    return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)};
  }
#else
  std::array<float, 4> v;
  template <class Op>
  static F4 map(Op op) {
    F4 r;
    for (int l = 0; l < 4; ++l) r.v[l] = op(l);
    return r;
  }
  static F4 load(const float* p) {
    return map([&](int l) { return p[l]; });
  }
  static F4 set(float a, float b, float c, float d) {
    return {{a, b, c, d}};
  }
  static F4 lanes_equal(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                        std::uint32_t value) {
    const std::uint32_t x[4] = {a, b, c, d};
    return map([&](int l) { return std::bit_cast<float>(x[l] == value ? ~0u : 0u); });
  }
  static F4 lanes_below(std::uint32_t n) {
    return map([&](int l) { return std::bit_cast<float>(std::uint32_t(l) < n ? ~0u : 0u); });
  }
  friend F4 and_not(F4 a, F4 b) {
    return map([&](int l) {
      return std::bit_cast<float>(~std::bit_cast<std::uint32_t>(a.v[l]) &
                                  std::bit_cast<std::uint32_t>(b.v[l]));
    });
  }
  friend F4 select(F4 mask, F4 a, F4 b) {
    return map([&](int l) { return std::bit_cast<std::uint32_t>(mask.v[l]) ? a.v[l] : b.v[l]; });
  }
  friend F4 operator&(F4 a, F4 mask) {
    return map([&](int l) { return std::bit_cast<std::uint32_t>(mask.v[l]) ? a.v[l] : 0.0f; });
  }
  friend void transpose(F4& a, F4& b, F4& c, F4& d) {
    const F4 r[4] = {a, b, c, d};
    F4* out[4] = {&a, &b, &c, &d};
    for (int i = 0; i < 4; ++i) *out[i] = map([&](int l) { return r[l].v[i]; });
  }
  static F4 splat(float x) {
    return map([&](int) { return x; });
  }
  void store(float* p) const {
    std::copy(v.begin(), v.end(), p);
  }
  friend F4 operator+(F4 a, F4 b) {
    return map([&](int l) { return a.v[l] + b.v[l]; });
  }
  friend F4 operator-(F4 a, F4 b) {
    return map([&](int l) { return a.v[l] - b.v[l]; });
  }
  friend F4 operator*(F4 a, F4 b) {
    return map([&](int l) { return a.v[l] * b.v[l]; });
  }
  friend F4 sqrt(F4 a) {
    return map([&](int l) { return std::sqrt(a.v[l]); });
  }
  friend F4 abs(F4 a) {
    return map([&](int l) { return std::abs(a.v[l]); });
  }
#endif
};
constexpr std::size_t kLanes = 4;

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
Choice choose_representative(const LevelContext& ctx, std::uint32_t cell, std::uint32_t begin,
                             std::uint32_t end, bool has_faces, const Vec3& cell_lo,
                             float cell_size, const Quadric& q, Scratch& s) {
  const Cut& prev = ctx.prev;
  // Weighted mean: the weights are the coordinates each vertex stands for.
  double mx = 0, my = 0, mz = 0, total = 0;
  for (std::uint32_t i = begin; i < end; ++i) {
    double wi = prev.weight[i];
    mx += wi * prev.pos[i].x;
    my += wi * prev.pos[i].y;
    mz += wi * prev.pos[i].z;
    total += wi;
  }
  mx /= total;
  my /= total;
  mz /= total;
  auto mean_distance = [&](const Vec3& p) {
    double dx = p.x - mx, dy = p.y - my, dz = p.z - mz;
    return sqrt_nonnegative(dx * dx + dy * dy + dz * dz);
  };
  const Vec3 origin{float(mx), float(my), float(mz)};

  // Candidates: the cell's vertices (at most kMaxCandidates, nearest the mean).
  s.n = 0;
  auto add_candidate = [&](const Vec3& p, std::uint32_t orig) {
    s.candidate[s.n] = p;
    s.candidate_orig[s.n] = orig;
    ++s.n;
  };
  if (end - begin > kMaxCandidates) {
    s.order.resize(end - begin);
    std::iota(s.order.begin(), s.order.end(), begin);
    std::nth_element(s.order.begin(), s.order.begin() + kMaxCandidates, s.order.end(),
                     [&](std::uint32_t a, std::uint32_t b) {
                       double da = mean_distance(prev.pos[a]), db = mean_distance(prev.pos[b]);
                       return da < db || (da == db && a < b);
                     });
    s.order.resize(kMaxCandidates);
    std::sort(s.order.begin(), s.order.end());
    for (std::uint32_t i : s.order) add_candidate(prev.pos[i], prev.orig[i]);
  } else {
    for (std::uint32_t i = begin; i < end; ++i) add_candidate(prev.pos[i], prev.orig[i]);
  }

  // | cell has triangles | quadric weight | heuristics used                         |
  // |--------------------|----------------|-----------------------------------------|
  // | no (line set)      | any            | weighted mean alone                     |
  // | yes                | 0              | area, volume, mean (the thesis)         |
  // | yes                | > 0            | all four, Lindstrom's point a candidate |
  const Weights use = has_faces ? ctx.weights : Weights{0, 0, 1, 0};
  if (use.quadric > 0) {
    auto x = quadric_minimum(q, {mx, my, mz});
    Vec3 p{float(x[0]), float(x[1]), float(x[2])};
    if (is_finite(p)) {
      p = min(max(p, cell_lo), cell_lo + Vec3{cell_size, cell_size, cell_size});
      // Its attributes: those of the nearest vertex of the cell.
      std::uint32_t nearest = begin;
      float best = std::numeric_limits<float>::infinity();
      for (std::uint32_t i = begin; i < end; ++i) {
        float d = length_squared(prev.pos[i] - p);
        if (d < best) best = d, nearest = i;
      }
      add_candidate(p, prev.orig[nearest]);
    }
  }

  // The terms that need no triangle, and the contenders.
  const std::size_t n = s.n;
  std::array<double, 4> largest{0, 0, 0, 0};
  double least_quadric = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& x = s.candidate[k];
    auto& h = s.score[k];
    h = {0, 0, 0, 0};
    if (use.mean > 0) h[2] = mean_distance(x);
    if (use.quadric > 0) h[3] = q(x.x, x.y, x.z);
    largest[2] = std::max(largest[2], h[2]);
    largest[3] = std::max(largest[3], h[3]);
    least_quadric = std::min(least_quadric, h[3]);
  }
  s.m = 0;
  if (use.quadric > 0 && largest[3] > 0) {
    const double slack = (use.area + use.volume + (largest[2] > 0 ? use.mean : 0)) * largest[3];
    for (std::size_t k = 0; k < n; ++k) {  // branch-free: the outcome is data
      s.contender[s.m] = static_cast<std::uint32_t>(k);
      s.m += use.quadric * (s.score[k][3] - least_quadric) <= slack;
    }
  } else {
    for (std::size_t k = 0; k < n; ++k) s.contender[s.m++] = static_cast<std::uint32_t>(k);
  }
  const std::size_t m = s.m;
  const bool measure = ctx.faces != nullptr && (use.area > 0 || use.volume > 0);
  if (measure && m > 1) {
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3 r = s.candidate[s.contender[k]] - origin;
      s.cx[k] = r.x, s.cy[k] = r.y, s.cz[k] = r.z;
    }
    const double area_before =
        use.area > 0 ? use.volume > 0 ? score_faces<true, true>(ctx, cell, origin, s, m)
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
  if (m == 1) return {s.candidate[s.contender[0]], s.candidate_orig[s.contender[0]]};
  const double weight[4] = {use.area, use.volume, use.mean, use.quadric};
  double factor[4];
  for (int i = 0; i < 4; ++i)
    factor[i] = weight[i] > 0 && largest[i] > 0 ? weight[i] / largest[i] : 0;
  std::size_t best = s.contender[0];
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < m; ++c) {
    const auto& h = s.score[s.contender[c]];
    const double score = factor[0] * h[0] + factor[1] * h[1] + factor[2] * h[2] + factor[3] * h[3];
    if (score < best_score) best_score = score, best = s.contender[c];
  }
  return {s.candidate[best], s.candidate_orig[best]};
}

// ------------------------------------------------------------------- the chain

/// Runs body(lo, hi) over [0, n) in chunks of kChunk items, in parallel
/// when there is more than one: coarse enough that a task's work outweighs
/// its cost (an item of a pass over an array costs nanoseconds; choosing a
/// cell's representative, up to microseconds: kCellChunk).
template <std::size_t kChunk = 2048, class Body>
void for_chunks(std::size_t n, const Body& body) {
  if (n <= kChunk) {
    body(std::size_t(0), n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kChunk),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

/// Cells per task when choosing representatives: small enough that the small
/// levels of a chain (hundreds of cells) still run on every thread.
constexpr std::size_t kCellChunk = 128;

struct Octree {
  Vec3 lo;          ///< corner of the bounding cube
  double side = 1;  ///< its side
  /// Corner of the depth-`depth` cell holding `code`.
  Vec3 cell_lo(std::uint64_t code, int depth) const {
    int shift = kMaxDepth - depth;
    double unit = side / double(1u << kMaxDepth);
    auto axis = [&](int a) {
      std::uint32_t q = compact_bits(code >> (2 - a)) >> shift << shift;
      return static_cast<float>(lo[a] + q * unit);
    };
    return {axis(0), axis(1), axis(2)};
  }
  double cell_side(int depth) const { return side / double(1u << depth); }
};

/// Fills `r` (whose error, stop reason and detail are set) with the level in
/// `cut`: its mesh, the input's attributes of its vertices and triangles, the
/// vertex and face maps. Reads `input` and `cut` only.
void fill_result(const TriangleMesh& input, const Cut& cut, SimplifyResult& r) {
  TriangleMesh& m = r.mesh;
  m.positions.assign(cut.pos.begin(), cut.pos.end());
  m.triangles.assign(cut.tris.begin(), cut.tris.end());
  m.lines.assign(cut.lines.begin(), cut.lines.end());
  if (input.has_normals()) {
    m.normals.reserve(cut.size());
    for (std::uint32_t v : cut.orig) m.normals.push_back(input.normals[v]);
  }
  if (input.has_texcoords()) {
    m.texcoords.reserve(cut.size());
    for (std::uint32_t v : cut.orig) m.texcoords.push_back(input.texcoords[v]);
  }
  if (input.has_colors()) {
    m.colors.reserve(cut.size());
    for (std::uint32_t v : cut.orig) m.colors.push_back(input.colors[v]);
  }
  if (input.has_materials()) {
    m.materials.reserve(cut.tris.size());
    for (std::uint32_t f : cut.tri_origin) m.materials.push_back(input.materials[f]);
  }
  r.vertex_map.assign(cut.orig.begin(), cut.orig.end());
  r.face_map.assign(cut.tri_origin.begin(), cut.tri_origin.end());
}

/// Checks the input, marks the vertices a triangle or line uses (1 in
/// `used`) and returns the box around them. The passes over the triangles
/// and the vertices run in parallel; the triangles in two halves, each
/// marking a byte array of its own (one shared array bounced its cache lines
/// between the cores and was slower than one thread; bits made each mark a
/// read-modify-write, chained through memory when neighbouring triangles
/// share a word), or'ed after. Each error names the first offender, as one
/// pass in order would.
Box3 validate(const TriangleMesh& mesh, Buffer<std::uint8_t>& used) {
  const std::size_t n = mesh.vertex_count(), nf = mesh.triangles.size();
  auto out_of_range = [&](const char* what, std::size_t i, std::uint32_t v) {
    return DataError(
        fmt::format("vertex clustering: {} {} uses vertex {} of only {}", what, i, v, n));
  };
  // Marks triangles [lo, hi); returns the first out of range, or nf.
  auto mark = [&](std::size_t lo, std::size_t hi, Buffer<std::uint8_t>& marks) {
    marks.assign(n, 0);
    for (std::size_t f = lo; f < hi; ++f) {
      const Triangle& t = mesh.triangles[f];
      if (std::max({t[0], t[1], t[2]}) >= n) return f;
      marks[t[0]] = marks[t[1]] = marks[t[2]] = 1;
    }
    return nf;
  };
  const std::size_t tri_parts = parts_of(nf);
  const std::array<std::size_t, 3> tri_bound = halves(nf, tri_parts);
  Buffer<std::uint8_t> second;
  std::array<std::size_t, 2> first_bad{nf, nf};
  for_parts(tri_parts, [&](std::size_t q) {
    first_bad[q] = mark(tri_bound[q], tri_bound[q + 1], q == 0 ? used : second);
  });
  const std::size_t bad = first_bad[0] < nf ? first_bad[0] : first_bad[1];
  if (bad < nf) {
    const Triangle& t = mesh.triangles[bad];
    throw out_of_range("triangle", bad, std::max({t[0], t[1], t[2]}));
  }
  // The lines mark the first array (the second is or'ed into it below, part
  // by part).
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    const Segment& s = mesh.lines[l];
    if (std::max(s[0], s[1]) >= n) throw out_of_range("line", l, std::max(s[0], s[1]));
    used[s[0]] = used[s[1]] = 1;
  }
  struct Bounds {
    Box3 box;
    std::size_t non_finite = SIZE_MAX;  ///< the first used vertex with one
  };
  // Two parts side by side for large inputs, each in plain float minima and
  // maxima (a task per few thousand vertices cost more than their work).
  std::array<Bounds, 2> part;
  const std::size_t parts = parts_of(n);
  const std::array<std::size_t, 3> bound = halves(n, parts);
  for_parts(parts, [&](std::size_t q) {
    const std::size_t v0 = bound[q], v1 = bound[q + 1];
    if (tri_parts == 2)
      for (std::size_t v = v0; v < v1; ++v) used[v] |= second[v];
    float lo[3] = {part[q].box.lo.x, part[q].box.lo.y, part[q].box.lo.z};
    float hi[3] = {part[q].box.hi.x, part[q].box.hi.y, part[q].box.hi.z};
    // Without branches on the data: an unused vertex takes the part of a
    // coordinate already in the box; finiteness is summed (x - x is 0 for a
    // finite x, NaN otherwise) and the first offender looked for only then.
    float not_finite = 0;
    for (std::size_t v = v0; v < v1; ++v) {
      const Vec3& p = mesh.positions[v];
      const bool in = used[v] != 0;
      for (int a = 0; a < 3; ++a) {
        const float x = p[a];
        not_finite += in ? x - x : 0.0f;
        lo[a] = std::min(lo[a], in ? x : lo[a]);
        hi[a] = std::max(hi[a], in ? x : hi[a]);
      }
    }
    if (not_finite != 0) {  // NaN compares unequal too
      for (std::size_t v = v0; v < v1; ++v) {
        if (used[v] && !is_finite(mesh.positions[v])) {
          part[q].non_finite = v;
          break;
        }
      }
    }
    part[q].box.lo = {lo[0], lo[1], lo[2]};
    part[q].box.hi = {hi[0], hi[1], hi[2]};
  });
  Bounds bounds = part[0];
  bounds.box.add(part[1].box);
  bounds.non_finite = std::min(part[0].non_finite, part[1].non_finite);
  if (bounds.non_finite != SIZE_MAX)
    throw DataError(
        fmt::format("vertex clustering: vertex {} has a non-finite coordinate", bounds.non_finite));
  auto check_size = [&](std::size_t size, std::size_t want, const char* what) {
    if (size != 0 && size != want)
      throw DataError(fmt::format("vertex clustering: {} {} for {}", size, what, want));
  };
  check_size(mesh.normals.size(), n, "normals");
  check_size(mesh.texcoords.size(), n, "texcoords");
  check_size(mesh.colors.size(), n, "colors");
  check_size(mesh.materials.size(), mesh.triangles.size(), "materials");
  return bounds.box;
}

}  // namespace

std::vector<SimplifyResult> vertex_clustering(const TriangleMesh& mesh,
                                              const VertexClusteringOptions& options) {
  Buffer<std::uint8_t> used;
  const Box3 box = validate(mesh, used);
  const std::size_t nv = mesh.vertex_count();
  const float min_diff = std::clamp(options.min_diff, 0.0f, 1.0f);
  Weights weights{
      std::max(0.0, double(options.area_weight)), std::max(0.0, double(options.volume_weight)),
      std::max(0.0, double(options.mean_weight)), std::max(0.0, double(options.quadric_weight))};
  const bool quadrics = weights.quadric > 0;

  // Level 0: the used coordinates, sorted into octree order, equal ones merged.
  Octree octree;
  octree.lo = box.empty() ? Vec3{} : box.lo;
  Vec3 size = box.size();
  octree.side = std::max({double(size.x), double(size.y), double(size.z)});
  if (!(octree.side > 0)) octree.side = 1;
  const double scale = double(1u << kMaxDepth) / octree.side;
  const std::uint32_t max_q = (1u << kMaxDepth) - 1;
  // Codes in parallel, one slot per vertex: an unused vertex gets kUnused
  // (above every 63-bit code), sorts last and is cut off. The order of equal
  // codes is settled by the sort, so its input order does not matter.
  Buffer<std::uint64_t> code(nv), order(nv);  // order: sort keys (see sort_vertices)
  for_chunks(nv, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t v = lo; v < hi; ++v) {
      if (!used[v]) {  // its coordinates may be anything
        code[v] = kUnused;
        order[v] = kUnused << 32 | v;
        continue;
      }
      // The offset from the box's corner is >= 0 (the rounding of an exact
      // difference >= 0), so truncation is the floor: no floor emulation
      // (baseline x86-64 has no rounding instruction).
      std::uint64_t c = 0;
      for (int a = 0; a < 3; ++a) {
        const double q = (double(mesh.positions[v][a]) - octree.lo[a]) * scale;
        const auto qi = static_cast<std::uint32_t>(std::min(q, double(max_q)));
        c |= morton_spread(qi) << (2 - a);
      }
      code[v] = c;
      order[v] = (c >> 31) << 32 | v;
    }
  });
  sort_vertices(order, code, mesh.positions);
  auto vertex = [&](std::size_t i) { return static_cast<std::uint32_t>(order[i]); };
  while (!order.empty() && code[vertex(order.size() - 1)] == kUnused) order.pop_back();

  // Every buffer below lives for the whole call and is reused level after
  // level (the two cuts swap): freeing and reallocating them per level would
  // fault their pages in again.
  RemapScratch remap_scratch;
  Buffer<Segment> line_candidates;
  Buffer<Triangle> mapped;  ///< a level's triangles, corners mapped to the next
  Cut cut;
  // Level-0 vertex of each used input vertex (unused ones are never read).
  Buffer<std::uint32_t> node_of(nv);
  {
    // Equal positions have equal codes: positions are compared only then.
    // One pass, each vertex's code and position gathered once (in octree
    // order they are scattered over memory); the arrays are sized for every
    // vertex and cut back. For large inputs in two parts side by side: the
    // second starts where the code changes (equal positions never straddle
    // the parts) and writes its vertices from its own first index on, as if
    // the first had merged none; if it had, they move down after.
    const std::size_t n = order.size();
    cut.pos.resize(n);
    cut.orig.resize(n);
    cut.code.resize(n);
    const std::size_t parts = parts_of(n);
    std::array<std::size_t, 3> bound = halves(n, parts);
    while (parts == 2 && bound[1] < n && code[vertex(bound[1])] == code[vertex(bound[1] - 1)])
      ++bound[1];
    std::array<std::size_t, 2> kept{0, 0};
    for_parts(parts, [&](std::size_t q) {
      const std::size_t begin = bound[q], end = bound[q + 1];
      std::size_t out = begin;
      std::uint64_t last_code = 0;
      Vec3 last_pos;
      // The gathers' addresses are known ahead: fetched kAhead vertices early.
      constexpr std::size_t kAhead = 16;
      for (std::size_t i = begin; i < end; ++i) {
        if (i + kAhead < end) {
          const std::uint32_t ahead = vertex(i + kAhead);
          __builtin_prefetch(&code[ahead]);
          __builtin_prefetch(&mesh.positions[ahead]);
          __builtin_prefetch(&node_of[ahead], 1);
        }
        const std::uint32_t v = vertex(i);
        const std::uint64_t c = code[v];
        const Vec3& p = mesh.positions[v];
        if (i == begin || c != last_code || p != last_pos) {
          cut.pos[out] = p;
          cut.orig[out] = v;
          cut.code[out] = c;
          ++out;
          last_code = c;
          last_pos = p;
        }
        node_of[v] = static_cast<std::uint32_t>(out - 1);
      }
      kept[q] = out - begin;
    });
    std::size_t count = kept[0];
    if (parts == 2) {
      if (const std::size_t gap = bound[1] - kept[0]; gap != 0) {
        auto move_down = [&](auto& array) {
          std::copy_n(array.begin() + bound[1], kept[1], array.begin() + kept[0]);
        };
        move_down(cut.pos);
        move_down(cut.orig);
        move_down(cut.code);
        for_chunks(n - bound[1], [&](std::size_t lo, std::size_t hi) {
          for (std::size_t i = bound[1] + lo; i < bound[1] + hi; ++i) node_of[vertex(i)] -= gap;
        });
      }
      count += kept[1];
    }
    cut.pos.resize(count);
    cut.orig.resize(count);
    cut.code.resize(count);
    cut.weight.assign(count, 1);
  }
  {
    // The input's triangles are in any order: sort those with three distinct
    // corners by their smallest corner (a stable counting sort of the mapped
    // triangles and their origins, so the remap reads them in sequence); the
    // others become line candidates in input order. For large inputs in two
    // parts side by side: each maps and counts one half of the triangles
    // into counters of its own (and collects its line candidates), a prefix
    // pass gives every vertex's run and each half's place in it (the first
    // half's triangles first: stable), then each part takes one half of the
    // vertices, scatters the triangles of their runs and squeezes the
    // doublets out of them, in place, run by run (each vertex's run is known
    // from the counts, so there is no looking for runs); the second half of
    // the runs then moves up if the first lost doublets. The first pass also
    // lists, per half of the vertices, the distinct triangles whose smallest
    // corner lies there, so that the second reads only its own.
    const std::size_t count = cut.pos.size();
    const std::size_t nf = mesh.triangles.size();
    const std::size_t parts = parts_of(nf);
    const std::array<std::size_t, 3> tri_bound = halves(nf, parts);
    auto distinct = [](const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[2] != t[0]; };
    mapped.resize(nf);
    std::array<Buffer<std::uint32_t>, 2> at;  // per part and vertex: count, then next slot
    std::array<Buffer<Segment>, 2> part_lines;
    std::array<std::size_t, 2> collapsed{0, 0};  // triangles with equal corners, per part
    const std::array<std::size_t, 3> vertex_bound = halves(count, parts);
    // [part][vertex half]: the distinct triangles of the part whose smallest
    // corner lies in the half, in order (sized for all of the part's).
    std::array<std::array<Buffer<std::uint32_t>, 2>, 2> own;
    std::array<std::array<std::size_t, 2>, 2> owned{};
    for_parts(parts, [&](std::size_t q) {
      at[q].assign(count, 0);
      for (Buffer<std::uint32_t>& list : own[q]) list.resize(tri_bound[q + 1] - tri_bound[q]);
      std::uint32_t* list[2] = {own[q][0].data(), own[q][1].data()};
      std::size_t listed[2] = {0, 0};
      for (std::size_t f = tri_bound[q]; f < tri_bound[q + 1]; ++f) {
        const Triangle& input = mesh.triangles[f];
        const Triangle t{node_of[input[0]], node_of[input[1]], node_of[input[2]]};
        mapped[f] = t;
        if (distinct(t)) {
          const std::uint32_t lo = std::min({t[0], t[1], t[2]});
          ++at[q][lo];
          const std::size_t h = lo >= vertex_bound[1];
          list[h][listed[h]++] = static_cast<std::uint32_t>(f);
          continue;
        }
        ++collapsed[q];
        if (!options.no_lines && (t[0] != t[1] || t[1] != t[2])) {
          std::uint32_t other = t[0] != t[1] ? t[1] : t[2];
          part_lines[q].push_back({std::min(t[0], other), std::max(t[0], other)});
        }
      }
      owned[q] = {listed[0], listed[1]};
    });
    for (const Buffer<Segment>& l : part_lines)
      line_candidates.insert(line_candidates.end(), l.begin(), l.end());
    std::uint32_t total = 0;
    for (std::size_t v = 0; v < count; ++v)
      for (std::size_t q = 0; q < parts; ++q) total += std::exchange(at[q][v], total);
    cut.tris.resize(total);
    cut.tri_origin.resize(total);
    // Each part then takes one half of the vertices: it scatters the
    // triangles whose smallest corner lies there (from both parts' lists:
    // the parts write to separate memory, where scattering each its half of
    // the triangles shared cache lines in every run) and squeezes their runs.
    std::array<std::size_t, 2> first{0, 0}, kept{0, 0};  // each part's runs
    if (parts == 2) first[1] = vertex_bound[1] < count ? at[0][vertex_bound[1]] : total;
    // Once scattered, the last part's counters hold where each run ends.
    const Buffer<std::uint32_t>& run_end = at[parts - 1];
    RemapScratch second_scratch;
    for_parts(parts, [&](std::size_t q) {
      const std::size_t v0 = vertex_bound[q], v1 = vertex_bound[q + 1];
      for (std::size_t p = 0; p < parts; ++p) {
        Buffer<std::uint32_t>& counter = at[p];
        const std::uint32_t* list = own[p][q].data();
        for (std::size_t k = 0; k < owned[p][q]; ++k) {
          const std::uint32_t f = list[k];
          const Triangle& t = mapped[f];
          const std::uint32_t slot = counter[std::min({t[0], t[1], t[2]})]++;
          cut.tris[slot] = t;
          cut.tri_origin[slot] = f;
        }
      }
      std::size_t begin = first[q], out = first[q];
      for (std::size_t v = v0; v < v1; ++v) {
        const std::size_t end = run_end[v];
        const std::size_t n = end - begin;
        // Until the first doublet, every run is already in place.
        if (out != begin) {
          for (std::size_t i = 0; i < n; ++i) {  // a few: no memmove call
            cut.tris[out + i] = cut.tris[begin + i];
            cut.tri_origin[out + i] = cut.tri_origin[begin + i];
          }
        }
        if (n == 1) {
          ++out;
        } else if (n > 1) {
          out += dedupe_run(&cut.tris[out], &cut.tri_origin[out], n, static_cast<std::uint32_t>(v),
                            q == 0 ? remap_scratch : second_scratch);
        }
        begin = end;
      }
      kept[q] = out - first[q];
    });
    if (parts == 2 && kept[0] != first[1]) {  // the first half lost doublets
      std::copy_n(cut.tris.begin() + first[1], kept[1], cut.tris.begin() + kept[0]);
      std::copy_n(cut.tri_origin.begin() + first[1], kept[1], cut.tri_origin.begin() + kept[0]);
    }
    cut.tris.resize(kept[0] + kept[1]);
    cut.tri_origin.resize(kept[0] + kept[1]);
    finish_faces(mesh.lines, node_of, count, line_candidates, cut, remap_scratch);
    // Every vertex is a corner of an input triangle or an end of an input
    // line (validate); when no triangle collapsed and there are no lines,
    // each is a corner of a kept triangle (a doublet's corners are those of
    // the one kept) and there is nothing to drop.
    if (collapsed[0] + collapsed[1] != 0 || !mesh.lines.empty())
      compact_vertices(count, number_used_vertices(count, cut, remap_scratch), cut, remap_scratch);
  }
  // The input vertices still represented, by their level-0 vertex (the
  // input vertices of one level-0 vertex share its position exactly), for
  // the displacement of each level: level 0's positions (kept when the first
  // level replaces them; until then cut.pos). Cells are runs of the previous
  // level's vertices in octree order and level 0 is in octree order, so
  // every vertex of a level stands for a run of level-0 vertices:
  // [level0_start[k], level0_start[k + 1]) for vertex k (until the first
  // level, [k, k + 1)), of which those a dropped vertex stood for are no
  // longer represented (level0_alive = 0).
  Buffer<Vec3> input_pos;
  Buffer<std::uint32_t> level0_start, next_start;
  Buffer<double> reach, next_reach;
  Buffer<std::uint8_t> level0_alive;
  node_of = {};
  order = {};
  code = {};
  std::vector<SimplifyResult> chain;
  // Level 0 and at most one level per octree depth: reserved, so that a
  // result being filled (below) never moves.
  chain.reserve(kMaxDepth + 2);
  // Copying a finished level into its result (a few large arrays: 5-10 % of
  // a call) only reads `cut`, so the next level, which reads `cut` and writes
  // `next`, does it in its remap task after the remap (the remap is the
  // shorter of the level's two long tasks: the copy fills the gap, where
  // copying at once held a thread from the level's first passes); when the
  // chain ends first, `finish` does it. `pending`: the result awaiting it.
  SimplifyResult* pending = nullptr;
  auto emit = [&](float error, StopReason reason, std::string detail) {
    assert(chain.size() < chain.capacity());
    SimplifyResult& r = chain.emplace_back();
    r.error = error;
    r.stop_reason = reason;
    r.stop_detail = std::move(detail);
    pending = &r;
  };
  const std::size_t input_tris = mesh.triangle_count();
  const bool count_target = options.target.triangles > 0 || options.target.ratio > 0;
  const std::size_t target_tris = options.target.triangle_target(input_tris);
  const float max_error = options.target.max_error;

  emit(0, StopReason::kNoReduction,
       fmt::format("level 0: the input with equal positions merged, {} "
                   "vertices, {} triangles, {} lines",
                   cut.size(), cut.tris.size(), cut.lines.size()));
  auto finish = [&](StopReason reason, const std::string& why) {
    if (pending) fill_result(mesh, cut, *pending);
    chain.back().stop_reason = reason;
    chain.back().stop_detail += "; stopped: " + why;
    return std::move(chain);
  };
  if (count_target && cut.tris.size() <= target_tris) {
    if (target_tris >= input_tris)
      return finish(StopReason::kNoReduction, "the target asks for no reduction");
    return finish(StopReason::kTargetReached,
                  fmt::format("{} triangles <= target {}", cut.tris.size(), target_tris));
  }

  Cut next;
  Buffer<std::uint32_t> cell_of;
  Buffer<std::uint32_t> cell_begin;
  Buffer<char> corner, wanted;
  CellFaces cell_faces;
  tbb::enumerable_thread_specific<Scratch> scratches;
  std::array<std::array<std::size_t, kMaxDepth + 1>, 2> histogram{};
  while (true) {
    const std::size_t n_prev = cut.size();
    // Cells per depth: 1 + the neighbours in octree order that part above it.
    // In two parts side by side for large levels; each part's own histogram
    // also tells where its cells start in the numbering below.
    const std::size_t parts = parts_of(n_prev);
    const std::array<std::size_t, 3> bound = halves(n_prev, parts);
    histogram[1].fill(0);
    for_parts(parts, [&](std::size_t q) {
      histogram[q].fill(0);
      for (std::size_t i = std::max<std::size_t>(bound[q], 1); i < bound[q + 1]; ++i)
        ++histogram[q][common_depth(cut.code[i - 1], cut.code[i])];
    });
    const auto limit = static_cast<std::size_t>(std::floor((1.0 - min_diff) * double(n_prev)));
    int depth = 0;
    std::size_t cells = 0;
    std::array<std::size_t, kMaxDepth + 2> cells_at;
    cells_at[0] = 1;
    for (int c = 1; c <= kMaxDepth + 1; ++c)
      cells_at[c] = cells_at[c - 1] + histogram[0][c - 1] + histogram[1][c - 1];
    for (int c = cut.depth - 1; c >= 1; --c) {
      if (cells_at[c] <= limit && cells_at[c] < n_prev) {
        depth = c;
        cells = cells_at[c];
        break;
      }
    }
    if (depth == 0) {
      if (cut.depth <= 1) return finish(StopReason::kCannotSimplify, "octree depth 1 reached");
      return finish(StopReason::kCannotSimplify,
                    fmt::format("no octree depth >= 1 leaves at most {} % of the {} vertices",
                                100 - 100 * min_diff, n_prev));
    }

    // The cells at `depth`: runs of vertices in octree order (numbered in
    // the same parts; the second part's first cell follows the first's).
    // Each cell's quadric: the sum of its vertices' (a vertex's is the sum of
    // the plane quadrics of the input triangles around it). Level 0 keeps
    // none: the first level adds each distinct triangle's plane quadric to
    // the cells of its three corners directly (level 0 positions are the
    // input's), which writes a third of the memory; its quadrics start at
    // zero, each part zeroing those of its cells.
    const bool quadrics_from_triangles = quadrics && cut.quadric.empty();
    if (quadrics) next.quadric.resize(cells);
    cell_of.resize(n_prev);
    cell_begin.resize(cells + 1);
    std::size_t first_part_cells = 1;
    for (int c = 0; c < depth; ++c) first_part_cells += histogram[0][c];
    for_parts(parts, [&](std::size_t q) {
      // The cell before the part's first start (kNone: wraps to 0 at i = 0).
      auto cell = static_cast<std::uint32_t>(q == 0 ? kNone : first_part_cells - 1);
      for (std::size_t i = bound[q]; i < bound[q + 1]; ++i) {
        if (i == 0 || common_depth(cut.code[i - 1], cut.code[i]) < depth)
          cell_begin[++cell] = static_cast<std::uint32_t>(i);
        cell_of[i] = cell;
      }
      if (quadrics_from_triangles) {
        const std::size_t first = q == 0 ? 0 : first_part_cells;
        std::fill(next.quadric.begin() + first, next.quadric.begin() + (cell + 1), Quadric{});
      }
    });
    cell_begin[cells] = static_cast<std::uint32_t>(n_prev);

    next.depth = depth;
    next.pos.resize(cells);
    next.weight.resize(cells);
    next.orig.resize(cells);
    next.code.resize(cells);
    // The triangles with their corners mapped to the new cells (read three
    // times below).
    mapped.resize(cut.tris.size());
    for_chunks(cut.tris.size(), [&](std::size_t lo, std::size_t hi) {
      for (std::size_t f = lo; f < hi; ++f) {
        const Triangle& t = cut.tris[f];
        mapped[f] = {cell_of[t[0]], cell_of[t[1]], cell_of[t[2]]};
      }
    });
    // Which vertices are corners of a triangle (all of them unless the level
    // has lines: a vertex nothing uses is never kept).
    corner.clear();
    if (!cut.lines.empty()) {
      corner.assign(n_prev, 0);
      for (const Triangle& t : cut.tris) corner[t[0]] = corner[t[1]] = corner[t[2]] = 1;
    }
    const float cell_size = static_cast<float>(octree.cell_side(depth));
    // Only cells of several vertices choose a representative, and only those
    // with more than one contender (see choose_representative) read the
    // triangles around them; listing those for the others is wasted, but
    // which cells have one contender is only known after the quadric terms,
    // and a second pass over the cells costs more than it saves.
    wanted.resize(cells);
    for (std::uint32_t j = 0; j < cells; ++j) wanted[j] = cell_begin[j + 1] - cell_begin[j] > 1;
    const bool measure = !cut.tris.empty() && (weights.area > 0 || weights.volume > 0);
    // The first level's quadrics and the cell face lists are independent
    // sequential passes (each scatters into its own arrays): side by side
    // when a second thread is free.
    // The faces of the new level need only the mapped triangles, not the
    // new vertices: they are remapped beside the quadrics, face lists and
    // choices (a task a free thread takes; one thread runs it at the wait).
    // At the first level the quadrics and the lists are the longer share of
    // the two: the remap task starts with the lists' count (when it gets to
    // it first), so that the other thread, done with quadrics and fill
    // first, starts on the representatives instead of waiting for the
    // remap to end. Whoever claims the count does it; the other waits for it
    // only if it needs it (the remap task never does).
    // Declared after everything it touches, so that on an exception it is
    // waited for before they go.
    enum : int { kCountFree, kCountClaimed, kCountDone, kCountFailed };
    std::atomic<int> count_state{kCountFree};
    const bool count_aside = measure && quadrics_from_triangles;
    auto claim_count = [&] {
      int expected = kCountFree;
      if (!count_state.compare_exchange_strong(expected, kCountClaimed)) return false;
      try {
        cell_faces.count(mapped, wanted);
      } catch (...) {  // (bad_alloc) the waiting thread must not wait forever
        count_state.store(kCountFailed, std::memory_order_release);
        throw;
      }
      count_state.store(kCountDone, std::memory_order_release);
      return true;
    };
    std::size_t kept_cells = 0;
    tbb::task_group remapping;
    remapping.run([&] {
      if (count_aside) claim_count();
      line_candidates.clear();
      remap_faces(
          cut.tris.size(), [&](std::size_t f) { return mapped[f]; },
          [&](std::size_t f) { return cut.tri_origin[f]; }, cut.lines, cell_of, cells,
          options.no_lines, line_candidates, next, remap_scratch);
      kept_cells = number_used_vertices(cells, next, remap_scratch);
      if (pending) fill_result(mesh, cut, *pending);
    });
    if (count_aside) {
      add_plane_quadrics(cut.pos, cut.tris, mapped, next.quadric);
      if (!claim_count()) {
        int state;
        while ((state = count_state.load(std::memory_order_acquire)) == kCountClaimed)
          std::this_thread::yield();
        if (state == kCountFailed) remapping.wait();  // rethrows the remap task's exception
      }
      cell_faces.fill(mapped, wanted);
    } else {
      tbb::parallel_invoke(
          [&] {
            if (!quadrics_from_triangles) return;
            add_plane_quadrics(cut.pos, cut.tris, mapped, next.quadric);
          },
          [&] {
            if (measure) cell_faces.build(mapped, wanted);
          });
    }
    const LevelContext ctx{cut, measure ? &cell_faces : nullptr, weights};
    // Cells are independent: each reads the previous level and writes its own slot.
    for_chunks<kCellChunk>(cells, [&](std::size_t lo, std::size_t hi) {
      Scratch& scratch = scratches.local();
      for (auto j = static_cast<std::uint32_t>(lo); j < hi; ++j) {
        const std::uint32_t b = cell_begin[j], e = cell_begin[j + 1];
        next.code[j] = cut.code[b];
        std::uint32_t weight = 0;
        for (std::uint32_t i = b; i < e; ++i) weight += cut.weight[i];
        next.weight[j] = weight;
        if (e - b == 1) {
          next.pos[j] = cut.pos[b];
          next.orig[j] = cut.orig[b];
          if (quadrics && !quadrics_from_triangles) next.quadric[j] = cut.quadric[b];
          continue;
        }
        if (quadrics && !quadrics_from_triangles) {
          Quadric sum{};
          for (std::uint32_t i = b; i < e; ++i) sum += cut.quadric[i];
          next.quadric[j] = sum;
        }
        const Quadric& q = quadrics ? next.quadric[j] : Quadric{};
        bool has_faces = corner.empty();
        for (std::uint32_t i = b; i < e && !has_faces; ++i) has_faces = corner[i] != 0;
        const Choice c = choose_representative(
            ctx, j, b, e, has_faces, octree.cell_lo(cut.code[b], depth), cell_size, q, scratch);
        next.pos[j] = c.pos;
        next.orig[j] = c.orig;
      }
    });
    remapping.wait();
    pending = nullptr;
    compact_vertices(cells, kept_cells, next, remap_scratch);
    const Buffer<std::uint32_t>& keep = remap_scratch.keep;
    if (next.tris.empty() && next.lines.empty())
      return finish(StopReason::kCannotSimplify,
                    fmt::format("the level at octree depth {} would be empty", depth));

    // The largest displacement of a represented input vertex, in double: a
    // float square overflows for coordinates beyond ~1.8e19. Cell by cell,
    // over the level-0 vertices it stands for (read in sequence), in tasks
    // of about kErrorChunk of them; the cells' runs of level-0 vertices give
    // the new level's (on an early return below they are not read again).
    // Each vertex of a level keeps a bound on the distance from it to the
    // level-0 vertices it stands for (`reach`), so the level-0 vertices of
    // a previous vertex k in cell j are within |p_j - p_k| + reach_k of the
    // new position p_j (with a margin for rounding); when that is no more
    // than the largest displacement found so far, they are not read. The
    // largest displacement is still exact: only vertices that cannot exceed
    // it are left out.
    const bool first_level = level0_start.empty();
    if (first_level) level0_alive.assign(n_prev, 1);
    const Buffer<Vec3>& level0_pos = first_level ? cut.pos : input_pos;
    const std::size_t n0 = level0_alive.size();
    auto level0_begin = [&](std::uint32_t k) {  // k <= n_prev
      return first_level ? k : level0_start[k];
    };
    next_start.resize(kept_cells + 1);
    next_reach.resize(kept_cells);
    std::atomic<double> largest2{0};
    constexpr std::size_t kErrorChunk = 4096;
    constexpr double kMargin = 1 + 1e-5;  // float rounding of a difference: 2^-24 relative
    const std::size_t grain = std::max<std::size_t>(1, cells * kErrorChunk / n0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, grain), [&](const auto& r) {
      double error2 = largest2.load(std::memory_order_relaxed);
      for (std::size_t j = r.begin(); j < r.end(); ++j) {
        const std::uint32_t n = keep[j];
        if (n == kNone) {
          const std::uint32_t i0 = level0_begin(cell_begin[j]);
          const std::uint32_t i1 = level0_begin(cell_begin[j + 1]);
          std::fill(level0_alive.begin() + i0, level0_alive.begin() + i1, 0);
          continue;
        }
        next_start[n] = level0_begin(cell_begin[j]);
        const Vec3 p = next.pos[n];
        auto displacement2 = [&](std::uint32_t i) {  // 0 for a vertex no longer represented
          const Vec3 d = level0_pos[i] - p;
          const double e2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
          return level0_alive[i] ? e2 : 0.0;
        };
        // The largest displacement of [i0, i1); four maxima side by side:
        // one would chain every vertex to the last.
        auto largest = [&](std::uint32_t i0, std::uint32_t i1) {
          double m[4] = {0, 0, 0, 0};
          std::uint32_t i = i0;
          for (; i + 4 <= i1; i += 4)
            for (std::uint32_t u = 0; u < 4; ++u) m[u] = std::max(m[u], displacement2(i + u));
          for (; i < i1; ++i) m[0] = std::max(m[0], displacement2(i));
          const double k2 = std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
          error2 = std::max(error2, k2);
          return std::sqrt(k2) * kMargin;
        };
        if (first_level) {  // one level-0 vertex per previous vertex: no bound to check
          next_reach[n] = largest(cell_begin[j], cell_begin[j + 1]);
          continue;
        }
        double cell_reach = 0;
        for (std::uint32_t k = cell_begin[j]; k < cell_begin[j + 1]; ++k) {
          const Vec3& q = cut.pos[k];
          const double dx = double(q.x) - p.x, dy = double(q.y) - p.y, dz = double(q.z) - p.z;
          const double bound = (std::sqrt(dx * dx + dy * dy + dz * dz) + reach[k]) * kMargin;
          cell_reach = std::max(cell_reach, bound * bound <= error2
                                                ? bound
                                                : largest(level0_start[k], level0_start[k + 1]));
        }
        next_reach[n] = cell_reach;
      }
      double seen = largest2.load(std::memory_order_relaxed);
      while (error2 > seen && !largest2.compare_exchange_weak(seen, error2)) {
      }
    });
    next_start[kept_cells] = static_cast<std::uint32_t>(n0);
    std::swap(level0_start, next_start);
    std::swap(reach, next_reach);
    const float error = float(std::sqrt(largest2.load()));
    if (error > max_error)
      return finish(
          StopReason::kErrorBudgetReached,
          fmt::format("the level at octree depth {} would move a vertex by {:.4g} > {:.4g}", depth,
                      error, max_error));

    std::string detail = fmt::format(
        "octree depth {} (cell side {:.4g}, diagonal {:.4g}): {} -> {} vertices (-{:.1f} %), "
        "{} triangles, {} lines; largest vertex displacement {:.4g}",
        depth, cell_size, std::sqrt(3.0) * cell_size, n_prev, next.size(),
        100.0 * (1.0 - double(next.size()) / double(n_prev)), next.tris.size(), next.lines.size(),
        error);
    std::swap(cut, next);
    if (first_level) input_pos = std::move(next.pos);  // level 0's
    emit(error, StopReason::kTargetReached, std::move(detail));
    if (count_target && cut.tris.size() <= target_tris)
      return finish(StopReason::kTargetReached,
                    fmt::format("{} triangles <= target {}", cut.tris.size(), target_tris));
    if (cut.size() <= 1) return finish(StopReason::kCannotSimplify, "one vertex left");
  }
}

}  // namespace lodforge
