// Quadric edge collapse.
//
// M. Garland, P. S. Heckbert, "Surface Simplification Using Quadric Error
// Metrics", SIGGRAPH 1997: every vertex carries the sum of the (area-weighted)
// squared-distance quadrics of its planes; the cheapest edge collapse goes
// first, to the position that minimises the summed quadric (with a fallback to
// the best point of the edge when that system is ill-conditioned), and border
// edges add penalty planes perpendicular to their face.
//
// H. Hoppe, "New Quadric Metric for Simplifying Meshes with Appearance
// Attributes", IEEE Visualization 1999: each attribute channel s is modelled
// over a triangle as a linear function g.p + d of the position; the quadric
// sum_t area_t (s - g_t.p - d_t)^2, minimised over s, is a quadric in p that
// joins the geometric one, and its minimiser gives the attribute at the new
// position. Attributes live on wedges (a position's distinct attribute sets),
// so attribute seams stay sharp.
//
// Implementation notes (meshoptimizer's simplifier is the speed model): the
// collapse loop is bound by memory latency (collapses jump around the mesh in
// cost order), so per-vertex and per-triangle state sit in one record each
// (128 and 32 bytes) and small per-vertex state (versions) in compact arrays;
// a per-position list of live triangles rewritten by appending; a bucket
// queue of 16-byte edge entries with lazy deletion (an entry carries the sum
// of the version stamps of its two vertices; stale entries are dropped in bulk
// when their bucket comes up and when they outnumber the live edges); set-up
// in a few linear passes without maps or sorting (the vertex kinds, the
// quadrics and the first plans of the edges in parallel, each summed or
// queued in triangle order, so the result does not depend on the thread
// count); no allocation per collapse beyond amortised vector growth;
// coordinates in power-of-two normalised units, so results do not depend on
// the model's unit. Per collapse the work is: one valid pop, the checks over
// the two fans, and one evaluation and push per edge of the merged vertex.
//
// The collapse loop is inherently sequential, so a large reduction starts
// with a regional phase (run_regions): the mesh is cut into a few regions,
// which collapse their own edges side by side on TBB's threads, each with its
// own queue, in rounds up to a common cost limit, so the order stays close to
// one queue's; the vertices on the cuts wait, and the whole mesh then goes on
// from one queue. On the bunny at 80-99 % reduction this changes the mean
// deviation by under 1 % against one queue throughout (a test checks 5 %).
#include "lodforge/simplify/quadric_collapse.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "lodforge/core/error.h"
#include "lodforge/simplify/regions.h"

