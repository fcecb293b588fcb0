// Vertex clustering by octree quantisation.
//
// Implements the vertex clustering of the LODCreator thesis: the octree of
// Gervautz & Purgathofer's colour quantisation ("A simple method for color
// quantization: octree quantization", 1988) applied to vertex positions, in
// the spirit of Rossignac & Borrel's "Multi-resolution 3D approximations for
// rendering complex scenes" (1993), with the thesis' three representative
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
// * A cell with more than 64 vertices (only when a level skips many depths)
//   scores the 64 closest to the weighted mean, so a level costs O(faces)
//   and not O(vertices x faces) per cell.
//
// Why a quadric heuristic: the thesis' heuristics choose among existing
// vertices, which on a curved surface leaves the new triangles on one side
// of the cell's surface; Lindstrom's point lies in the middle of it. On the
// Stanford bunny the thesis' method misses its own published figures at 50 %
// and 99 % reduction; with the quadric point as a candidate every figure is
// met (measurements and the choice of the default weight: see the header).
//
// The steps, in detail/: clustering_level0 (level 0 from the input),
// clustering_sort (its octree order), clustering_choice (a level's
// representatives), clustering_faces (a level's faces); this file drives
// them level by level (choose_depth, number_cells, map_triangles,
// remap_and_pick, measure_error).
#include "lodforge/simplify/vertex_clustering.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>
#include <tbb/task_group.h>

#include "lodforge/simplify/detail/clustering_choice.h"
#include "lodforge/simplify/detail/clustering_cut.h"
#include "lodforge/simplify/detail/clustering_faces.h"
#include "lodforge/simplify/detail/clustering_level0.h"

namespace lodforge {
namespace {

using namespace detail::clustering;  // NOLINT(google-build-using-namespace)

/// Items per task of a level's passes over its vertices.
constexpr std::size_t kGrain = 16384;

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

/// The largest displacement of a represented input vertex over the levels.
///
/// The input vertices of one level-0 vertex share its position exactly, so
/// it is measured over level 0's positions (kept when the first level
/// replaces them; until then the previous cut's). Cells are runs of the
/// previous level's vertices in octree order and level 0 is in octree
/// order, so every vertex of a level stands for a run of level-0 vertices:
/// [level0_start[k], level0_start[k + 1]) for vertex k (until the first
/// level, [k, k + 1)), of which those a dropped vertex stood for are no
/// longer represented (level0_alive = 0).
///
/// Each vertex of a level keeps a bound on the distance from it to the
/// level-0 vertices it stands for (`reach`), so the level-0 vertices of a
/// previous vertex k in cell j are within |p_j - p_k| + reach_k of the new
/// position p_j (with a margin for rounding); when that is no more than the
/// largest displacement found so far (on this thread), they are not read.
/// The largest displacement is still exact: only vertices that cannot
/// exceed it are left out.
class Displacement {
 public:
  /// The largest displacement of the level `next` made of `prev` by `cells`
  /// (`keep`: cell -> its vertex in `next` or kNone), in double: a float
  /// square overflows for coordinates beyond ~1.8e19. Cell by cell, over the
  /// level-0 vertices it stands for (read in sequence), in tasks of about
  /// kErrorChunk of them.
  float measure(const Cut& prev, const Cells& cells, std::span<const std::uint32_t> keep,
                std::size_t kept, const Cut& next);
  /// Keeps level 0's positions once the first level no longer holds them.
  void keep_level0(Buffer<Vec3>&& pos) { input_pos_ = std::move(pos); }

 private:
  double cell_reach(const Cut& prev, const Cells& cells, std::size_t j, const Vec3& p,
                    bool first_level, double& error2) const;

