#include "lodforge/simplify/detail/clustering_level0.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <utility>

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_scan.h>

#include "lodforge/core/error.h"
#include "lodforge/core/morton.h"
#include "lodforge/simplify/detail/clustering_sort.h"

namespace lodforge::detail::clustering {
namespace {

/// Items per task of level 0's passes over the input (a pass's item costs
/// nanoseconds: below this a task costs more than it saves).
constexpr std::size_t kGrain = 16384;

/// Marks the vertices a triangle or line uses (1 in `used`); throws
/// DataError naming the first face with an index out of range. On the
/// calling thread: a shared byte array written by several threads shares
/// its cache lines between them.
void mark_used(const TriangleMesh& mesh, Buffer<std::uint8_t>& used) {
  const std::size_t n = mesh.vertex_count();
  auto out_of_range = [&](const char* what, std::size_t i, std::uint32_t v) {
    return DataError(
        fmt::format("vertex clustering: {} {} uses vertex {} of only {}", what, i, v, n));
  };
  used.assign(n, 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const std::uint32_t largest = std::max({t[0], t[1], t[2]});
    if (largest >= n) throw out_of_range("triangle", f, largest);
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
    const Segment& s = mesh.lines[l];
    if (std::max(s[0], s[1]) >= n) throw out_of_range("line", l, std::max(s[0], s[1]));
    used[s[0]] = used[s[1]] = 1;
  }
}

/// The box around the used vertices, or DataError naming the first used
/// vertex with a non-finite coordinate.
Box3 used_bounds(const TriangleMesh& mesh, const Buffer<std::uint8_t>& used) {
  struct Bounds {
    Box3 box;
    std::size_t non_finite = SIZE_MAX;  ///< the first used vertex with one
  };
  const Bounds bounds = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.vertex_count(), kGrain), Bounds{},
      [&](const tbb::blocked_range<std::size_t>& r, Bounds part) {
        float lo[3] = {part.box.lo.x, part.box.lo.y, part.box.lo.z};
        float hi[3] = {part.box.hi.x, part.box.hi.y, part.box.hi.z};
        // Without branches on the data: an unused vertex takes the part of a
        // coordinate already in the box; finiteness is summed (x - x is 0 for
        // a finite x, NaN otherwise) and the first offender looked for only
        // then.
        float not_finite = 0;
        for (std::size_t v = r.begin(); v < r.end(); ++v) {
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
          for (std::size_t v = r.begin(); v < r.end(); ++v) {
            if (used[v] && !is_finite(mesh.positions[v])) {
              part.non_finite = std::min(part.non_finite, v);
              break;
            }
          }
        }
        part.box.lo = {lo[0], lo[1], lo[2]};
        part.box.hi = {hi[0], hi[1], hi[2]};
        return part;
      },
      [](Bounds a, const Bounds& b) {
        a.box.add(b.box);
        a.non_finite = std::min(a.non_finite, b.non_finite);
        return a;
      });
  if (bounds.non_finite != SIZE_MAX)
    throw DataError(
        fmt::format("vertex clustering: vertex {} has a non-finite coordinate", bounds.non_finite));
  return bounds.box;
}

/// Checks the input and returns the box around the used vertices (1 in
/// `used`). Each error names the first offender.
Box3 validate(const TriangleMesh& mesh, Buffer<std::uint8_t>& used) {
  mark_used(mesh, used);
  const Box3 box = used_bounds(mesh, used);
  const std::size_t n = mesh.vertex_count();
  auto check_size = [&](std::size_t size, std::size_t want, const char* what) {
    if (size != 0 && size != want)
      throw DataError(fmt::format("vertex clustering: {} {} for {}", size, what, want));
  };
  check_size(mesh.normals.size(), n, "normals");
  check_size(mesh.texcoords.size(), n, "texcoords");
  check_size(mesh.colors.size(), n, "colors");
  check_size(mesh.materials.size(), mesh.triangles.size(), "materials");
  return box;
}

Octree octree_around(const Box3& box) {
  Octree octree;
  octree.lo = box.empty() ? Vec3{} : box.lo;
  const Vec3 size = box.size();
  octree.side = std::max({double(size.x), double(size.y), double(size.z)});
  if (!(octree.side > 0)) octree.side = 1;
  return octree;
}