namespace lodforge {
namespace {

struct D3 {
  double x = 0, y = 0, z = 0;
};
inline D3 operator+(D3 a, D3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline D3 operator-(D3 a, D3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline D3 operator*(D3 a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline double dot(D3 a, D3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline D3 cross(D3 a, D3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm2(D3 a) {
  return dot(a, a);
}

/// Symmetric quadric Q(p) = p^T A p + 2 b.p + c.
struct Quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0, c = 0;

  void add(const Quadric& o) {
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
  }
  /// weight * (n.p + d)^2
  void add_plane(D3 n, double d, double w) {
    a00 += w * n.x * n.x;
    a01 += w * n.x * n.y;
    a02 += w * n.x * n.z;
    a11 += w * n.y * n.y;
    a12 += w * n.y * n.z;
    a22 += w * n.z * n.z;
    b0 += w * n.x * d;
    b1 += w * n.y * d;
    b2 += w * n.z * d;
    c += w * d * d;
  }
  D3 apply_a(D3 p) const {
    return {a00 * p.x + a01 * p.y + a02 * p.z, a01 * p.x + a11 * p.y + a12 * p.z,
            a02 * p.x + a12 * p.y + a22 * p.z};
  }
  // Inlined by force: with evaluate() called from two places GCC stopped
  // inlining it, which cost 5 % on meshes with attributes (fandisk).
  [[gnu::always_inline]] double eval(D3 p) const {
    D3 ap = apply_a(p);
    return std::max(0.0, dot(p, ap) + 2 * (b0 * p.x + b1 * p.y + b2 * p.z) + c);
  }
};

/// The corner (0, 1, 2) of triangle `c` that is vertex `p`, which must be one
/// of them; without branches, since which one it is depends on the data.
inline int corner_of(const std::uint32_t* c, std::uint32_t p) {
  return int{c[1] == p} | int{c[2] == p} << 1;
}
/// The corners after and before corner k.
constexpr int kNext[3] = {1, 2, 0};
constexpr int kPrev[3] = {2, 0, 1};

/// Vertex (welded position) kinds. A vertex moves only as its kind allows:
///
/// | kind     | where it is                                   | may move along          |
/// |----------|-----------------------------------------------|-------------------------|
/// | kFree    | interior, one wedge, no feature edge          | any edge                |
/// | kFeature | on exactly two feature edges (border, seam,   | its feature edges only  |
/// |          | material boundary): the middle of a line      |                         |
/// | kLocked  | line ends and crossings, non-manifold or      | never (others may       |
/// |          | inconsistently oriented edges, line segments, | collapse onto it)       |
/// |          | borders under lock_border                     |                         |
///
/// A free vertex's edges are never feature edges, so an edge whose two ends
/// may both move joins two vertices of the same kind.
enum Kind : std::uint8_t { kFree, kFeature, kLocked };

/// A planned collapse: vertex `u` goes into vertex `v`, which moves to `w`.
struct Collapse {
  double cost = 0;
  std::uint32_t u = kNone, v = kNone;
  D3 w;
};

/// A queued collapse of edge {a, b}: 16 bytes, so that the four children of a
/// node of the 4-ary heap below span at most two cache lines. `key` orders
/// entries (see heap_key()). `stamp` is the sum of the versions of a and b
/// when it was pushed; versions only grow, so the sum is unchanged exactly
/// when neither end changed.
struct HeapEntry {
  std::uint32_t key;
  std::uint32_t a, b;
  std::uint32_t stamp;
};

/// The heap key of a cost: the bits of the float cost (non-negative floats
/// order like their bit patterns, and their sign bit is free), shifted up to
/// make room for the deferred flag, so that a deferred sliver goes after an
/// ordinary collapse of the same cost.
inline std::uint32_t heap_key(double cost, bool deferred) {
  float f = static_cast<float>(cost);
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u << 1 | std::uint32_t{deferred};
}
inline bool is_deferred(const HeapEntry& e) {
  return (e.key & 1) != 0;
}

/// Min-heap of HeapEntry by (cost, deferred last), 4-ary: half the depth of a
/// binary heap and its children side by side in memory. Entries are deleted
/// lazily (see run()), so pops dominate; a pop moves the hole down to a leaf
/// and then sifts the last entry up from there (Floyd), which saves one
/// comparison per level since the last entry usually belongs near the bottom.
class EdgeHeap {
 public:
  bool empty() const { return v_.empty(); }
  std::size_t size() const { return v_.size(); }
  const HeapEntry& top() const { return v_[0]; }
  void clear() { v_.clear(); }
  /// Drops the entries for which `stale` holds and re-orders the rest.
  template <class Stale>
  void drop_if(Stale stale) {
    std::erase_if(v_, stale);
    make();
  }
  /// Becomes the entries of `from` (this heap must be empty); `from` is left
  /// empty, with this heap's old storage.
  void take(std::vector<HeapEntry>& from) {
    assert(v_.empty());
    v_.swap(from);
    make();
  }
  /// Appends without ordering; call make() before the next push or pop.
  void append(const HeapEntry& e) { v_.push_back(e); }
  void make() {
    if (v_.size() < 2) return;
    for (std::size_t i = (v_.size() - 2) / 4 + 1; i-- > 0;) sift_down(i);
  }
  void push(const HeapEntry& e) {
    v_.push_back(e);
    sift_up(v_.size() - 1, e);
  }
  HeapEntry pop() {
    const HeapEntry top = v_[0];
    const HeapEntry last = v_.back();
    v_.pop_back();
    const std::size_t n = v_.size();
    if (n == 0) return top;
    std::size_t i = 0;
    HeapEntry* h = v_.data();
    // Full families first, with a branch-free minimum of four.
    for (std::size_t c = 1; c + 4 <= n; c = 4 * i + 1) {
      // Which child is smallest is data: select by arithmetic, not branches.
      std::size_t b01 = c + std::size_t{h[c + 1].key < h[c].key};
      std::size_t b23 = c + 2 + std::size_t{h[c + 3].key < h[c + 2].key};
      std::size_t best = b01 + (b23 - b01) * std::size_t{h[b23].key < h[b01].key};
      h[i] = h[best];
      i = best;
    }
    if (std::size_t c = 4 * i + 1; c < n) {
      std::size_t best = c;
      for (std::size_t j = c + 1; j < n; ++j)
        if (h[j].key < h[best].key) best = j;
      h[i] = h[best];
      i = best;
    }
    sift_up(i, last);
    return top;
  }

 private:
  void sift_up(std::size_t i, const HeapEntry& x) {
    while (i > 0) {
      std::size_t p = (i - 1) / 4;
      if (v_[p].key <= x.key) break;
      v_[i] = v_[p];
      i = p;
    }
    v_[i] = x;
  }
  void sift_down(std::size_t i) {
    const HeapEntry x = v_[i];
    const std::size_t n = v_.size();
    for (;;) {
      std::size_t c = 4 * i + 1;
      if (c >= n) break;
      std::size_t end = std::min(c + 4, n), best = c;
      std::uint32_t kb = v_[c].key;
      for (std::size_t j = c + 1; j < end; ++j)
        if (v_[j].key < kb) kb = v_[j].key, best = j;
      if (kb >= x.key) break;
      v_[i] = v_[best];
      i = best;
    }
    v_[i] = x;
  }

  std::vector<HeapEntry> v_;
};

/// The queue of collapses: a bucket queue in front of a small exact heap.
/// Keys are bucketed by their top bits (the float exponent and a few mantissa
/// bits, so a bucket spans a few percent of cost); a push beyond the current
/// bucket is an append, and only the current bucket is kept in heap order,
/// so the heap holds a few hundred entries instead of all of them and stale
/// entries (see run()) cost an append and a pop in that small heap. The order
/// stays exact: a push into the current bucket or below goes into the heap.
class CollapseQueue {
 public:
  /// `shift`: key bits below the bucket index (18 for a whole mesh; the
  /// small queues of the regions use fewer, wider buckets).
  explicit CollapseQueue(int shift = 18)
      : shift_(shift), buckets_(std::size_t{1} << (32 - shift)), used_(buckets_.size() / 64) {}
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  void clear() {
    for (std::size_t w = 0; w < used_.size(); ++w)
      for (std::uint64_t bits = used_[w]; bits != 0; bits &= bits - 1)
        buckets_[64 * w + static_cast<std::size_t>(std::countr_zero(bits))].clear();
    std::fill(used_.begin(), used_.end(), 0);
    heap_.clear();
    current_ = 0;
    size_ = 0;
  }
  void push(const HeapEntry& e) {
    ++size_;
    std::size_t b = e.key >> shift_;
    if (b <= current_) {
      heap_.push(e);
    } else {
      buckets_[b].push_back(e);
      used_[b / 64] |= std::uint64_t{1} << (b % 64);
    }
  }
  /// Removes the smallest entry into `out`; false if there is none or its key
  /// is above `limit` (then it stays). Entries
  /// for which `stale` holds are dropped in bulk when their bucket becomes
  /// the heap (most entries are stale by then: they were pushed long before
  /// their cost came up, and their vertices changed since), so they cost a
  /// scan instead of a pop.
  template <class Stale>
  bool pop(HeapEntry& out, Stale stale, std::uint32_t limit = 0xffffffffu) {
    while (heap_.empty()) {
      if (size_ == 0) return false;
      // The next bucket in use becomes the heap.
      std::size_t w = (current_ + 1) / 64;
      std::uint64_t bits = used_[w] & (~std::uint64_t{0} << ((current_ + 1) % 64));
      while (bits == 0) bits = used_[++w];
      const std::size_t next = 64 * w + static_cast<std::size_t>(std::countr_zero(bits));
      if (next > limit >> shift_) return false;
      current_ = next;
      used_[w] &= ~(std::uint64_t{1} << (current_ % 64));
      std::vector<HeapEntry>& bucket = buckets_[current_];
      const std::size_t before = bucket.size();
      std::erase_if(bucket, stale);
      size_ -= before - bucket.size();
      heap_.take(bucket);
    }
    if (heap_.top().key > limit) return false;
    --size_;
    out = heap_.pop();
    return true;
  }
  /// The next entry of the current bucket, if any (for prefetching).
  const HeapEntry* peek() const { return heap_.empty() ? nullptr : &heap_.top(); }
  /// Drops the entries for which `stale` holds.
  template <class Stale>
  void drop_if(Stale stale) {
    heap_.drop_if(stale);
    size_ = heap_.size();
    for (std::size_t w = 0; w < used_.size(); ++w)
      for (std::uint64_t bits = used_[w]; bits != 0; bits &= bits - 1) {
        std::size_t b = 64 * w + static_cast<std::size_t>(std::countr_zero(bits));
        std::erase_if(buckets_[b], stale);
        size_ += buckets_[b].size();
        if (buckets_[b].empty()) used_[w] &= ~(std::uint64_t{1} << (b % 64));
      }
  }

 private:
  int shift_;
  std::vector<std::vector<HeapEntry>> buckets_;
  std::vector<std::uint64_t> used_;  // bit b: bucket b is not empty
  EdgeHeap heap_;                    // the current bucket and anything below it
  std::size_t current_ = 0;
  std::size_t size_ = 0;
};

/// The wedge merges of a collapse: (wedge of u, wedge of v) per edge triangle.
using WedgePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// What try_collapse decided (kNoRoom: a region's stretch of triangle lists
/// is full, see Lane).
enum class Outcome { kDone, kRejected, kSliver, kOverBudget, kNoRoom };

/// Why Collapser::drain stopped.
enum class Halt { kFloor, kEmpty, kLimit, kNoRoom };

/// Scratch stamps per position (a vertex is marked when its mark equals the
/// current stamp): one set per thread, since marks are written for the
/// neighbours of a collapse, which regions may share.
/// (The calling thread keeps its marks in the vertex records, which a
/// collapse reads anyway, and leaves `mark` empty; see Collapser::mark().)
struct Marks {
  std::vector<std::uint32_t> mark;
  std::uint32_t stamp = 0;
};

/// One collapse loop's state: its queue, counts and scratch. The whole mesh
/// has one; in the first phase of a large reduction (Collapser::run_regions)
/// every region has its own and touches only the vertices it owns.
struct Lane {
  explicit Lane(int shift = 18) : queue(shift) {}
  CollapseQueue queue;
  std::size_t live = 0;  // live triangles (of the region)
  // A region: its live triangles without a seam corner, which its floor and
  // the goal of the rounds count (the seams stay as they are, so the
  // triangles around them would never get down to a share of the target).
  std::size_t inner = 0;
  std::size_t collapses_since_fill = 0;
  std::size_t budget_rejections = 0;
  // A region: the id its vertices carry in owner_, and its own stretch
  // [refs_next, refs_end) of refs_ for the triangle lists that grow (the
  // whole mesh appends at the end of refs_ instead).
  std::uint8_t id = 0;
  std::size_t refs_next = 0, refs_end = 0;
  std::size_t floor = 0;  // its share of the target (of inner for a region)
  bool done = false;
  WedgePairs wedge_pairs;
  std::vector<std::pair<std::uint32_t, float>> new_errors;
  std::vector<std::uint32_t> new_list;
  std::vector<std::uint32_t> requeue;
};

// At most 3 + 2 + 3 attribute channels; a wedge's attribute quadric holds the
// summed p-part (10), the area (1) and per channel G (3) and D (1).
constexpr int kMaxChannels = 8;
constexpr int kMaxAttrStride = 11 + 4 * kMaxChannels;

class Collapser {
 public:
  Collapser(const TriangleMesh& mesh, const QuadricCollapseOptions& options)
      : mesh_(mesh), options_(options) {
    build();
  }

  std::size_t live_triangles() const { return seq_.live; }
  std::size_t input_triangles() const { return mesh_.triangles.size(); }

  /// Collapses until at most `target` triangles are live or nothing is
  /// allowed; returns why it stopped.
  StopReason run(std::size_t target, std::string& detail);
  SimplifyResult snapshot() const;

 private:
  void build();
  void compute_kinds();
  bool is_ring(std::uint32_t p) const;
  void compute_quadrics();
  void add_quadrics(std::uint32_t lo, std::uint32_t hi);
  template <class Emit>
  void plan_edges(Emit emit);
  void fill_heap();
  void run_regions(std::size_t target);
  std::vector<std::uint8_t> partition(int parts) const;
  // The collapse loop, for the whole mesh (kRegional false) or a region.
  template <bool kRegional>
  Halt drain(Lane& lane, Marks& marks, std::uint32_t limit);
  template <bool kRegional>
  void push_edges(std::uint32_t a, Lane& lane, Marks& marks, bool collect_rejected = false);
  template <bool kRegional>
  Outcome try_collapse(const Collapse& c, bool allow_slivers, Lane& lane, Marks& marks);
  /// The mark of position x: in its record for the calling thread (the
  /// whole mesh), in the thread's own array for a region (regions share
  /// the records of the seam vertices).
  template <bool kRegional>
  std::uint32_t& mark(Marks& marks, std::uint32_t x) {
    if constexpr (kRegional)
      return marks.mark[x];
    else
      return vx_[x].mark;
  }
  /// Reads the state only (`pairs` is scratch): safe on several threads.
  bool evaluate(std::uint32_t a, std::uint32_t b, Collapse& out, WedgePairs& pairs) const;
  int edge_triangles(std::uint32_t a, std::uint32_t b, std::uint32_t* tris) const;
  bool is_feature_edge(std::uint32_t a, std::uint32_t b, bool& movable) const;
  void collect_wedge_pairs(std::uint32_t u, std::uint32_t v, WedgePairs& pairs) const;
  void attribute_quadric(std::uint32_t u, std::uint32_t v, const WedgePairs& pairs,
                         Quadric& q) const;
  void update_wedge_attributes(std::uint32_t v);
  D3 position_of_corner(std::uint32_t t, int k) const { return vx_[tri_[t].v[k]].pos; }
  std::uint32_t* tris_begin(std::uint32_t p) { return refs_.data() + vx_[p].ref_start; }
  const std::uint32_t* tris_begin(std::uint32_t p) const { return refs_.data() + vx_[p].ref_start; }
  std::uint32_t tris_count(std::uint32_t p) const { return vx_[p].ref_count; }

  const TriangleMesh& mesh_;
  const QuadricCollapseOptions& options_;

  // Positions (welded vertices): everything a collapse reads or writes per
  // vertex in one 128-byte record, so that touching a vertex costs one or two
  // cache misses instead of one per array (the collapse loop is bound by
  // memory latency: collapses jump around the mesh in cost order).
  struct alignas(64) Vertex {
    Quadric q;
    D3 pos;
    std::uint32_t ref_start = 0, ref_count = 0;  // its live triangles in refs_
    std::uint32_t mark = 0;                      // the calling thread's scratch stamp (Marks)
    std::uint32_t first_wedge = kNone;
    Kind kind = kFree;
    // Set on both ends of a rejected collapse; a change next to such a vertex
    // queues its edges again, since the change may have made them valid.
    std::uint8_t rejected = 0;
    // It has one wedge (no attribute seam), so a collapse need not walk
    // the wedge lists, which live elsewhere in memory.
    std::uint8_t one_wedge = 1;
  };
  static_assert(sizeof(Vertex) == 128);
  std::vector<Vertex> vx_;
  // Versions apart, 4 bytes each: most queue entries are stale, and checking
  // one reads two versions, which should stay in cache.
  std::vector<std::uint32_t> version_;
  std::vector<std::uint32_t> refs_;
  Marks marks_;  // the calling thread's stamp (its marks are in vx_)
  // Regions of the first phase (run_regions): the region owning each
  // position (all its triangles are in it), kSeam for the others.
  static constexpr std::uint8_t kSeam = regions::kSeam;
  std::vector<std::uint8_t> owner_;
  std::vector<std::uint8_t> seam_tri_;  // per triangle: it has a seam corner

  // Wedges (distinct position + attribute sets).
  std::vector<std::uint32_t> wedge_origin_;  // first input vertex of the wedge
  std::vector<std::uint32_t> wedge_vertex_;  // its position
  std::vector<std::uint32_t> next_wedge_;    // next wedge of the same position
  std::vector<std::uint32_t> wedge_parent_;  // wedge it merged into, or itself
  std::vector<std::uint32_t> input_wedge_;   // #V of the input: input vertex -> wedge
  int channels_ = 0;
  double scale_ = 1;  // model units -> working units (a power of two)
  int attr_stride_ = 0;
  std::array<double, kMaxChannels> channel_scale_{};
  std::vector<double> wedge_quadric_;  // attr_stride_ per wedge
  std::vector<float> wedge_attr_;      // channels_ per wedge, current values

  // Triangles (the input's, minus those using a position twice).
  // One 32-byte record per triangle, two to a cache line.
  struct alignas(32) Tri {
    std::uint32_t v[3];  // positions
    std::uint32_t w[3];  // wedges
    float error;         // the bound e(T)
    std::uint32_t alive;
  };
  std::vector<Tri> tri_;

  Lane seq_;  // the whole mesh's queue and counts
  // Rejected collapses are retried when their neighbourhood changes; a full
  // refill of the heap is only the safety net, tried a few times.
  static constexpr int kMaxRefills = 4;
  int refills_ = 0;
};

void Collapser::build() {
  const std::size_t nv = mesh_.positions.size();
  const std::size_t nf = mesh_.triangles.size();
  for (const Triangle& t : mesh_.triangles)
    for (std::uint32_t i : t)
      if (i >= nv)
        throw DataError("quadric_collapse: triangle index " + std::to_string(i) +
                        " out of range (" + std::to_string(nv) + " vertices)");
  for (const Segment& s : mesh_.lines)
    for (std::uint32_t i : s)
      if (i >= nv) throw DataError("quadric_collapse: line index out of range");

  // Weld by position with an open-addressing hash; vertices of one position
  // with equal attributes share a wedge.
  std::size_t cap = 1;
  while (cap < 2 * nv + 1) cap <<= 1;
  std::vector<std::uint32_t> table(cap, kNone);
  auto bits = [](float f) {
    f = f == 0.0f ? 0.0f : f;  // +0 == -0
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
  };
  std::vector<std::uint32_t> vertex_position(nv);
  input_wedge_.assign(nv, kNone);
  std::vector<std::uint32_t> position_first_input;  // per position: first input vertex
  std::vector<std::uint32_t> next_same_position(nv, kNone);
  auto same_attributes = [&](std::uint32_t i, std::uint32_t j) {
    if (mesh_.has_normals() && !(mesh_.normals[i] == mesh_.normals[j])) return false;
    if (mesh_.has_texcoords() && !(mesh_.texcoords[i] == mesh_.texcoords[j])) return false;
    if (mesh_.has_colors() && !(mesh_.colors[i] == mesh_.colors[j])) return false;
    return true;
  };
  for (std::uint32_t i = 0; i < nv; ++i) {
    const Vec3& p = mesh_.positions[i];
    std::uint32_t h = bits(p.x) * 73856093u ^ bits(p.y) * 19349663u ^ bits(p.z) * 83492791u;
    std::size_t slot = (h ^ (h >> 15)) & (cap - 1);
    while (table[slot] != kNone && !(mesh_.positions[position_first_input[table[slot]]] == p))
      slot = (slot + 1) & (cap - 1);
    if (table[slot] == kNone) {
      table[slot] = static_cast<std::uint32_t>(position_first_input.size());
      position_first_input.push_back(i);
    }
    vertex_position[i] = table[slot];
  }
  const std::size_t np = position_first_input.size();
  vx_.resize(np);
  version_.assign(np, 0);
  std::vector<std::uint32_t> last_input(np, kNone);
  for (std::uint32_t i = 0; i < nv; ++i) {
    std::uint32_t p = vertex_position[i];
    // Look for an earlier input vertex of the same position and attributes.
    for (std::uint32_t j = position_first_input[p]; j != kNone && j != i; j = next_same_position[j])
      if (same_attributes(i, j)) {
        input_wedge_[i] = input_wedge_[j];
        break;
      }
    if (last_input[p] != kNone && last_input[p] != i) next_same_position[last_input[p]] = i;
    last_input[p] = i;
    if (input_wedge_[i] == kNone) {
      auto w = static_cast<std::uint32_t>(wedge_origin_.size());
      input_wedge_[i] = w;
      wedge_origin_.push_back(i);
      wedge_vertex_.push_back(p);
      next_wedge_.push_back(vx_[p].first_wedge);
      vx_[p].one_wedge = vx_[p].first_wedge == kNone;
      vx_[p].first_wedge = w;
    }
  }
  const std::size_t nw = wedge_origin_.size();
  wedge_parent_.resize(nw);
  for (std::uint32_t w = 0; w < nw; ++w) wedge_parent_[w] = w;
  for (std::size_t p = 0; p < np; ++p) {
    const Vec3& q = mesh_.positions[position_first_input[p]];
    vx_[p].pos = {q.x, q.y, q.z};
  }

  // Triangles: drop those using a position twice.
  tri_.assign(nf, Tri{{0, 0, 0}, {0, 0, 0}, 0.0f, 0});
  std::vector<std::uint8_t> used(np, 0);
  for (std::size_t t = 0; t < nf; ++t) {
    for (int k = 0; k < 3; ++k) {
      std::uint32_t i = mesh_.triangles[t][k];
      tri_[t].v[k] = vertex_position[i];
      tri_[t].w[k] = input_wedge_[i];
    }
    std::uint32_t a = tri_[t].v[0], b = tri_[t].v[1], c = tri_[t].v[2];
    if (a != b && b != c && c != a) {
      tri_[t].alive = 1;
      ++seq_.live;
      for (int k = 0; k < 3; ++k) used[tri_[t].v[k]] = 1;
    }
  }
  for (std::size_t p = 0; p < np; ++p)
    if (used[p] || !mesh_.lines.empty()) {
      const D3& q = vx_[p].pos;
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        throw DataError("quadric_collapse: vertex " + std::to_string(position_first_input[p]) +
                        " has a non-finite coordinate");
    }

  // Work in power-of-two units in which the bounding box's longest side is in
  // [0.5, 1): multiplying by a power of two is exact, so every decision is
  // the same at any scale (costs are fourth powers of lengths: in model units
  // they overflowed or underflowed float keys beyond about 2^+-30), and the
  // output is scaled back exactly.
  D3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
        std::numeric_limits<double>::max()};
  D3 hi = lo * -1;
  for (std::size_t p = 0; p < np; ++p)
    if (used[p]) {
      const D3& q = vx_[p].pos;
      lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
    }
  const double side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 0.0});
  if (side > 0 && std::isfinite(side)) {
    int exponent = 0;
    std::frexp(side, &exponent);
    scale_ = std::ldexp(1.0, -exponent);
    for (std::size_t p = 0; p < np; ++p) vx_[p].pos = vx_[p].pos * scale_;
  }

  // Vertex -> triangle lists (CSR, later rewritten by appending).
  for (std::size_t t = 0; t < nf; ++t)
    if (tri_[t].alive)
      for (int k = 0; k < 3; ++k) ++vx_[tri_[t].v[k]].ref_count;
  std::uint32_t sum = 0;
  for (std::size_t p = 0; p < np; ++p) {
    vx_[p].ref_start = sum;
    sum += vx_[p].ref_count;
    vx_[p].ref_count = 0;
  }
  refs_.reserve(std::size_t{sum} * 3);
  refs_.resize(sum);
  for (std::size_t t = 0; t < nf; ++t)
    if (tri_[t].alive)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t p = tri_[t].v[k];
        refs_[vx_[p].ref_start + vx_[p].ref_count++] = static_cast<std::uint32_t>(t);
      }

  // Attribute channels, scaled so that a unit difference costs like a
  // displacement of weight x diagonal.
  const double diagonal =
      side > 0 && std::isfinite(side) ? std::sqrt(norm2(hi - lo)) * scale_ : 1.0;
  auto add_channels = [&](bool present, int count, float weight) {
    if (!present) return;
    for (int i = 0; i < count; ++i)
      channel_scale_[channels_++] = std::max(double(weight), 1e-4) * diagonal;
  };
  add_channels(mesh_.has_normals(), 3, options_.normal_weight);
  add_channels(mesh_.has_texcoords(), 2, options_.texcoord_weight);
  add_channels(mesh_.has_colors(), 3, options_.color_weight);
  attr_stride_ = channels_ > 0 ? 11 + 4 * channels_ : 0;
  if (channels_ > 0) {
    wedge_attr_.resize(nw * channels_);
    for (std::size_t w = 0; w < nw; ++w) {
      std::uint32_t i = wedge_origin_[w];
      float* a = &wedge_attr_[w * channels_];
      int c = 0;
      if (mesh_.has_normals())
        for (int k = 0; k < 3; ++k) a[c++] = mesh_.normals[i][k];
      if (mesh_.has_texcoords()) {
        a[c++] = mesh_.texcoords[i].x;
        a[c++] = mesh_.texcoords[i].y;
      }
      if (mesh_.has_colors())
        for (int k = 0; k < 3; ++k) a[c++] = mesh_.colors[i][k];
    }
  }

  compute_kinds();
  compute_quadrics();
  seq_.wedge_pairs.reserve(16);
  seq_.new_errors.reserve(64);
  seq_.new_list.resize(64);
}

/// Whether p's fan (at most 16 triangles) is one closed ring: the corners
/// after p distinct, those before p distinct, and each after one a before one.
bool Collapser::is_ring(std::uint32_t p) const {
  const std::uint32_t valence = vx_[p].ref_count;
  assert(valence <= 16);
  std::uint32_t nx[16], pv[16];
  const std::uint32_t* ts = tris_begin(p);
  for (std::uint32_t i = 0; i < valence; ++i) {
    const Tri& t = tri_[ts[i]];
    const int k = corner_of(t.v, p);
    nx[i] = t.v[kNext[k]];
    pv[i] = t.v[kPrev[k]];
  }
  bool ring = true;
  for (std::uint32_t i = 1; i < valence; ++i)
    for (std::uint32_t j = 0; j < i; ++j) ring &= (nx[j] != nx[i]) & (pv[j] != pv[i]);
  for (std::uint32_t i = 0; i < valence && ring; ++i) {
    bool found = false;
    for (std::uint32_t j = 0; j < valence; ++j) found |= pv[j] == nx[i];
    ring = found;
  }
  return ring;
}

// Feature edges around each vertex decide its kind (table above). Each
// triangle of the fan contributes its two edges at p; per neighbour o, the
// triangles running p -> o and o -> p are counted, so a vertex costs
// O(valence) (a small fan searches its few neighbours linearly, a large one
// finds them by marks).
void Collapser::compute_kinds() {
  const std::size_t np = vx_.size();
  struct Corner {
    std::uint32_t next, prev;  // the corners after and before p
    std::uint32_t t;           // triangle
    std::uint32_t k;           // p's corner in it
  };
  std::vector<Corner> fan;
  // Per neighbour o: the triangles running p -> o and o -> p, and the fan
  // index of the last one of each direction.
  struct Neighbour {
    std::uint32_t o;
    std::uint32_t fwd = 0, bwd = 0, fwd_at = 0, bwd_at = 0;
  };
  std::vector<Neighbour> nbs;
  nbs.reserve(64);
  std::vector<std::uint32_t> slot_of(np);  // large fans: o -> index in nbs
  const bool materials = mesh_.has_materials();
  // No seams anywhere (one wedge per position) and no materials: a fan that
  // is one closed ring, each neighbour once after p and once before it, has
  // no feature edge and is free; that common case is told apart without the
  // neighbour bookkeeping below (which decides the same for it).
  const bool plain = !materials && wedge_origin_.size() == np;
  // Those two cases (and unused vertices) in parallel: each reads the mesh and
  // writes its own kind; `decided` lists them.
  std::vector<std::uint8_t> decided(np, 0);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(np), 4096),
                    [&](const tbb::blocked_range<std::uint32_t>& r) {
                      for (std::uint32_t p = r.begin(); p != r.end(); ++p) {
                        const std::uint32_t valence = vx_[p].ref_count;
                        if (valence == 0) {
                          vx_[p].kind = kLocked;
                          decided[p] = 1;
                        } else if (plain && valence <= 16 && is_ring(p)) {
                          vx_[p].kind = kFree;  // one wedge: plain
                          decided[p] = 1;
                        }
                      }
                    });
  for (std::uint32_t p = 0; p < np; ++p) {
    if (decided[p]) continue;
    fan.clear();
    const std::uint32_t* ts = tris_begin(p);
    for (std::uint32_t i = 0; i < vx_[p].ref_count; ++i) {
      const Tri& t = tri_[ts[i]];
      auto k = static_cast<std::uint32_t>(corner_of(t.v, p));
      fan.push_back({t.v[kNext[k]], t.v[kPrev[k]], ts[i], k});
    }
    // A typical fan has about six neighbours: those are found by a linear
    // search in nbs, which stays in cache; a large fan marks its neighbours.
    nbs.clear();
    const bool small = fan.size() <= 16;
    const std::uint32_t counted = ++marks_.stamp;
    auto slot = [&](std::uint32_t o) -> Neighbour& {
      if (small) {
        for (Neighbour& n : nbs)
          if (n.o == o) return n;
      } else if (vx_[o].mark == counted) {
        return nbs[slot_of[o]];
      } else {
        vx_[o].mark = counted;
        slot_of[o] = static_cast<std::uint32_t>(nbs.size());
      }
      nbs.push_back({o});
      return nbs.back();
    };
    for (std::uint32_t i = 0; i < fan.size(); ++i) {
      Neighbour& f = slot(fan[i].next);
      ++f.fwd;
      f.fwd_at = i;
      Neighbour& b = slot(fan[i].prev);
      ++b.bwd;
      b.bwd_at = i;
    }
    int features = 0;
    bool border = false, locked = false;
    for (const Neighbour& n : nbs) {
      if (n.fwd + n.bwd == 1) {
        ++features;
        border = true;
      } else if (n.fwd + n.bwd > 2 || n.fwd != 1) {
        locked = true;  // non-manifold, or inconsistently oriented
      } else {
        const Corner& f = fan[n.fwd_at];
        const Corner& b = fan[n.bwd_at];
        bool seam = tri_[f.t].w[f.k] != tri_[b.t].w[b.k] ||
                    tri_[f.t].w[kNext[f.k]] != tri_[b.t].w[kPrev[b.k]];
        bool material = materials && mesh_.materials[f.t] != mesh_.materials[b.t];
        if (seam || material) ++features;
      }
    }
    if (locked || (features != 0 && features != 2) || (border && options_.lock_border))
      vx_[p].kind = kLocked;
    else if (features == 2)
      vx_[p].kind = kFeature;
    else
      vx_[p].kind = vx_[p].one_wedge ? kFree : kLocked;
  }
  for (const Segment& s : mesh_.lines)
    for (std::uint32_t i : s) {
      // Vertices of line segments stay where they are; look the position up
      // through the wedge.
      vx_[wedge_vertex_[input_wedge_[i]]].kind = kLocked;
    }
}