  Buffer<Vec3> input_pos_;
  Buffer<std::uint32_t> level0_start_, next_start_;
  Buffer<double> reach_, next_reach_;
  Buffer<std::uint8_t> level0_alive_;
  tbb::enumerable_thread_specific<double> largest2_;
};

constexpr double kMargin = 1 + 1e-5;  // float rounding of a difference: 2^-24 relative

/// The bound on the distance from p to the level-0 vertices of cell j
/// (exact where they are read); raises error2 to their largest squared
/// displacement where it is larger.
double Displacement::cell_reach(const Cut& prev, const Cells& cells, std::size_t j, const Vec3& p,
                                bool first_level, double& error2) const {
  const Buffer<Vec3>& level0_pos = first_level ? prev.pos : input_pos_;
  auto displacement2 = [&](std::uint32_t i) {  // 0 for a vertex no longer represented
    const Vec3 d = level0_pos[i] - p;
    const double e2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    return level0_alive_[i] ? e2 : 0.0;
  };
  // The largest displacement of [i0, i1); four maxima side by side: one
  // would chain every vertex to the last.
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
  const std::uint32_t b = cells.begin[j], e = cells.begin[j + 1];
  if (first_level) return largest(b, e);  // one level-0 vertex per previous vertex
  double reach = 0;
  for (std::uint32_t k = b; k < e; ++k) {
    const Vec3& q = prev.pos[k];
    const double dx = double(q.x) - p.x, dy = double(q.y) - p.y, dz = double(q.z) - p.z;
    const double bound = (std::sqrt(dx * dx + dy * dy + dz * dz) + reach_[k]) * kMargin;
    reach = std::max(
        reach, bound * bound <= error2 ? bound : largest(level0_start_[k], level0_start_[k + 1]));
  }
  return reach;
}

float Displacement::measure(const Cut& prev, const Cells& cells,
                            std::span<const std::uint32_t> keep, std::size_t kept,
                            const Cut& next) {
  const bool first_level = level0_start_.empty();
  if (first_level) level0_alive_.assign(prev.size(), 1);
  const std::size_t n0 = level0_alive_.size();
  auto level0_begin = [&](std::uint32_t k) {  // k <= prev.size()
    return first_level ? k : level0_start_[k];
  };
  next_start_.resize(kept + 1);
  next_reach_.resize(kept);
  for (double& e : largest2_) e = 0;
  constexpr std::size_t kErrorChunk = 4096;
  const std::size_t n_cells = cells.count();
  const std::size_t grain = std::max<std::size_t>(1, n_cells * kErrorChunk / n0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_cells, grain), [&](const auto& r) {
    double& largest2 = largest2_.local();
    double error2 = largest2;
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const std::uint32_t n = keep[j];
      if (n == kNone) {
        const std::uint32_t i0 = level0_begin(cells.begin[j]);
        const std::uint32_t i1 = level0_begin(cells.begin[j + 1]);
        std::fill(level0_alive_.begin() + i0, level0_alive_.begin() + i1, 0);
        continue;
      }
      next_start_[n] = level0_begin(cells.begin[j]);
      next_reach_[n] = cell_reach(prev, cells, j, next.pos[n], first_level, error2);
    }
    largest2 = error2;
  });
  next_start_[kept] = static_cast<std::uint32_t>(n0);
  std::swap(level0_start_, next_start_);
  std::swap(reach_, next_reach_);
  return float(std::sqrt(largest2_.combine([](double a, double b) { return std::max(a, b); })));
}

/// The chain of levels of one call. Every buffer lives for the whole call
/// and is reused level after level (the two cuts swap): freeing and
/// reallocating them per level would fault their pages in again.
class Chain {
 public:
  Chain(const TriangleMesh& mesh, const VertexClusteringOptions& options);
  std::vector<SimplifyResult> run();

 private:
  /// The deepest depth above the cut whose cells leave at most (1 -
  /// min_diff) x the vertices (and fewer), or 0; its cell count in `cells`.
  int choose_depth(std::size_t& cells) const;
  void number_cells(int depth, std::size_t count);
  void map_triangles();
  /// The next level's faces (remap_faces, beside the rest) and vertices
  /// (representatives); returns how many vertices are used.
  std::size_t remap_and_pick();
  void emit(float error, StopReason reason, std::string detail);
  std::vector<SimplifyResult> finish(StopReason reason, const std::string& why);
  /// The stop before the first level, if the target asks for it.
  bool level0_meets_target(StopReason& reason, std::string& why) const;