/// Each vertex's Morton code in `code` and its sort key (see
/// sort_octree_order) in `keys`: an unused vertex gets kUnused (above every
/// 63-bit code), sorts last and is cut off. The order of equal codes is
/// settled by the sort, so the keys' order does not matter.
void morton_codes(const TriangleMesh& mesh, const Buffer<std::uint8_t>& used, const Octree& octree,
                  Buffer<std::uint64_t>& code, Buffer<std::uint64_t>& keys) {
  const std::size_t nv = mesh.vertex_count();
  const double scale = double(1u << kMaxDepth) / octree.side;
  const std::uint32_t max_q = (1u << kMaxDepth) - 1;
  code.resize(nv);
  keys.resize(nv);
  for_chunks(nv, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t v = lo; v < hi; ++v) {
      if (!used[v]) {  // its coordinates may be anything
        code[v] = kUnused;
        keys[v] = kUnused << 32 | v;
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
      keys[v] = (c >> 31) << 32 | v;
    }
  });
}

/// The level-0 vertices: one per run of equal coordinates of the sorted
/// vertices (`order`, used ones only); `node_of[v]` is input vertex v's.
/// Equal positions have equal codes: positions are compared only then. A
/// parallel scan (TBB): each range counts, then writes, its new vertices
/// from its place on; each vertex's code and position are gathered once.
void merge_equal_positions(const TriangleMesh& mesh, const Buffer<std::uint64_t>& order,
                           const Buffer<std::uint64_t>& code, Cut& cut,
                           Buffer<std::uint32_t>& node_of) {
  const std::size_t n = order.size();
  cut.pos.resize(n);
  cut.orig.resize(n);
  cut.code.resize(n);
  auto vertex = [&](std::size_t i) { return static_cast<std::uint32_t>(order[i]); };
  // Vertices [begin, end), the first new one numbered `out`; returns the
  // number after the last.
  auto merge = [&](std::size_t begin, std::size_t end, std::size_t out, bool write) {
    std::uint64_t last_code = 0;
    Vec3 last_pos;
    if (begin > 0) {
      last_code = code[vertex(begin - 1)];
      last_pos = mesh.positions[vertex(begin - 1)];
    }
    // The gathers' addresses are known ahead (octree order scatters them
    // over memory): fetched kAhead vertices early. Invariant: a prefetch
    // only reads ahead, within [begin, end).
    constexpr std::size_t kAhead = 16;
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kAhead < end) {
        const std::uint32_t ahead = vertex(i + kAhead);
        __builtin_prefetch(&code[ahead]);
        __builtin_prefetch(&mesh.positions[ahead]);
        if (write) __builtin_prefetch(&node_of[ahead], 1);
      }
      const std::uint32_t v = vertex(i);
      const std::uint64_t c = code[v];
      const Vec3& p = mesh.positions[v];
      if (i == 0 || c != last_code || p != last_pos) {
        if (write) {
          cut.pos[out] = p;
          cut.orig[out] = v;
          cut.code[out] = c;
        }
        ++out;
        last_code = c;
        last_pos = p;
      }
      if (write) node_of[v] = static_cast<std::uint32_t>(out - 1);
    }
    return out;
  };
  const std::size_t count = tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n, kGrain), std::size_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t out, bool is_final) {
        return merge(r.begin(), r.end(), out, is_final);
      },
      std::plus<>());
  cut.pos.resize(count);
  cut.orig.resize(count);
  cut.code.resize(count);
  cut.weight.assign(count, 1);
}

bool distinct(const Triangle& t) {
  return t[0] != t[1] && t[1] != t[2] && t[2] != t[0];
}

/// The input's triangles in level-0 vertices, sorted (stably) by smallest
/// corner into `cut.tris` (and their input triangles into
/// `cut.tri_origin`), doublets dropped; those that collapse (two or three
/// equal corners) are left out, and those that collapse to a line are
/// appended to `line_candidates` in input order unless `no_lines`.
///
/// A counting sort by smallest corner, by groups of vertices so that it runs
/// in parallel, each task writing memory of its own (map_and_count,
/// list_by_group, sort_group, join_groups below).
class TriangleSort {
 public:
  TriangleSort(const TriangleMesh& mesh, const Buffer<std::uint32_t>& node_of, Cut& cut)
      : mesh_(mesh),
        node_of_(node_of),
        cut_(cut),
        nf_(mesh.triangles.size()),
        groups_(std::max<std::size_t>(1, (cut.size() + (std::size_t(1) << kShift) - 1) >> kShift)),
        blocks_(std::max<std::size_t>(1, (nf_ + kGrain - 1) / kGrain)) {}