// The vertices are cut into a few ranges, one task each: a task goes through
// all triangles and adds what a triangle gives to the vertices (and their
// wedges) of its range only, so every sum is added up in triangle order, as
// one pass would (the result does not depend on the thread count). Vertex
// numbers follow the mesh, so few triangles reach into two ranges and are
// worked out twice.
void Collapser::compute_quadrics() {
  if (attr_stride_ > 0) wedge_quadric_.assign(wedge_origin_.size() * attr_stride_, 0.0);
  const auto np = static_cast<std::uint32_t>(vx_.size());
  const std::uint32_t parts =
      tri_.size() < 16384
          ? 1u
          : static_cast<std::uint32_t>(std::clamp(tbb::this_task_arena::max_concurrency(), 1, 8));
  tbb::parallel_for(std::uint32_t{0}, parts, [&](std::uint32_t i) {
    add_quadrics(static_cast<std::uint32_t>(std::uint64_t{np} * i / parts),
                 static_cast<std::uint32_t>(std::uint64_t{np} * (i + 1) / parts));
  });
}

/// The quadrics of the triangles at the vertices in [lo, hi) (see
/// compute_quadrics()).
void Collapser::add_quadrics(std::uint32_t lo, std::uint32_t hi) {
  const std::size_t nf = tri_.size();
  const double border_weight = options_.border_weight;
  auto mine = [&](std::uint32_t v) { return v >= lo && v < hi; };
  for (std::size_t t = 0; t < nf; ++t) {
    if (!tri_[t].alive) continue;
    const std::uint32_t* corners = tri_[t].v;
    if (!mine(corners[0]) && !mine(corners[1]) && !mine(corners[2])) continue;
    D3 p[3] = {position_of_corner(t, 0), position_of_corner(t, 1), position_of_corner(t, 2)};
    D3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    D3 n = cross(e1, e2);
    double len = std::sqrt(norm2(n));
    if (len <= 0) continue;
    double area = 0.5 * len;
    n = n * (1 / len);
    Quadric q;
    q.add_plane(n, -dot(n, p[0]), area);
    for (int k = 0; k < 3; ++k)
      if (mine(corners[k])) vx_[corners[k]].q.add(q);

    // Penalty planes through feature edges, perpendicular to the face.
    if (border_weight > 0) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = corners[k], b = corners[(k + 1) % 3];
        if (!mine(a) && !mine(b)) continue;
        if (vx_[a].kind == kFree || vx_[b].kind == kFree) continue;
        bool movable = false;
        if (!is_feature_edge(a, b, movable)) continue;
        D3 edge = vx_[b].pos - vx_[a].pos;
        double l2 = norm2(edge);
        if (l2 <= 0) continue;
        D3 m = cross(edge, n);
        double ml = std::sqrt(norm2(m));
        if (ml <= 0) continue;
        m = m * (1 / ml);
        Quadric pq;
        pq.add_plane(m, -dot(m, vx_[a].pos), border_weight * l2);
        if (mine(a)) vx_[a].q.add(pq);
        if (mine(b)) vx_[b].q.add(pq);
      }
    }

    // Hoppe's attribute quadrics: per channel the in-plane gradient g and
    // offset d with g.p_i + d = s_i at the three corners.
    if (attr_stride_ > 0) {
      double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
      double det = g11 * g22 - g12 * g12;
      if (det <= 1e-30 * g11 * g22) continue;
      std::array<D3, kMaxChannels> grad;
      std::array<double, kMaxChannels> off;
      for (int c = 0; c < channels_; ++c) {
        double sc = channel_scale_[c];
        double s0 = wedge_attr_[tri_[t].w[0] * channels_ + c] * sc;
        double s1 = wedge_attr_[tri_[t].w[1] * channels_ + c] * sc;
        double s2 = wedge_attr_[tri_[t].w[2] * channels_ + c] * sc;
        double r1 = s1 - s0, r2 = s2 - s0;
        double alpha = (g22 * r1 - g12 * r2) / det, beta = (g11 * r2 - g12 * r1) / det;
        grad[c] = e1 * alpha + e2 * beta;
        off[c] = s0 - dot(grad[c], p[0]);
      }
      for (int k = 0; k < 3; ++k) {
        if (!mine(corners[k])) continue;
        double* wq = &wedge_quadric_[std::size_t{tri_[t].w[k]} * attr_stride_];
        Quadric* qp = reinterpret_cast<Quadric*>(wq);
        static_assert(sizeof(Quadric) == 10 * sizeof(double));
        for (int c = 0; c < channels_; ++c) {
          // area * (g.p + d)^2 as a quadric in p.
          D3 g = grad[c];
          double d = off[c];
          qp->a00 += area * g.x * g.x;
          qp->a01 += area * g.x * g.y;
          qp->a02 += area * g.x * g.z;
          qp->a11 += area * g.y * g.y;
          qp->a12 += area * g.y * g.z;
          qp->a22 += area * g.z * g.z;
          qp->b0 += area * g.x * d;
          qp->b1 += area * g.y * d;
          qp->b2 += area * g.z * d;
          qp->c += area * d * d;
          double* ch = wq + 11 + 4 * c;
          ch[0] += area * g.x;
          ch[1] += area * g.y;
          ch[2] += area * g.z;
          ch[3] += area * d;
        }
        wq[10] += area;
      }
    }
  }
}

