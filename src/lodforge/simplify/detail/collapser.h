#pragma once
/// The state and steps of quadric_collapse (see quadric_collapse.h for the
/// contract and quadric_collapse.cpp for the method). Internal to simplify/:
/// set-up in collapser_build.cpp, the collapse loop in collapser_loop.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/core/quadric.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/detail/collapse_queue.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/regions.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge::detail::qem {

/// A point or vector in double precision (the working units of the collapse).
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

/// A x p, the quadratic part of q applied to p.
inline D3 apply_a(const Quadric& q, D3 p) {
  return {q.a00 * p.x + q.a01 * p.y + q.a02 * p.z, q.a01 * p.x + q.a11 * p.y + q.a12 * p.z,
          q.a02 * p.x + q.a12 * p.y + q.a22 * p.z};
}
/// Q(p), clamped at 0.
inline double eval(const Quadric& q, D3 p) {
  return q(p.x, p.y, p.z);
}

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
  // Set-up (collapser_build.cpp): the steps of build(), in order.
  void build();
  /// Per input vertex: its position (welded vertex); per position: its first
  /// input vertex.
  struct Welding {
    std::vector<std::uint32_t> vertex_position;
    std::vector<std::uint32_t> position_first_input;
  };
  Welding weld_positions() const;
  void make_wedges(const Welding& welding);
  std::vector<std::uint8_t> collect_triangles(const Welding& welding);
  double normalise_units(const std::vector<std::uint8_t>& used);
  void build_triangle_lists();
  void set_up_channels(double diagonal);
  void compute_kinds();
  bool is_ring(std::uint32_t p) const;
  void compute_quadrics();
  void add_quadrics(std::uint32_t lo, std::uint32_t hi);
  void add_attribute_quadrics(std::uint32_t t, double area, D3 e1, D3 e2, std::uint32_t lo,
                              std::uint32_t hi);
  // The collapse loop (collapser_loop.cpp).
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
  template <bool kRegional>
  bool link_condition(std::uint32_t u, std::uint32_t v, Marks& marks, std::uint32_t& s_common);
  template <bool kRegional>
  Outcome check_fans(const Collapse& c, bool allow_slivers, Lane& lane, Marks& marks,
                     std::uint32_t s_common);
  void merge_wedges(std::uint32_t u, std::uint32_t v, Lane& lane);
  template <bool kRegional>
  void rewrite_triangle_lists(std::uint32_t u, std::uint32_t v, Lane& lane);
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
    Quadric q{};
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

}  // namespace lodforge::detail::qem
