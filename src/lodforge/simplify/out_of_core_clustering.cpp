// Out-of-core vertex clustering.
//
// Implements P. Lindstrom, "Out-of-Core Simplification of Large Polygonal
// Models" (SIGGRAPH 2000): a uniform grid, one pass over a triangle soup
// that sums per occupied cell the quadrics (Garland & Heckbert, "Surface
// Simplification Using Quadric Error Metrics", SIGGRAPH 1997) of the
// triangles touching it and keeps the triangles that span three cells, then
// one representative per cell at the minimum of its quadric. Only the
// occupied cells and the kept triangles are held: memory follows the output.
//
// Where it departs from the paper:
// * The paper's singular quadrics are solved with a truncated
//   pseudo-inverse about the cell's centre; here the same effect comes from
//   the regularised solve of core/quadric.h about the mean of the corners
//   that fell in the cell (the rule of simplify/vertex_clustering), and the
//   point is clamped into its cell so that the error bound holds.
// * The paper takes a grid resolution; here it is found from a triangle
//   count by an area estimate and a few corrective passes (header).
#include "lodforge/simplify/out_of_core_clustering.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "lodforge/core/math.h"
#include "lodforge/core/morton.h"
#include "lodforge/core/quadric.h"

namespace lodforge {
namespace {

constexpr std::uint32_t kMaxGrid = std::uint32_t{1} << 21;  // Morton codes: 21 bits an axis
constexpr int kMaxPasses = 6;
constexpr double kLowEnough = 0.7;  // a result of at least 0.7 T ends the search

/// What the survey pass finds: the box of the corners, the area, the count.
struct Survey {
  Box3 box;
  double area = 0;
  std::uint64_t triangles = 0;
};

Vec3 cross_d(const StreamedTriangle& t, std::array<double, 3>& n) {
  const Vec3 &p = t.corner[0], &q = t.corner[1], &r = t.corner[2];
  const double ux = double(q.x) - p.x, uy = double(q.y) - p.y, uz = double(q.z) - p.z;
  const double vx = double(r.x) - p.x, vy = double(r.y) - p.y, vz = double(r.z) - p.z;
  n = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  return p;
}

Survey survey(const TriangleStream& input) {
  Survey s;
  s.triangles =
      input.for_each_triangle([&](std::span<const StreamedTriangle> chunk, std::uint64_t) {
        for (const StreamedTriangle& t : chunk) {
          for (const Vec3& c : t.corner) s.box.add(c);
          std::array<double, 3> n;
          cross_d(t, n);
          s.area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        }
      });
  return s;
}

/// A uniform grid of cubic cells of side h from `lo`; a cell is named by the
/// Morton code of its integer coordinates (so sorting names sorts cells in
/// Z-order).
struct Grid {
  std::array<double, 3> lo{};
  double h = 1;
  std::array<std::uint32_t, 3> n{1, 1, 1};

  Grid(const Box3& box, double side) : h(side) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = box.lo[a];
      const double cells = std::ceil((double(box.hi[a]) - box.lo[a]) / h);
      n[a] = static_cast<std::uint32_t>(std::clamp(cells, 1.0, double(kMaxGrid)));
    }
  }
  std::uint32_t coordinate(float x, int a) const {
    const double c = std::floor((double(x) - lo[a]) / h);
    return static_cast<std::uint32_t>(std::clamp(c, 0.0, double(n[a] - 1)));
  }
  std::uint64_t cell_of(const Vec3& p) const {
    return morton_code(coordinate(p.x, 0), coordinate(p.y, 1), coordinate(p.z, 2));
  }
  /// The integer coordinate of axis a of a cell (bits a, a + 3, ... of its name).
  static std::uint32_t axis(std::uint64_t key, int a) {
    std::uint32_t c = 0;
    for (int b = 0; b < 21; ++b) c |= static_cast<std::uint32_t>((key >> (3 * b + a)) & 1) << b;
    return c;
  }
};