/// Triangles on edge {a, b}, at most 3 written; returns the count (which may
/// exceed 3).
int Collapser::edge_triangles(std::uint32_t a, std::uint32_t b, std::uint32_t* tris) const {
  int n = 0;
  const std::uint32_t* ts = tris_begin(a);
  for (std::uint32_t i = 0; i < vx_[a].ref_count; ++i) {
    std::uint32_t t = ts[i];
    if (tri_[t].v[0] == b || tri_[t].v[1] == b || tri_[t].v[2] == b) {
      if (n < 3) tris[n] = t;
      ++n;
    }
  }
  return n;
}

/// Whether {a, b} is a border, seam or material edge; `movable` tells whether
/// a feature vertex may slide along it (false on non-manifold edges).
bool Collapser::is_feature_edge(std::uint32_t a, std::uint32_t b, bool& movable) const {
  std::uint32_t t[3];
  int n = edge_triangles(a, b, t);
  movable = n == 1 || n == 2;
  if (n == 1) return true;
  if (n != 2) return true;
  auto wedge_at = [&](std::uint32_t tri, std::uint32_t q) {
    for (int k = 0; k < 3; ++k)
      if (tri_[tri].v[k] == q) return tri_[tri].w[k];
    return kNone;
  };
  if (wedge_at(t[0], a) != wedge_at(t[1], a) || wedge_at(t[0], b) != wedge_at(t[1], b)) return true;
  return mesh_.has_materials() && mesh_.materials[t[0]] != mesh_.materials[t[1]];
}