  /// Sorts; returns how many triangles collapsed.
  std::size_t run(bool no_lines, Buffer<Segment>& line_candidates) {
    const std::size_t collapsed = map_and_count(no_lines, line_candidates);
    list_by_group();
    cut_.tris.resize(list_.size());
    cut_.tri_origin.resize(list_.size());
    kept_.resize(groups_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups_, 1), [&](const auto& r) {
      RemapScratch scratch;
      Buffer<std::uint32_t> slot;
      for (std::size_t g = r.begin(); g < r.end(); ++g) sort_group(g, scratch, slot);
    });
    join_groups();
    return collapsed;
  }

 private:
  /// A group: the 2^kShift (>= kGrain) vertices from g << kShift on.
  static constexpr int kShift = std::bit_width(kGrain - 1);

  std::pair<std::size_t, std::size_t> block_range(std::size_t b) const {
    return {b * kGrain, std::min(nf_, (b + 1) * kGrain)};
  }

  /// Blocks of kGrain triangles map their corners to level-0 vertices and
  /// count their distinct triangles per group (into at_); the collapsed
  /// ones give the line candidates. Returns how many collapsed.
  std::size_t map_and_count(bool no_lines, Buffer<Segment>& line_candidates) {
    mapped_.resize(nf_);
    at_.resize(blocks_ * groups_);
    Buffer<Buffer<Segment>> block_lines(blocks_);
    Buffer<std::size_t> collapsed(blocks_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks_, 1), [&](const auto& r) {
      for (std::size_t b = r.begin(); b < r.end(); ++b) {
        std::uint32_t* counter = &at_[b * groups_];
        std::fill_n(counter, groups_, 0);
        std::size_t lost = 0;
        const auto [f0, f1] = block_range(b);
        for (std::size_t f = f0; f < f1; ++f) {
          const Triangle& input = mesh_.triangles[f];
          const Triangle t{node_of_[input[0]], node_of_[input[1]], node_of_[input[2]]};
          mapped_[f] = t;
          if (distinct(t)) {
            ++counter[std::min({t[0], t[1], t[2]}) >> kShift];
            continue;
          }
          ++lost;
          if (!no_lines && (t[0] != t[1] || t[1] != t[2])) {
            const std::uint32_t other = t[0] != t[1] ? t[1] : t[2];
            block_lines[b].push_back({std::min(t[0], other), std::max(t[0], other)});
          }
        }
        collapsed[b] = lost;
      }
    });
    for (const Buffer<Segment>& l : block_lines)
      line_candidates.insert(line_candidates.end(), l.begin(), l.end());
    std::size_t lost = 0;
    for (std::size_t c : collapsed) lost += c;
    return lost;
  }

  /// Each block lists its distinct triangles (smallest corner << 32 |
  /// index) in its slots of its groups' parts of list_: a group's part
  /// starts where the groups before it end, and in it the blocks come in
  /// order (stable), so the list's order is the final one.
  void list_by_group() {
    group_start_.resize(groups_ + 1);
    std::uint32_t total = 0;
    for (std::size_t g = 0; g < groups_; ++g) {
      group_start_[g] = total;
      for (std::size_t b = 0; b < blocks_; ++b) total += std::exchange(at_[b * groups_ + g], total);
    }
    group_start_[groups_] = total;
    list_.resize(total);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks_, 1), [&](const auto& r) {
      for (std::size_t b = r.begin(); b < r.end(); ++b) {
        std::uint32_t* next = &at_[b * groups_];
        const auto [f0, f1] = block_range(b);
        for (std::size_t f = f0; f < f1; ++f) {
          const Triangle& t = mapped_[f];
          if (!distinct(t)) continue;
          const std::uint32_t lo = std::min({t[0], t[1], t[2]});
          list_[next[lo >> kShift]++] = std::uint64_t(lo) << 32 | f;
        }
      }
    });
  }

  /// Group g counts its list per vertex, scatters its triangles to their
  /// places and squeezes the doublets out of each vertex's run; its
  /// triangles left are at the front of its part (kept_[g] of them).
  void sort_group(std::size_t g, RemapScratch& scratch, Buffer<std::uint32_t>& slot) {
    const std::size_t v0 = g << kShift, v1 = std::min(cut_.size(), (g + 1) << kShift);
    const std::uint32_t begin = group_start_[g], end = group_start_[g + 1];
    // Counts into slot[v - v0 + 1], then each vertex's first slot.
    slot.assign(v1 - v0 + 1, 0);
    for (std::uint32_t k = begin; k < end; ++k) ++slot[(list_[k] >> 32) - v0 + 1];
    slot[0] = begin;
    for (std::size_t v = v0; v < v1; ++v) slot[v - v0 + 1] += slot[v - v0];
    for (std::uint32_t k = begin; k < end; ++k) {
      const auto f = static_cast<std::uint32_t>(list_[k]);
      const std::uint32_t s = slot[(list_[k] >> 32) - v0]++;
      cut_.tris[s] = mapped_[f];
      cut_.tri_origin[s] = f;
    }
    // slot[v - v0] now ends v's run.
    std::size_t run = begin, out = begin;
    for (std::size_t v = v0; v < v1; ++v) {
      const std::size_t run_end = slot[v - v0];
      const std::size_t n = run_end - run;
      // Until the first doublet, every run is already in place.
      if (out != run) {
        for (std::size_t i = 0; i < n; ++i) {  // a few: no memmove call
          cut_.tris[out + i] = cut_.tris[run + i];
          cut_.tri_origin[out + i] = cut_.tri_origin[run + i];
        }
      }
      if (n == 1) {
        ++out;
      } else if (n > 1) {
        out += dedupe_run(&cut_.tris[out], &cut_.tri_origin[out], n, static_cast<std::uint32_t>(v),
                          scratch);
      }
      run = run_end;
    }
    kept_[g] = static_cast<std::uint32_t>(out - begin);
  }

  /// Moves the groups' triangles together where groups before lost doublets.
  void join_groups() {
    std::size_t size = kept_[0];
    for (std::size_t g = 1; g < groups_; ++g) {
      if (size != group_start_[g]) {
        std::copy_n(cut_.tris.begin() + group_start_[g], kept_[g], cut_.tris.begin() + size);
        std::copy_n(cut_.tri_origin.begin() + group_start_[g], kept_[g],
                    cut_.tri_origin.begin() + size);
      }
      size += kept_[g];
    }
    cut_.tris.resize(size);
    cut_.tri_origin.resize(size);
  }

  const TriangleMesh& mesh_;
  const Buffer<std::uint32_t>& node_of_;
  Cut& cut_;
  std::size_t nf_, groups_, blocks_;
  Buffer<Triangle> mapped_;
  Buffer<std::uint32_t> at_;  ///< [block][group]: the count, then the next slot in the list
  Buffer<std::uint32_t> group_start_;
  Buffer<std::uint64_t> list_;
  Buffer<std::uint32_t> kept_;
};

}  // namespace