/// The longest side of `box`, in double (a float difference of extreme
/// coordinates overflows).
double longest_side(const Box3& box) {
  double longest = 0;
  for (int a = 0; a < 3; ++a) longest = std::max(longest, double(box.hi[a]) - box.lo[a]);
  return longest;
}

/// The side h of the finest grid over `box` (2^21 cells along its longest side).
double finest_side(const Box3& box) {
  const double longest = longest_side(box);
  return longest > 0 ? longest / kMaxGrid : 1.0;
}

/// What a pass sums for one cell. Quadrics are in coordinates relative to
/// the grid's corner `lo`, which keeps their constant terms small.
struct Cell {
  Quadric q;
  std::array<double, 3> sum;  ///< of the corners that fell in the cell (relative)
  std::uint64_t corners;
  std::uint64_t key;
  std::uint64_t min_vertex;
  Box3 box;  ///< of those corners (absolute)
};

/// A kept triangle: three distinct cells, the smallest first (orientation
/// kept), and the first input triangle that gave it.
struct Triple {
  std::array<std::uint32_t, 3> c;
  std::uint64_t face;
};

std::array<std::uint32_t, 3> rotate_smallest_first(std::array<std::uint32_t, 3> c) {
  if (c[1] < c[0] && c[1] < c[2]) return {c[1], c[2], c[0]};
  if (c[2] < c[0] && c[2] < c[1]) return {c[2], c[0], c[1]};
  return c;
}

std::uint64_t mix(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return h;
}

/// Open addressing from a 64-bit hash to an index into the caller's array;
/// the caller says whether the entry at an index is the one sought.
class IndexTable {
 public:
  IndexTable() { slots_.assign(1024, kNone); }
  /// The index stored for the entry equal to the sought one (`equal(i)`),
  /// or the result of `make()` stored for it.
  template <class Equal, class Make, class HashOf>
  std::uint32_t find_or_insert(std::uint64_t hash, const Equal& equal, const Make& make,
                               const HashOf& hash_of) {
    std::size_t mask = slots_.size() - 1;
    for (std::size_t i = mix(hash) & mask;; i = (i + 1) & mask) {
      if (slots_[i] == kNone) {
        const std::uint32_t index = make();
        slots_[i] = index;
        if (2 * ++size_ > slots_.size()) grow(hash_of);
        return index;
      }
      if (equal(slots_[i])) return slots_[i];
    }
  }
  std::size_t size() const { return size_; }

 private:
  template <class HashOf>
  void grow(const HashOf& hash_of) {
    std::vector<std::uint32_t> old(2 * slots_.size(), kNone);
    old.swap(slots_);
    const std::size_t mask = slots_.size() - 1;
    for (std::uint32_t index : old) {
      if (index == kNone) continue;
      std::size_t i = mix(hash_of(index)) & mask;
      while (slots_[i] != kNone) i = (i + 1) & mask;
      slots_[i] = index;
    }
  }
  std::vector<std::uint32_t> slots_;
  std::size_t size_ = 0;
};

std::uint64_t triple_hash(const std::array<std::uint32_t, 3>& c) {
  return (std::uint64_t{c[0]} << 32 | c[1]) ^ mix(c[2] + 0x9e3779b97f4a7c15ull);
}

/// One clustering pass: the cells and kept triples of a grid.
struct Pass {
  std::vector<Cell> cells;
  std::vector<Triple> triples;
  bool complete = true;  ///< false: stopped at the triple cap
};

/// A triangle prepared for the sequential sums: its cells and its quadric.
struct Prepared {
  std::array<std::uint64_t, 3> key;
  Quadric q;
};