/// The wedge merges of collapsing u into v: for each triangle on the edge,
/// (wedge of u, wedge of v).
void Collapser::collect_wedge_pairs(std::uint32_t u, std::uint32_t v, WedgePairs& pairs) const {
  pairs.clear();
  const std::uint32_t* ts = tris_begin(u);
  for (std::uint32_t i = 0; i < vx_[u].ref_count; ++i) {
    std::uint32_t t = ts[i];
    std::uint32_t wu = kNone, wv = kNone;
    for (int k = 0; k < 3; ++k) {
      if (tri_[t].v[k] == u) wu = tri_[t].w[k];
      if (tri_[t].v[k] == v) wv = tri_[t].w[k];
    }
    if (wv == kNone) continue;
    bool known = false;
    for (auto& pr : pairs) known |= pr.first == wu;
    if (!known) pairs.push_back({wu, wv});
  }
}

/// Adds to `q` the attribute quadrics (minimised over the attribute values) of
/// the wedges the collapse of u into v leaves at v, whose wedge merges are
/// `pairs` (collect_wedge_pairs).
void Collapser::attribute_quadric(std::uint32_t u, std::uint32_t v, const WedgePairs& pairs,
                                  Quadric& q) const {
  std::array<double, kMaxAttrStride> merged;
  auto add_reduced = [&](const double* wq) {
    q.add(*reinterpret_cast<const Quadric*>(wq));
    double area = wq[10];
    if (area <= 0) return;
    double inv = 1 / area;
    for (int c = 0; c < channels_; ++c) {
      const double* g = wq + 11 + 4 * c;
      Quadric r;
      r.a00 = g[0] * g[0];
      r.a01 = g[0] * g[1];
      r.a02 = g[0] * g[2];
      r.a11 = g[1] * g[1];
      r.a12 = g[1] * g[2];
      r.a22 = g[2] * g[2];
      r.b0 = g[0] * g[3];
      r.b1 = g[1] * g[3];
      r.b2 = g[2] * g[3];
      r.c = g[3] * g[3];
      q.a00 -= inv * r.a00;
      q.a01 -= inv * r.a01;
      q.a02 -= inv * r.a02;
      q.a11 -= inv * r.a11;
      q.a12 -= inv * r.a12;
      q.a22 -= inv * r.a22;
      q.b0 -= inv * r.b0;
      q.b1 -= inv * r.b1;
      q.b2 -= inv * r.b2;
      q.c -= inv * r.c;
    }
  };
  const std::size_t s = attr_stride_;
  for (std::uint32_t w = vx_[v].first_wedge; w != kNone; w = next_wedge_[w]) {
    const double* wq = &wedge_quadric_[w * s];
    bool any = false;
    for (auto& pr : pairs)
      if (pr.second == w) {
        if (!any) std::copy(wq, wq + s, merged.begin());
        any = true;
        const double* uq = &wedge_quadric_[pr.first * s];
        for (std::size_t i = 0; i < s; ++i) merged[i] += uq[i];
      }
    add_reduced(any ? merged.data() : wq);
  }
  for (std::uint32_t w = vx_[u].first_wedge; w != kNone; w = next_wedge_[w]) {
    bool paired = false;
    for (auto& pr : pairs) paired |= pr.first == w;
    if (!paired) add_reduced(&wedge_quadric_[w * s]);
  }
}

/// Plans the collapse of edge {a, b}; false if neither end may move.
///
/// | a may move | b may move | plan                                           |
/// |------------|------------|------------------------------------------------|
/// | no         | no         | none                                           |
/// | yes        | no         | a into b, at b                                 |
/// | no         | yes        | b into a, at a                                 |
/// | yes        | yes        | a into b, at the quadric's minimiser if it is  |
/// |            |            | well conditioned and near the edge, else at    |
/// |            |            | the best point of the edge                     |
bool Collapser::evaluate(std::uint32_t a, std::uint32_t b, Collapse& out, WedgePairs& pairs) const {
  bool ma = vx_[a].kind == kFree, mb = vx_[b].kind == kFree;
  if (vx_[a].kind == kFeature || vx_[b].kind == kFeature) {
    bool movable = false;
    bool feature = is_feature_edge(a, b, movable);
    if (vx_[a].kind == kFeature) ma = feature && movable;
    if (vx_[b].kind == kFeature) mb = feature && movable;
    if (ma && mb && !feature) ma = mb = false;
  }
  if (!ma && !mb) return false;
  std::uint32_t u = a, v = b;
  if (!ma) std::swap(u, v);
  Quadric q = vx_[u].q;
  q.add(vx_[v].q);
  if (attr_stride_ > 0) {
    collect_wedge_pairs(u, v, pairs);
    attribute_quadric(u, v, pairs, q);
  }
  D3 w = vx_[v].pos;
  if (ma && mb) {
    D3 pa = vx_[u].pos, pb = vx_[v].pos;
    D3 mid = (pa + pb) * 0.5;
    double l2 = norm2(pb - pa);
    // Adjugate of the symmetric A: six cofactors give both det and A^-1.
    const double c00 = q.a11 * q.a22 - q.a12 * q.a12, c01 = q.a12 * q.a02 - q.a01 * q.a22,
                 c02 = q.a01 * q.a12 - q.a11 * q.a02, c11 = q.a00 * q.a22 - q.a02 * q.a02,
                 c12 = q.a01 * q.a02 - q.a00 * q.a12, c22 = q.a00 * q.a11 - q.a01 * q.a01;
    double det = q.a00 * c00 + q.a01 * c01 + q.a02 * c02;
    double tr = q.a00 + q.a11 + q.a22;
    if (std::abs(det) > 1e-9 * tr * tr * tr) {
      // Solve A x = -g, g = A mid + b, relative to the midpoint for accuracy.
      const D3 bv{q.b0, q.b1, q.b2};
      const D3 g = q.apply_a(mid) + bv;
      double inv = -1 / det;
      D3 x{(c00 * g.x + c01 * g.y + c02 * g.z) * inv, (c01 * g.x + c11 * g.y + c12 * g.z) * inv,
           (c02 * g.x + c12 * g.y + c22 * g.z) * inv};
      if (norm2(x) <= l2) {
        // Q(mid + x) = Q(mid) + 2 g.x + x.A x = Q(mid) + g.x since A x = -g,
        // and Q(mid) = mid.(g + b) + c.
        out.u = u;
        out.v = v;
        out.w = mid + x;
        out.cost = std::max(0.0, dot(mid, g + bv) + q.c + dot(g, x));
        return true;
      }
    }
    {
      // Ill-conditioned, or the minimiser is far from the edge: the best
      // point of the segment u..v, minimising Q(pa + t d) over t in [0, 1].
      D3 d = pb - pa;
      double dad = dot(d, q.apply_a(d));
      double slope = dot(d, q.apply_a(pa) + D3{q.b0, q.b1, q.b2});
      double best_t = q.eval(pa) <= q.eval(pb) ? 0.0 : 1.0;
      if (dad > 0) {
        double t = std::clamp(-slope / dad, 0.0, 1.0);
        if (q.eval(pa + d * t) < q.eval(pa + d * best_t)) best_t = t;
      }
      w = pa + d * best_t;
    }
  }
  out.u = u;
  out.v = v;
  out.w = w;
  out.cost = q.eval(w);
  return true;
}

/// Queues the edges of `a` in `lane`; `collect_rejected` notes neighbours
/// flagged in Vertex::rejected. A region queues only edges between vertices
/// it owns.
template <bool kRegional>
void Collapser::push_edges(std::uint32_t a, Lane& lane, Marks& marks, bool collect_rejected) {
  // In a manifold fan every neighbour follows `a` in exactly one triangle, so
  // the corners after `a` are the neighbours; a corner before `a` is one too
  // only where the fan is open (a border), which the marks find.
  const std::uint32_t s = ++marks.stamp;
  const std::uint32_t* ts = tris_begin(a);
  const std::uint32_t n = vx_[a].ref_count;
  auto push = [&](std::uint32_t b) {
    std::uint32_t& m = mark<kRegional>(marks, b);
    if (m == s) return;  // only in non-manifold or inconsistent fans
    m = s;
    if (kRegional && owner_[b] != lane.id) return;
    if (collect_rejected && vx_[b].rejected) lane.requeue.push_back(b);
    Collapse c;
    if (evaluate(a, b, c, lane.wedge_pairs))
      lane.queue.push({heap_key(c.cost, false), a, b, version_[a] + version_[b]});
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t* c = tri_[ts[i]].v;
    push(c[kNext[corner_of(c, a)]]);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t* c = tri_[ts[i]].v;
    push(c[kPrev[corner_of(c, a)]]);
  }
}