  const TriangleMesh& mesh_;
  const VertexClusteringOptions& options_;
  float min_diff_;
  Weights weights_;
  bool count_target_;
  std::size_t target_tris_;
  Octree octree_;
  RemapScratch remap_scratch_;
  Buffer<Segment> line_candidates_;
  Buffer<Triangle> mapped_;  ///< a level's triangles, corners mapped to the next
  Cut cut_, next_;
  Cells cells_;
  Buffer<char> corner_, wanted_;
  CellFaces cell_faces_;
  RepresentativePicker picker_;
  Displacement displacement_;
  std::vector<SimplifyResult> chain_;
  /// Copying a finished level into its result (a few large arrays: 5-10 % of
  /// a call) only reads `cut_`, so the next level, which reads `cut_` and
  /// writes `next_`, does it in its remap task after the remap (the remap is
  /// the shorter of the level's two long tasks: the copy fills the gap);
  /// when the chain ends first, `finish` does it. The result awaiting it.
  SimplifyResult* pending_ = nullptr;
};

Chain::Chain(const TriangleMesh& mesh, const VertexClusteringOptions& options)
    : mesh_(mesh),
      options_(options),
      min_diff_(std::clamp(options.min_diff, 0.0f, 1.0f)),
      weights_{std::max(0.0, double(options.area_weight)),
               std::max(0.0, double(options.volume_weight)),
               std::max(0.0, double(options.mean_weight)),
               std::max(0.0, double(options.quadric_weight))},
      count_target_(options.target.triangles > 0 || options.target.ratio > 0),
      target_tris_(options.target.triangle_target(mesh.triangle_count())) {
  // Level 0 and at most one level per octree depth: reserved, so that a
  // result being filled never moves.
  chain_.reserve(kMaxDepth + 2);
}

void Chain::emit(float error, StopReason reason, std::string detail) {
  assert(chain_.size() < chain_.capacity());
  SimplifyResult& r = chain_.emplace_back();
  r.error = error;
  r.stop_reason = reason;
  r.stop_detail = std::move(detail);
  pending_ = &r;
}

std::vector<SimplifyResult> Chain::finish(StopReason reason, const std::string& why) {
  if (pending_) fill_result(mesh_, cut_, *pending_);
  chain_.back().stop_reason = reason;
  chain_.back().stop_detail += "; stopped: " + why;
  return std::move(chain_);
}

int Chain::choose_depth(std::size_t& cells) const {
  // Cells per depth: 1 + the neighbours in octree order that part above it.
  using Histogram = std::array<std::size_t, kMaxDepth + 1>;
  const std::size_t n_prev = cut_.size();
  const Histogram histogram = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(std::min<std::size_t>(1, n_prev), n_prev, kGrain),
      Histogram{},
      [&](const tbb::blocked_range<std::size_t>& r, Histogram h) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
          ++h[common_depth(cut_.code[i - 1], cut_.code[i])];
        return h;
      },
      [](Histogram a, const Histogram& b) {
        for (std::size_t c = 0; c < a.size(); ++c) a[c] += b[c];
        return a;
      });
  const auto limit = static_cast<std::size_t>(std::floor((1.0 - min_diff_) * double(n_prev)));
  std::array<std::size_t, kMaxDepth + 2> cells_at;
  cells_at[0] = 1;
  for (int c = 1; c <= kMaxDepth + 1; ++c) cells_at[c] = cells_at[c - 1] + histogram[c - 1];
  for (int c = cut_.depth - 1; c >= 1; --c) {
    if (cells_at[c] <= limit && cells_at[c] < n_prev) {
      cells = cells_at[c];
      return c;
    }
  }
  return 0;
}