/// Clusters every triangle of `input` on `grid`; stops early (complete =
/// false) when more than `cap` triples are kept. Each chunk's triangles are
/// prepared in parallel and summed in stream order, so the sums do not
/// depend on the thread count or the chunk size.
Pass cluster_pass(const TriangleStream& input, const Grid& grid, std::size_t cap) {
  Pass pass;
  IndexTable cell_table, triple_table;
  std::vector<Prepared> prepared;
  auto cell_hash = [&](std::uint32_t i) { return pass.cells[i].key; };
  auto triple_hash_of = [&](std::uint32_t i) { return triple_hash(pass.triples[i].c); };
  struct Stop {};
  try {
    input.for_each_triangle([&](std::span<const StreamedTriangle> chunk, std::uint64_t first) {
      prepared.resize(chunk.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunk.size(), 1024), [&](const auto& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const StreamedTriangle& t = chunk[i];
          Prepared& p = prepared[i];
          for (int c = 0; c < 3; ++c) p.key[c] = grid.cell_of(t.corner[c]);
          // Area-weighted plane: with n unnormalised, weight 1 / (2 |n|)
          // gives area x the squared distance.
          std::array<double, 3> n;
          const Vec3 a = cross_d(t, n);
          const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
          if (!(len > 0)) {
            p.q = Quadric{};
            continue;
          }
          const double ax = a.x - grid.lo[0], ay = a.y - grid.lo[1], az = a.z - grid.lo[2];
          p.q = Quadric::plane(n[0], n[1], n[2], -(n[0] * ax + n[1] * ay + n[2] * az), 0.5 / len);
        }
      });
      for (std::size_t i = 0; i < chunk.size(); ++i) {
        const StreamedTriangle& t = chunk[i];
        const Prepared& p = prepared[i];
        std::array<std::uint32_t, 3> c;
        for (int k = 0; k < 3; ++k) {
          const std::uint64_t key = p.key[k];
          c[k] = cell_table.find_or_insert(
              key, [&](std::uint32_t j) { return pass.cells[j].key == key; },
              [&] {
                Cell& cell = pass.cells.emplace_back();
                cell.q = Quadric{};
                cell.sum = {0, 0, 0};
                cell.corners = 0;
                cell.key = key;
                cell.min_vertex = t.vertex[k];
                return static_cast<std::uint32_t>(pass.cells.size() - 1);
              },
              cell_hash);
          Cell& cell = pass.cells[c[k]];
          cell.q += p.q;
          const Vec3& v = t.corner[k];
          cell.sum[0] += v.x - grid.lo[0];
          cell.sum[1] += v.y - grid.lo[1];
          cell.sum[2] += v.z - grid.lo[2];
          ++cell.corners;
          cell.min_vertex = std::min(cell.min_vertex, t.vertex[k]);
          cell.box.add(v);
        }
        if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;
        const std::array<std::uint32_t, 3> tri = rotate_smallest_first(c);
        triple_table.find_or_insert(
            triple_hash(tri), [&](std::uint32_t j) { return pass.triples[j].c == tri; },
            [&] {
              pass.triples.push_back({tri, first + i});
              return static_cast<std::uint32_t>(pass.triples.size() - 1);
            },
            triple_hash_of);
        if (pass.triples.size() > cap) throw Stop{};
      }
    });
  } catch (const Stop&) {
    pass.complete = false;
  }
  return pass;
}