/// Plans every edge once and hands the plans to `emit` in triangle order
/// (so that queues filled from them do not depend on the thread count).
template <class Emit>
void Collapser::plan_edges(Emit emit) {
  // Every edge once, from the triangles: a half-edge a -> b stands for its
  // edge when a < b, or when there is no b -> a (an open border, which only
  // joins vertices that are not free). The edges are planned in parallel,
  // in chunks of triangles, and handed over in triangle order afterwards.
  const std::size_t nf = tri_.size();
  constexpr std::size_t kChunk = 8192;
  std::vector<std::vector<HeapEntry>> planned((nf + kChunk - 1) / kChunk);
  auto plan_chunk = [&](std::size_t chunk, WedgePairs& pairs) {
    std::vector<HeapEntry>& out = planned[chunk];
    out.reserve(2 * kChunk);
    for (std::size_t t = chunk * kChunk; t < std::min(nf, (chunk + 1) * kChunk); ++t) {
      if (!tri_[t].alive) continue;
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = tri_[t].v[k], b = tri_[t].v[(k + 1) % 3];
        if (a > b) {
          if (vx_[a].kind == kFree || vx_[b].kind == kFree) continue;
          bool twin = false;
          const std::uint32_t* ts = tris_begin(b);
          for (std::uint32_t i = 0; i < vx_[b].ref_count && !twin; ++i) {
            const std::uint32_t* c = tri_[ts[i]].v;
            twin = (c[0] == b && c[1] == a) || (c[1] == b && c[2] == a) || (c[2] == b && c[0] == a);
          }
          if (twin) continue;
        }
        Collapse c;
        if (evaluate(a, b, c, pairs))
          out.push_back({heap_key(c.cost, false), a, b, version_[a] + version_[b]});
      }
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, planned.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      WedgePairs pairs;
                      for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk)
                        plan_chunk(chunk, pairs);
                    });
  for (const std::vector<HeapEntry>& entries : planned)
    for (const HeapEntry& e : entries) emit(e);
}

void Collapser::fill_heap() {
  seq_.queue.clear();
  plan_edges([&](const HeapEntry& e) { seq_.queue.push(e); });
  seq_.collapses_since_fill = 0;
  seq_.budget_rejections = 0;
}

/// Checks the collapse (link condition, duplicate triangles, flips, slivers,
/// error budget) and performs it if allowed. A collapse that fails only the
/// sliver test is reported as such: the caller defers it (see run()).
template <bool kRegional>
Outcome Collapser::try_collapse(const Collapse& c, bool allow_slivers, Lane& lane, Marks& marks) {
  const std::uint32_t u = c.u, v = c.v;
  const D3 w = c.w;

  // Link condition: the vertices adjacent to both u and v must be exactly the
  // third corners of the triangles on the edge.
  const std::uint32_t s_u = ++marks.stamp;
  const std::uint32_t s_common = ++marks.stamp;
  const std::uint32_t* tu = tris_begin(u);
  const std::uint32_t* tvv = tris_begin(v);
  const std::uint32_t nu = vx_[u].ref_count, nv = vx_[v].ref_count;
  // The neighbours' quadrics (the first line of their records) are read by
  // push_edges() after the collapse: asked for below, as the fans are walked.
  int edge_tris = 0;
  for (std::uint32_t i = 0; i < nu; ++i) {
    std::uint32_t t = tu[i];
    bool has_v = false;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t x = tri_[t].v[k];
      has_v |= x == v;
      __builtin_prefetch(&vx_[x].q);
      mark<kRegional>(marks, x) = s_u;  // u too: it is skipped below
    }
    edge_tris += has_v;
    // An edge triangle leaves the list of its third corner if the collapse
    // is done: ask for that list now.
    const std::uint32_t* c = tri_[t].v;
    const std::uint32_t third = has_v ? c[0] ^ c[1] ^ c[2] ^ u ^ v : u;
    __builtin_prefetch(refs_.data() + vx_[third].ref_start);
  }
  int common = 0;
  for (std::uint32_t i = 0; i < nv; ++i) {
    std::uint32_t t = tvv[i];
    for (int k = 0; k < 3; ++k) {
      // Branch-free: which corners match depends on the data.
      std::uint32_t x = tri_[t].v[k];
      __builtin_prefetch(&vx_[x].q);
      std::uint32_t& m = mark<kRegional>(marks, x);
      bool hit = (m == s_u) & (x != v) & (x != u);
      common += hit;
      m = hit ? s_common : m;
    }
  }
  if (edge_tris == 0 || common != edge_tris) return Outcome::kRejected;

  // Geometry of the triangles that stay: flips, slivers, duplicates, bound.
  std::vector<std::pair<std::uint32_t, float>>& new_errors = lane.new_errors;
  new_errors.clear();
  const double min_q = allow_slivers ? 0.0 : double(options_.min_triangle_quality);
  bool sliver = false;
  const double max_error = options_.target.max_error * scale_;
  bool over_budget = false;
  // The bound of a triangle that keeps its place in the mesh grows by the
  // distance its moved corner travels (see the header).
  const D3 pu = vx_[u].pos, pv = vx_[v].pos;
  const double move_u = std::sqrt(norm2(w - pu)), move_v = std::sqrt(norm2(w - pv));
  auto check = [&](std::uint32_t t, std::uint32_t moved, D3 pk, double move) {
    const std::uint32_t* c = tri_[t].v;
    const int k = corner_of(c, moved);
    // Corners (moved, a, b) in the triangle's order; both normals are taken
    // against the edge a -> b that stays.
    const D3 pa = vx_[c[kNext[k]]].pos, pb = vx_[c[kPrev[k]]].pos;
    const D3 e = pb - pa, da_old = pa - pk, da_new = pa - w;
    const D3 n_old = cross(da_old, e), n_new = cross(da_new, e);
    double area2_new = norm2(n_new), area2_old = norm2(n_old);
    if (area2_new <= 0 && area2_old > 0) return false;
    if (dot(n_old, n_new) < 0) return false;
    if (min_q > 0) {
      // quality = 2 sqrt(3) |n| / l (l = sum of squared edge lengths), so
      // q_new < min_q  <=>  12 |n_new|^2 < min_q^2 l_new^2 and
      // q_new < q_old  <=>  |n_new|^2 l_old^2 < |n_old|^2 l_new^2.
      double ee = norm2(e);
      double l_new = ee + norm2(da_new) + norm2(pb - w);
      double l_old = ee + norm2(da_old) + norm2(pb - pk);
      if (12 * area2_new < min_q * min_q * l_new * l_new &&
          area2_new * l_old * l_old < area2_old * l_new * l_new)
        sliver = true;
    }
    // Rounded up to float: the relative rounding error of float (2^-24) is
    // below the 1e-6 added first.
    auto ef = static_cast<float>((tri_[t].error + move) * (1 + 1e-6));
    if (ef > max_error) {
      over_budget = true;
      return false;
    }
    new_errors.push_back({t, ef});
    return true;
  };
  for (std::uint32_t i = 0; i < nu; ++i) {
    std::uint32_t t = tu[i];
    const std::uint32_t* c = tri_[t].v;
    const int k = corner_of(c, u);
    const std::uint32_t x = c[kNext[k]], y = c[kPrev[k]];
    if (x == v || y == v) continue;
    // (u, x, y) becomes (v, x, y): a duplicate if v already has a triangle on x and y.
    if (mark<kRegional>(marks, x) == s_common && mark<kRegional>(marks, y) == s_common)
      for (std::uint32_t j = 0; j < nv; ++j) {
        std::uint32_t t2 = tvv[j];
        int hits = 0;
        for (int k = 0; k < 3; ++k) hits += tri_[t2].v[k] == x || tri_[t2].v[k] == y;
        if (hits == 2) return Outcome::kRejected;
      }
    if (!check(t, u, pu, move_u)) return over_budget ? Outcome::kOverBudget : Outcome::kRejected;
  }
  for (std::uint32_t i = 0; i < nv; ++i) {
    std::uint32_t t = tvv[i];
    if (tri_[t].v[0] == u || tri_[t].v[1] == u || tri_[t].v[2] == u) continue;
    if (!check(t, v, pv, move_v)) return over_budget ? Outcome::kOverBudget : Outcome::kRejected;
  }
  if (sliver) return Outcome::kSliver;
  // v's list may grow to nu + nv - 2 (see below); a region must have room.
  if (kRegional && nu + nv > lane.refs_end - lane.refs_next) return Outcome::kNoRoom;

  // Allowed: perform it. Wedges of u merge into the wedges of v they meet on
  // the edge triangles; others move to v as they are.
  const std::uint32_t fu = vx_[u].first_wedge, fv = vx_[v].first_wedge;
  if (attr_stride_ == 0 && vx_[u].one_wedge && vx_[v].one_wedge) {
    // One wedge on each side (no attribute seams here): they merge.
    wedge_parent_[fu] = fv;
  } else {
    collect_wedge_pairs(u, v, lane.wedge_pairs);
    for (std::uint32_t wu = fu; wu != kNone;) {
      std::uint32_t next = next_wedge_[wu];
      std::uint32_t target = kNone;
      for (auto& pr : lane.wedge_pairs)
        if (pr.first == wu) target = pr.second;
      if (target != kNone) {
        wedge_parent_[wu] = target;
        if (attr_stride_ > 0) {
          double* dst = &wedge_quadric_[std::size_t{target} * attr_stride_];
          const double* src = &wedge_quadric_[std::size_t{wu} * attr_stride_];
          for (int i = 0; i < attr_stride_; ++i) dst[i] += src[i];
        }
      } else {
        wedge_vertex_[wu] = v;
        next_wedge_[wu] = vx_[v].first_wedge;
        vx_[v].first_wedge = wu;
      }
      wu = next;
    }
    vx_[v].one_wedge = next_wedge_[vx_[v].first_wedge] == kNone;
  }
  vx_[u].first_wedge = kNone;

  for (auto& [t, e] : new_errors) tri_[t].error = e;
  // v's new list: its own triangles but the edge ones, then u's that stay.
  // The edge triangles die and leave the lists of their third corners too,
  // so that every list holds live triangles only.
  // (Written through a pointer into scratch of room nu + nv: push_back
  // here stopped being inlined, 8 % of a call.)
  if (lane.new_list.size() < nu + nv) lane.new_list.resize(nu + nv);
  std::uint32_t* const new_list = lane.new_list.data();
  std::uint32_t new_count = 0;
  for (std::uint32_t i = 0; i < nv; ++i) {
    std::uint32_t t = tvv[i];
    if (tri_[t].v[0] != u && tri_[t].v[1] != u && tri_[t].v[2] != u) new_list[new_count++] = t;
  }
  for (std::uint32_t i = 0; i < nu; ++i) {
    std::uint32_t t = tu[i];
    std::uint32_t* c = tri_[t].v;
    if (c[0] == v || c[1] == v || c[2] == v) {
      tri_[t].alive = 0;
      --lane.live;
      if constexpr (kRegional) lane.inner -= seam_tri_[t] == 0;
      std::uint32_t x = c[0] != u && c[0] != v ? c[0] : c[1] != u && c[1] != v ? c[1] : c[2];
      // A region leaves the lists of the seam vertices it does not own
      // alone (other regions may change them); run_regions() drops their
      // dead triangles afterwards.
      if (kRegional && owner_[x] != lane.id) continue;
      std::uint32_t* xs = tris_begin(x);
      std::uint32_t nx = vx_[x].ref_count;
      for (std::uint32_t j = 0; j < nx; ++j)
        if (xs[j] == t) {
          xs[j] = xs[--nx];
          break;
        }
      vx_[x].ref_count = nx;
      continue;
    }
    for (int k = 0; k < 3; ++k)
      if (c[k] == u) {
        c[k] = v;
        std::uint32_t wu = tri_[t].w[k];
        tri_[t].w[k] = wedge_parent_[wu] != wu ? wedge_parent_[wu] : wu;
      }
    new_list[new_count++] = t;
  }
  if (new_count <= vx_[v].ref_count) {
    std::copy(new_list, new_list + new_count, refs_.begin() + vx_[v].ref_start);
  } else if (kRegional) {
    vx_[v].ref_start = static_cast<std::uint32_t>(lane.refs_next);
    std::copy(new_list, new_list + new_count, refs_.begin() + lane.refs_next);
    lane.refs_next += new_count;
  } else {
    vx_[v].ref_start = static_cast<std::uint32_t>(refs_.size());
    refs_.insert(refs_.end(), new_list, new_list + new_count);
  }
  vx_[v].ref_count = new_count;
  vx_[u].ref_count = 0;

  vx_[v].q.add(vx_[u].q);
  vx_[v].pos = w;
  ++version_[u];
  ++version_[v];
  if (attr_stride_ > 0) update_wedge_attributes(v);
  return Outcome::kDone;
}