void Chain::number_cells(int depth, std::size_t count) {
  // The cells at `depth`: runs of vertices in octree order, numbered by a
  // parallel scan. Each cell's quadric: the sum of its vertices' (a vertex's
  // is the sum of the plane quadrics of the input triangles around it).
  // Level 0 keeps none: the first level adds each distinct triangle's plane
  // quadric to the cells of its three corners directly (level 0 positions
  // are the input's), which writes a third of the memory; its quadrics
  // start at zero, each zeroed where its cell starts.
  const std::size_t n_prev = cut_.size();
  const bool zero_quadrics = weights_.quadric > 0 && cut_.quadric.empty();
  if (weights_.quadric > 0) next_.quadric.resize(count);
  cells_.depth = depth;
  cells_.of.resize(n_prev);
  cells_.begin.resize(count + 1);
  tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n_prev, kGrain), std::uint32_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t started, bool is_final) {
        std::uint32_t cell = started - 1;  // the cell before the range (wraps at 0)
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const bool starts = i == 0 || common_depth(cut_.code[i - 1], cut_.code[i]) < depth;
          if (!is_final) {
            cell += starts;
            continue;
          }
          if (starts) {
            cells_.begin[++cell] = static_cast<std::uint32_t>(i);
            if (zero_quadrics) next_.quadric[cell] = Quadric{};
          }
          cells_.of[i] = cell;
        }
        return cell + 1;
      },
      std::plus<>());
  cells_.begin[count] = static_cast<std::uint32_t>(n_prev);
}

void Chain::map_triangles() {
  // The triangles with their corners mapped to the new cells (read three
  // times: quadrics, face lists, remap).
  mapped_.resize(cut_.tris.size());
  for_chunks(cut_.tris.size(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t f = lo; f < hi; ++f) {
      const Triangle& t = cut_.tris[f];
      mapped_[f] = {cells_.of[t[0]], cells_.of[t[1]], cells_.of[t[2]]};
    }
  });
  // Which vertices are corners of a triangle (all of them unless the level
  // has lines: a vertex nothing uses is never kept).
  corner_.clear();
  if (!cut_.lines.empty()) {
    corner_.assign(cut_.size(), 0);
    for (const Triangle& t : cut_.tris) corner_[t[0]] = corner_[t[1]] = corner_[t[2]] = 1;
  }
}

std::size_t Chain::remap_and_pick() {
  const std::size_t cells = cells_.count();
  const bool quadrics_from_triangles = weights_.quadric > 0 && cut_.quadric.empty();
  // Only cells of several vertices choose a representative, and only those
  // with more than one contender read the triangles around them; listing
  // those for the others is wasted, but which cells have one contender is
  // only known after the quadric terms, and a second pass over the cells
  // costs more than it saves.
  wanted_.resize(cells);
  for (std::uint32_t j = 0; j < cells; ++j) wanted_[j] = cells_.begin[j + 1] - cells_.begin[j] > 1;
  const bool measure = !cut_.tris.empty() && (weights_.area > 0 || weights_.volume > 0);
  // The faces of the new level need only the mapped triangles, not the new
  // vertices: they are remapped in a task beside the quadrics, face lists
  // and choices. At the first level the quadrics and the lists are the
  // longer share: the lists' count is a task of its own, spawned first so
  // that a free thread takes it before the remap (a thief takes the oldest
  // task), and the quadrics, the lists' fill and the choices follow on this
  // thread. The task groups are declared after everything they touch, so
  // that on an exception they are waited for before those go.
  std::size_t kept_cells = 0;
  const bool count_aside = measure && quadrics_from_triangles;
  tbb::task_group counting, remapping;
  if (count_aside) counting.run([&] { cell_faces_.count(mapped_, wanted_); });
  remapping.run([&] {
    line_candidates_.clear();
    remap_faces(mapped_, cut_.tri_origin, cut_.lines, cells_.of, cells, options_.no_lines,
                line_candidates_, next_, remap_scratch_);
    kept_cells = number_used_vertices(cells, next_, remap_scratch_);
    if (pending_) fill_result(mesh_, cut_, *pending_);
  });
  if (count_aside) {
    add_plane_quadrics(cut_.pos, cut_.tris, mapped_, next_.quadric);
    counting.wait();
    cell_faces_.fill(mapped_, wanted_);
  } else {
    tbb::parallel_invoke(
        [&] {
          if (quadrics_from_triangles)
            add_plane_quadrics(cut_.pos, cut_.tris, mapped_, next_.quadric);
        },
        [&] {
          if (measure) cell_faces_.build(mapped_, wanted_);
        });
  }
  picker_.pick(cut_, cells_, measure ? &cell_faces_ : nullptr, weights_, corner_, octree_, next_);
  remapping.wait();
  pending_ = nullptr;
  compact_vertices(cells, kept_cells, next_, remap_scratch_);
  return kept_cells;
}