/// The mesh of a complete pass: one vertex per cell used by a triple, at its
/// clamped quadric minimum, and the error bound of the header.
SimplifyResult build_result(const Grid& grid, Pass& pass) {
  SimplifyResult r;
  std::vector<std::uint32_t> used;
  {
    std::vector<char> is_used(pass.cells.size(), 0);
    for (const Triple& t : pass.triples)
      for (std::uint32_t c : t.c) is_used[c] = 1;
    for (std::uint32_t c = 0; c < pass.cells.size(); ++c)
      if (is_used[c]) used.push_back(c);
  }
  std::sort(used.begin(), used.end(), [&](std::uint32_t a, std::uint32_t b) {
    return pass.cells[a].key < pass.cells[b].key;
  });
  std::vector<std::uint32_t> vertex_of(pass.cells.size(), kNone);
  r.mesh.positions.resize(used.size());
  r.vertex_map.resize(used.size());
  double error2 = 0;
  for (std::uint32_t v = 0; v < used.size(); ++v) {
    const Cell& cell = pass.cells[used[v]];
    vertex_of[used[v]] = v;
    const double corners = double(cell.corners);
    const std::array<double, 3> mean{cell.sum[0] / corners, cell.sum[1] / corners,
                                     cell.sum[2] / corners};
    std::array<double, 3> x = quadric_minimum(cell.q, mean);
    Vec3 p;
    double far2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double c0 = Grid::axis(cell.key, a) * grid.h;
      x[a] = std::clamp(x[a], c0, c0 + grid.h);
      p[a] = static_cast<float>(x[a] + grid.lo[a]);
      const double far = std::max(std::abs(double(p[a]) - cell.box.lo[a]),
                                  std::abs(double(p[a]) - cell.box.hi[a]));
      far2 += far * far;
    }
    error2 = std::max(error2, far2);
    r.mesh.positions[v] = p;
    r.vertex_map[v] = static_cast<std::uint32_t>(std::min<std::uint64_t>(cell.min_vertex, kNone));
  }
  r.error = static_cast<float>(std::sqrt(error2));
  std::vector<Triple> tris(pass.triples.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const Triple& t = pass.triples[f];
    tris[f] = {rotate_smallest_first({vertex_of[t.c[0]], vertex_of[t.c[1]], vertex_of[t.c[2]]}),
               t.face};
  }
  std::sort(tris.begin(), tris.end(), [](const Triple& a, const Triple& b) { return a.c < b.c; });
  r.mesh.triangles.resize(tris.size());
  r.face_map.resize(tris.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    r.mesh.triangles[f] = tris[f].c;
    r.face_map[f] = static_cast<std::uint32_t>(std::min<std::uint64_t>(tris[f].face, kNone));
  }
  return r;
}

std::string grid_text(const Grid& g) {
  return fmt::format("grid {} x {} x {} (cell side {:.4g}, diagonal {:.4g})", g.n[0], g.n[1],
                     g.n[2], g.h, std::sqrt(3.0) * g.h);
}