/// The attributes of v's wedges at v's (new) position: the minimisers of
/// their attribute quadrics.
void Collapser::update_wedge_attributes(std::uint32_t v) {
  const D3 p = vx_[v].pos;
  for (std::uint32_t w = vx_[v].first_wedge; w != kNone; w = next_wedge_[w]) {
    const double* wq = &wedge_quadric_[std::size_t{w} * attr_stride_];
    double area = wq[10];
    if (area <= 0) continue;
    float* a = &wedge_attr_[std::size_t{w} * channels_];
    for (int c = 0; c < channels_; ++c) {
      const double* g = wq + 11 + 4 * c;
      a[c] = static_cast<float>((g[0] * p.x + g[1] * p.y + g[2] * p.z + g[3]) / area /
                                channel_scale_[c]);
    }
    int c = 0;
    if (mesh_.has_normals()) {
      Vec3 n = normalized(Vec3{a[0], a[1], a[2]});
      a[0] = n.x, a[1] = n.y, a[2] = n.z;
      c = 3;
    }
    if (mesh_.has_texcoords()) c += 2;
    if (mesh_.has_colors())
      for (int k = 0; k < 3; ++k) a[c + k] = std::clamp(a[c + k], 0.0f, 1.0f);
  }
}

/// Pops and performs the collapses of `lane` until it counts at most
/// `lane.floor` live triangles, its queue is empty, the next key is above
/// `limit`, or (a region) its list stretch is full.
template <bool kRegional>
Halt Collapser::drain(Lane& lane, Marks& marks, std::uint32_t limit) {
  auto stale = [&](const HeapEntry& x) { return version_[x.a] + version_[x.b] != x.stamp; };
  CollapseQueue& queue = lane.queue;
  while ((kRegional ? lane.inner : lane.live) > lane.floor) {
    if (queue.size() > 8 * lane.live + 1024) {
      // Mostly stale entries (a closed mesh has 1.5 edges per triangle):
      // dropping them keeps the heap shallow and in cache as the mesh shrinks.
      queue.drop_if(stale);
    }
    HeapEntry e;
    if (!queue.pop(e, stale, limit)) return queue.empty() ? Halt::kEmpty : Halt::kLimit;
    const bool deferred = is_deferred(e);
    if (stale(e)) continue;
    // The two fans are usually cold (the last collapse was elsewhere): ask
    // for all their triangles at once, before the evaluation, instead of one
    // miss after the other in the checks.
    for (std::uint32_t x : {e.a, e.b}) {
      const std::uint32_t* ts = tris_begin(x);
      for (std::uint32_t i = 0; i < vx_[x].ref_count; ++i) __builtin_prefetch(&tri_[ts[i]]);
    }
    if (const HeapEntry* next = queue.peek()) {
      // Likely the next collapse: its ends' records arrive while this one is
      // checked and done.
      for (std::uint32_t x : {next->a, next->b}) {
        __builtin_prefetch(&vx_[x]);
        __builtin_prefetch(reinterpret_cast<const char*>(&vx_[x]) + 64);
      }
    }
    Collapse c;
    if (!evaluate(e.a, e.b, c, lane.wedge_pairs)) continue;
    // A collapse that would create a sliver waits until nothing cheaper than
    // twice its cost is left (ties: after the others); then it is taken, since
    // the alternative is a worse shape.
    Outcome outcome = try_collapse<kRegional>(c, deferred, lane, marks);
    if (outcome == Outcome::kSliver) {
      queue.push({heap_key(2 * c.cost, true), e.a, e.b, e.stamp});
      continue;
    }
    if (outcome == Outcome::kOverBudget) {
      // Bounds only grow: this collapse stays over budget unless u or v
      // change, which re-queues it anyway.
      ++lane.budget_rejections;
      continue;
    }
    if (outcome == Outcome::kRejected) {
      vx_[e.a].rejected = vx_[e.b].rejected = 1;
      continue;
    }
    if (outcome == Outcome::kNoRoom) return Halt::kNoRoom;
    ++lane.collapses_since_fill;
    if (const HeapEntry* next = queue.peek()) {
      // The records of the next collapse's ends were asked for above and
      // have arrived by now: ask for their triangle lists, which arrive while
      // the edges of the merged vertex are queued.
      __builtin_prefetch(tris_begin(next->a));
      __builtin_prefetch(tris_begin(next->b));
    }
    lane.requeue.clear();
    push_edges<kRegional>(c.v, lane, marks, true);
    for (std::size_t i = 0; i < lane.requeue.size(); ++i) {
      std::uint32_t n = lane.requeue[i];
      vx_[n].rejected = 0;
      push_edges<kRegional>(n, lane, marks);
    }
  }
  return Halt::kFloor;
}

StopReason Collapser::run(std::size_t target, std::string& detail) {
  if (seq_.live <= target) {
    detail = "reached " + std::to_string(seq_.live) + " triangles (target " +
             std::to_string(target) + ")";
    return StopReason::kTargetReached;
  }
  if (seq_.queue.empty() && seq_.collapses_since_fill == 0) {
    // The regional phase when it removes at least a quarter of the
    // triangles (regions::worthwhile).
    if (regions::worthwhile(target, seq_.live)) run_regions(target);
    fill_heap();
  }
  seq_.floor = target;
  while (seq_.live > target) {
    if (drain<false>(seq_, marks_, 0xffffffffu) != Halt::kEmpty) break;
    // Collapses rejected earlier may be allowed now that their
    // neighbourhood changed: try every edge again while that still helps.
    if (seq_.collapses_since_fill == 0 || ++refills_ > kMaxRefills) break;
    fill_heap();
  }
  if (seq_.live <= target) {
    detail = "reached " + std::to_string(seq_.live) + " triangles (target " +
             std::to_string(target) + ")";
    return StopReason::kTargetReached;
  }
  if (seq_.budget_rejections > 0) {
    detail = "every remaining collapse would raise the error bound above the budget of " +
             std::to_string(options_.target.max_error) + "; " + std::to_string(seq_.live) +
             " triangles remain (target " + std::to_string(target) + ")";
    return StopReason::kErrorBudgetReached;
  }
  detail =
      "no edge can collapse without flipping or degenerating a triangle, changing the "
      "topology (link condition) or moving a locked border/feature vertex; " +
      std::to_string(seq_.live) + " triangles remain (target " + std::to_string(target) + ")";
  return StopReason::kCannotSimplify;
}

/// The region of every triangle (see regions::kd_partition).
std::vector<std::uint8_t> Collapser::partition(int parts) const {
  const std::size_t nf = tri_.size();
  std::vector<float> centre(3 * nf);
  std::vector<std::uint8_t> use(nf);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, nf, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const auto i = static_cast<std::uint32_t>(t);
          const D3 c =
              position_of_corner(i, 0) + position_of_corner(i, 1) + position_of_corner(i, 2);
          centre[3 * t] = float(c.x);
          centre[3 * t + 1] = float(c.y);
          centre[3 * t + 2] = float(c.z);
          use[t] = tri_[t].alive != 0;
        }
      });
  return regions::kd_partition(centre, use, parts);
}