bool Chain::level0_meets_target(StopReason& reason, std::string& why) const {
  if (!count_target_ || cut_.tris.size() > target_tris_) return false;
  if (target_tris_ >= mesh_.triangle_count()) {
    reason = StopReason::kNoReduction;
    why = "the target asks for no reduction";
  } else {
    reason = StopReason::kTargetReached;
    why = fmt::format("{} triangles <= target {}", cut_.tris.size(), target_tris_);
  }
  return true;
}

std::vector<SimplifyResult> Chain::run() {
  octree_ = build_level0(mesh_, options_.no_lines, cut_, remap_scratch_);
  emit(0, StopReason::kNoReduction,
       fmt::format("level 0: the input with equal positions merged, {} "
                   "vertices, {} triangles, {} lines",
                   cut_.size(), cut_.tris.size(), cut_.lines.size()));
  StopReason reason{};
  if (std::string why; level0_meets_target(reason, why)) return finish(reason, why);
  while (true) {
    const std::size_t n_prev = cut_.size();
    std::size_t cells = 0;
    const int depth = choose_depth(cells);
    if (depth == 0) {
      if (cut_.depth <= 1) return finish(StopReason::kCannotSimplify, "octree depth 1 reached");
      return finish(StopReason::kCannotSimplify,
                    fmt::format("no octree depth >= 1 leaves at most {} % of the {} vertices",
                                100 - 100 * min_diff_, n_prev));
    }
    number_cells(depth, cells);
    next_.depth = depth;
    next_.pos.resize(cells);
    next_.weight.resize(cells);
    next_.orig.resize(cells);
    next_.code.resize(cells);
    map_triangles();
    const std::size_t kept = remap_and_pick();
    if (next_.tris.empty() && next_.lines.empty())
      return finish(StopReason::kCannotSimplify,
                    fmt::format("the level at octree depth {} would be empty", depth));
    const bool first_level = chain_.size() == 1;  // level 0 is all there is
    const float error = displacement_.measure(cut_, cells_, remap_scratch_.keep, kept, next_);
    if (error > options_.target.max_error)
      return finish(
          StopReason::kErrorBudgetReached,
          fmt::format("the level at octree depth {} would move a vertex by {:.4g} > {:.4g}", depth,
                      error, options_.target.max_error));
    const auto cell_size = static_cast<float>(octree_.cell_side(depth));
    std::string detail = fmt::format(
        "octree depth {} (cell side {:.4g}, diagonal {:.4g}): {} -> {} vertices (-{:.1f} %), "
        "{} triangles, {} lines; largest vertex displacement {:.4g}",
        depth, cell_size, std::sqrt(3.0) * cell_size, n_prev, next_.size(),
        100.0 * (1.0 - double(next_.size()) / double(n_prev)), next_.tris.size(),
        next_.lines.size(), error);
    std::swap(cut_, next_);
    if (first_level) displacement_.keep_level0(std::move(next_.pos));  // level 0's
    emit(error, StopReason::kTargetReached, std::move(detail));
    if (count_target_ && cut_.tris.size() <= target_tris_)
      return finish(StopReason::kTargetReached,
                    fmt::format("{} triangles <= target {}", cut_.tris.size(), target_tris_));
    if (cut_.size() <= 1) return finish(StopReason::kCannotSimplify, "one vertex left");
  }
}

}  // namespace

std::vector<SimplifyResult> vertex_clustering(const TriangleMesh& mesh,
                                              const VertexClusteringOptions& options) {
  return Chain(mesh, options).run();
}

}  // namespace lodforge