/// The grid search of the header's table for a triangle count `target`;
/// `passes` counts the clustering passes.
SimplifyResult search_count(const TriangleStream& input, const Survey& s, std::size_t target,
                            double h_error, int& passes) {
  const double h_fine = finest_side(s.box);
  const double h_coarse = std::max(longest_side(s.box), h_fine);
  auto clamp_side = [&](double h) {
    return std::clamp(h, h_fine, std::max(h_fine, std::min(h_coarse, h_error)));
  };
  double h = clamp_side(target > 0 ? std::sqrt(3 * s.area / double(target)) : h_coarse);
  const std::size_t cap = 4 * target + 65536;
  std::size_t pass_cap = cap;
  // Sides known to give more than `target` (below) and at most (above).
  double too_fine = 0, fine_enough = std::numeric_limits<double>::infinity();
  std::optional<SimplifyResult> best, smallest_over;
  std::optional<Grid> best_grid, over_grid;
  while (passes < kMaxPasses) {
    const Grid grid(s.box, h);
    Pass pass = cluster_pass(input, grid, pass_cap);
    ++passes;
    const std::size_t out = pass.triples.size();
    double next = h;
    if (!pass.complete && clamp_side(2 * h) == h) {
      pass_cap = std::numeric_limits<std::size_t>::max();  // the error budget allows no coarser
      continue;
    }
    if (!pass.complete) {
      too_fine = std::max(too_fine, h);
      next = 2 * h;
    } else if (out > target) {
      too_fine = std::max(too_fine, h);
      if (!smallest_over || out < smallest_over->mesh.triangle_count())
        smallest_over = build_result(grid, pass), over_grid = grid;
      next = h * std::sqrt(double(out) / double(std::max<std::size_t>(target, 1))) * 1.02;
    } else {
      fine_enough = std::min(fine_enough, h);
      if (!best || out > best->mesh.triangle_count())
        best = build_result(grid, pass), best_grid = grid;
      if (double(out) >= kLowEnough * double(target)) break;
      next = h * std::sqrt(std::max<double>(double(out), 1) / double(target));
    }
    // Stay strictly between the sides known to be too fine and fine enough.
    if (!(next > too_fine && next < fine_enough))
      next =
          std::isfinite(fine_enough) ? std::sqrt(std::max(too_fine, h_fine) * fine_enough) : 2 * h;
    next = clamp_side(next);
    if (next == h || next <= too_fine || next >= fine_enough) break;
    h = next;
  }
  SimplifyResult r;
  if (best) {
    r = std::move(*best);
    r.stop_reason = StopReason::kTargetReached;
    r.stop_detail =
        fmt::format("{}: {} triangles <= target {} ({} clustering pass{})", grid_text(*best_grid),
                    r.mesh.triangle_count(), target, passes, passes == 1 ? "" : "es");
  } else if (smallest_over) {
    r = std::move(*smallest_over);
    const bool budget = over_grid->h >= h_error * (1 - 1e-9);
    r.stop_reason = budget ? StopReason::kErrorBudgetReached : StopReason::kCannotSimplify;
    r.stop_detail = fmt::format("{}: {} triangles > target {} (after {} clustering passes{})",
                                grid_text(*over_grid), r.mesh.triangle_count(), target, passes,
                                budget ? "; coarser cells would exceed the error budget" : "");
  } else {
    r.stop_reason = StopReason::kCannotSimplify;
    r.stop_detail = fmt::format("no clustering pass finished within {} triangles", cap);
  }
  return r;
}

}  // namespace

OutOfCoreClusteringResult out_of_core_clustering(const TriangleStream& input,
                                                 const OutOfCoreClusteringOptions& options) {
  const Survey s = survey(input);
  OutOfCoreClusteringResult r;
  r.input_triangles = s.triangles;
  if (s.triangles == 0) {
    r.passes = 1;
    r.stop_reason = StopReason::kCannotSimplify;
    r.stop_detail = "the input has no triangles";
    return r;
  }
  const SimplifyTarget& target = options.target;
  const bool by_count = target.triangles > 0 || target.ratio > 0;
  const double h_error = std::isfinite(target.max_error)
                             ? std::max(double(target.max_error), 0.0) / std::sqrt(3.0) * (1 - 1e-6)
                             : std::numeric_limits<double>::infinity();
  const double longest = longest_side(s.box);
  if (options.grid == 0 && by_count) {
    int passes = 0;
    static_cast<SimplifyResult&>(r) = search_count(
        input, s, target.triangle_target(static_cast<std::size_t>(s.triangles)), h_error, passes);
    r.passes = 1 + passes;
    return r;
  }
  // One pass: the grid given, the error budget's, or the finest.
  double h = finest_side(s.box);
  if (options.grid > 0 && longest > 0)
    h = std::max(h, longest / std::min(options.grid, kMaxGrid));
  else if (std::isfinite(h_error))
    h = std::max(h, h_error);
  const Grid grid(s.box, h);
  Pass pass = cluster_pass(input, grid, std::numeric_limits<std::size_t>::max());
  static_cast<SimplifyResult&>(r) = build_result(grid, pass);
  r.passes = 2;
  r.stop_reason = options.grid > 0         ? StopReason::kTargetReached
                  : std::isfinite(h_error) ? StopReason::kErrorBudgetReached
                                           : StopReason::kNoReduction;
  r.stop_detail =
      fmt::format("{}: {} triangles (1 clustering pass)", grid_text(grid), r.mesh.triangle_count());
  return r;
}

}  // namespace lodforge