/// The first phase of a large reduction: the mesh is cut into regions (see
/// partition()), and each region collapses its own edges, those between
/// vertices all of whose triangles lie in it, with its own queue, on TBB's
/// threads. The vertices on the cuts (seams) stay as they are, so regions
/// share nothing they write. To stay close to the order of one queue over the
/// whole mesh, the regions advance together in rounds, each round up to a
/// common cost limit that grows from round to round, until the triangles
/// without a seam corner are down to their share of regions::goal(); a region
/// never goes below its share of the target. (Counting the seams' triangles
/// too would drive the interiors far below the target, since the seams stay:
/// on the bunny that cost 10x in mean deviation.) run() then continues on the whole mesh (seams
/// included) from a new queue. The regions and rounds depend on the mesh and target only, so the
/// result does not depend on the thread count.
void Collapser::run_regions(std::size_t target) {
  const std::size_t np = vx_.size();
  const int parts = regions::part_count(seq_.live);
  const std::vector<std::uint8_t> tri_region = partition(parts);

  // Owners: the region of all of a position's triangles, if it is one.
  owner_.assign(np, kSeam);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t p = r.begin(); p != r.end(); ++p) {
                        const std::uint32_t n = vx_[p].ref_count;
                        if (n == 0) continue;
                        const std::uint32_t* ts = tris_begin(static_cast<std::uint32_t>(p));
                        const std::uint8_t region = tri_region[ts[0]];
                        bool one = true;
                        for (std::uint32_t i = 1; i < n; ++i) one &= tri_region[ts[i]] == region;
                        if (one) owner_[p] = region;
                      }
                    });

  // Lanes: a share of the target, and a stretch of refs_ for growing lists
  // (room for 4 entries per triangle; a 99 % reduction of the bunny appends
  // about 3.3; a lane that runs out stops, see drain()).
  std::vector<std::unique_ptr<Lane>> lanes;
  for (int r = 0; r < parts; ++r) {
    lanes.push_back(std::make_unique<Lane>(20));
    lanes.back()->id = static_cast<std::uint8_t>(r);
  }
  seam_tri_.assign(tri_.size(), 0);
  std::size_t inner = 0;
  for (std::size_t t = 0; t < tri_.size(); ++t)
    if (tri_[t].alive) {
      Lane& lane = *lanes[tri_region[t]];
      ++lane.live;
      const std::uint32_t* c = tri_[t].v;
      seam_tri_[t] = owner_[c[0]] == kSeam || owner_[c[1]] == kSeam || owner_[c[2]] == kSeam;
      lane.inner += seam_tri_[t] == 0;
      inner += seam_tri_[t] == 0;
    }
  std::size_t next = refs_.size();
  for (auto& lane : lanes) {
    lane->floor = (lane->inner * target + seq_.live - 1) / seq_.live;
    lane->refs_next = next;
    next += 4 * lane->live;
    lane->refs_end = next;
  }
  refs_.resize(next);

  std::uint32_t limit = 0xffffffffu;
  plan_edges([&](const HeapEntry& e) {
    const std::uint8_t region = owner_[e.a];
    if (region == kSeam || owner_[e.b] != region) return;
    lanes[region]->queue.push(e);
    limit = std::min(limit, e.key);
  });

  tbb::enumerable_thread_specific<Marks> marks([&] {
    Marks m;
    m.mark.assign(np, 0);
    return m;
  });
  // The goal, for the inner triangles: their share of regions::goal().
  const std::size_t goal = regions::goal(target, seq_.live) * inner / seq_.live;
  regions::run_rounds(lanes, goal, limit, 1, [&](Lane& lane, std::uint32_t round_limit) {
    return drain<true>(lane, marks.local(), round_limit) != Halt::kLimit;
  });

  // Back to one mesh: the seams' lists lose the triangles that died in
  // regions, and the counts add up.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t p = r.begin(); p != r.end(); ++p) {
                        if (owner_[p] != kSeam) continue;
                        std::uint32_t* ts = refs_.data() + vx_[p].ref_start;
                        std::uint32_t kept = 0;
                        for (std::uint32_t i = 0; i < vx_[p].ref_count; ++i)
                          if (tri_[ts[i]].alive) ts[kept++] = ts[i];
                        vx_[p].ref_count = kept;
                      }
                    });
  std::size_t live = 0;
  for (auto& lane : lanes) live += lane->live;
  seq_.live = live;
  owner_.clear();
  seam_tri_.clear();
}

SimplifyResult Collapser::snapshot() const {
  SimplifyResult r;
  const std::size_t nw = wedge_origin_.size();
  std::vector<std::uint32_t> out_index(nw, kNone);
  const std::size_t nf = tri_.size();
  auto root = [&](std::uint32_t w) {
    while (wedge_parent_[w] != w) w = wedge_parent_[w];
    return w;
  };
  for (std::size_t t = 0; t < nf; ++t)
    if (tri_[t].alive)
      for (int k = 0; k < 3; ++k) out_index[tri_[t].w[k]] = 0;
  for (const Segment& s : mesh_.lines)
    for (std::uint32_t i : s) out_index[root(input_wedge_[i])] = 0;
  std::uint32_t count = 0;
  for (std::size_t w = 0; w < nw; ++w)
    if (out_index[w] == 0)
      out_index[w] = count++;
    else
      out_index[w] = kNone;
  TriangleMesh& m = r.mesh;
  m.positions.resize(count);
  r.vertex_map.resize(count);
  if (mesh_.has_normals()) m.normals.resize(count);
  if (mesh_.has_texcoords()) m.texcoords.resize(count);
  if (mesh_.has_colors()) m.colors.resize(count);
  for (std::size_t w = 0; w < nw; ++w) {
    std::uint32_t o = out_index[w];
    if (o == kNone) continue;
    const D3& p = vx_[wedge_vertex_[w]].pos;
    const double back = 1 / scale_;  // exact: a power of two
    m.positions[o] = {static_cast<float>(p.x * back), static_cast<float>(p.y * back),
                      static_cast<float>(p.z * back)};
    r.vertex_map[o] = wedge_origin_[w];
    int c = 0;
    const float* a = channels_ > 0 ? &wedge_attr_[w * channels_] : nullptr;
    if (mesh_.has_normals()) {
      m.normals[o] = {a[0], a[1], a[2]};
      c = 3;
    }
    if (mesh_.has_texcoords()) {
      m.texcoords[o] = {a[c], a[c + 1]};
      c += 2;
    }
    if (mesh_.has_colors()) m.colors[o] = {a[c], a[c + 1], a[c + 2]};
  }
  m.triangles.reserve(seq_.live);
  r.face_map.reserve(seq_.live);
  float error = 0;
  for (std::size_t t = 0; t < nf; ++t) {
    if (!tri_[t].alive) continue;
    m.triangles.push_back(
        {out_index[tri_[t].w[0]], out_index[tri_[t].w[1]], out_index[tri_[t].w[2]]});
    r.face_map.push_back(static_cast<std::uint32_t>(t));
    if (mesh_.has_materials()) m.materials.push_back(mesh_.materials[t]);
    error = std::max(error, tri_[t].error);
  }
  for (const Segment& s : mesh_.lines)
    m.lines.push_back({out_index[root(input_wedge_[s[0]])], out_index[root(input_wedge_[s[1]])]});
  r.error = static_cast<float>(error / scale_);
  return r;
}

/// The triangle count `target` asks for; an error budget alone asks for as
/// few as the budget allows.
std::size_t triangle_goal(const SimplifyTarget& target, std::size_t input) {
  if (target.triangles == 0 && target.ratio <= 0)
    return std::isfinite(target.max_error) ? 0 : input;
  return target.triangle_target(input);
}

}  // namespace

std::vector<SimplifyResult> quadric_collapse_chain(
    const TriangleMesh& mesh, const QuadricCollapseOptions& options,
    const std::function<std::optional<std::size_t>(std::size_t level, std::size_t previous)>&
        next_target) {
  std::vector<SimplifyResult> results;
  const std::size_t input = mesh.triangles.size();
  std::optional<std::size_t> next = next_target(0, input);
  if (!next) return results;
  Collapser collapser(mesh, options);
  bool stopped = false;
  StopReason last_reason = StopReason::kNoReduction;
  std::string last_detail;
  while (next) {
    const std::size_t target = *next;
    if (!stopped) {
      if (target >= input && !std::isfinite(options.target.max_error)) {
        last_reason = StopReason::kNoReduction;
        last_detail = "the target (" + std::to_string(target) +
                      " triangles) asks for no "
                      "reduction of " +
                      std::to_string(input) + " triangles";
      } else {
        last_reason = collapser.run(target, last_detail);
        stopped = last_reason != StopReason::kTargetReached;
      }
    }
    SimplifyResult r = collapser.snapshot();
    r.stop_reason = last_reason;
    r.stop_detail = last_detail;
    const std::size_t reached = r.mesh.triangles.size();
    results.push_back(std::move(r));
    if (stopped) break;
    next = next_target(results.size(), reached);
  }
  return results;
}

std::vector<SimplifyResult> quadric_collapse_chain(
    const TriangleMesh& mesh, const QuadricCollapseOptions& options,
    const std::vector<std::size_t>& triangle_targets) {
  std::vector<SimplifyResult> results = quadric_collapse_chain(
      mesh, options, [&](std::size_t level, std::size_t) -> std::optional<std::size_t> {
        if (level < triangle_targets.size()) return triangle_targets[level];
        return std::nullopt;
      });
  // After an early stop, the remaining targets get the last mesh again.
  while (!results.empty() && results.size() < triangle_targets.size())
    results.push_back(results.back());
  return results;
}

SimplifyResult quadric_collapse(const TriangleMesh& mesh, const QuadricCollapseOptions& options) {
  std::size_t target = triangle_goal(options.target, mesh.triangles.size());
  return std::move(quadric_collapse_chain(mesh, options, {target}).front());
}

}  // namespace lodforge
