#include "lodforge/simplify/detail/clustering_faces.h"

#include <algorithm>
#include <cassert>

namespace lodforge::detail::clustering {

/// dedupe_run (below) for any n: out of line, for the runs of more than
/// three triangles and those with doublets.
std::size_t dedupe_long_run(Triangle* tris, std::uint32_t* origin, std::size_t n,
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
void remap_faces(std::span<const Triangle> mapped, std::span<const std::uint32_t> origin,
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
  const std::size_t count = mapped.size();
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
    const Triangle t = mapped[f];
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
    tri_origin[kept] = origin[f];
    kept += keep;
  }
  if (kept - run_begin > 1) flush();
  to.tris.resize(kept);
  to.tri_origin.resize(kept);
  line_candidates.resize(lines_before + candidates);
  finish_faces(lines, vertex_map, new_count, line_candidates, to, scratch);
}

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

}  // namespace lodforge::detail::clustering