Octree build_level0(const TriangleMesh& mesh, bool no_lines, Cut& cut, RemapScratch& scratch) {
  Buffer<std::uint8_t> used;
  const Octree octree = octree_around(validate(mesh, used));
  Buffer<std::uint64_t> code, order;  // order: sort keys (see sort_octree_order)
  morton_codes(mesh, used, octree, code, order);
  sort_octree_order(order, code, mesh.positions);
  while (!order.empty() && code[static_cast<std::uint32_t>(order.back())] == kUnused)
    order.pop_back();
  // Level-0 vertex of each used input vertex (unused ones are never read).
  Buffer<std::uint32_t> node_of(mesh.vertex_count());
  merge_equal_positions(mesh, order, code, cut, node_of);
  Buffer<Segment> line_candidates;
  const std::size_t count = cut.size();
  const std::size_t collapsed = TriangleSort(mesh, node_of, cut).run(no_lines, line_candidates);
  finish_faces(mesh.lines, node_of, count, line_candidates, cut, scratch);
  // Every vertex is a corner of an input triangle or an end of an input
  // line (validate); when no triangle collapsed and there are no lines,
  // each is a corner of a kept triangle (a doublet's corners are those of
  // the one kept) and there is nothing to drop.
  if (collapsed != 0 || !mesh.lines.empty())
    compact_vertices(count, number_used_vertices(count, cut, scratch), cut, scratch);
  return octree;
}

}  // namespace lodforge::detail::clustering
