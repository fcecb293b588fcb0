// The collapse loop of quadric_collapse: planning a collapse (placement and
// cost), checking and performing it, the queue of the whole mesh, and the
// regional first phase of a large reduction.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "lodforge/simplify/detail/collapser.h"

namespace lodforge::detail::qem {

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
    q += *reinterpret_cast<const Quadric*>(wq);
    double area = wq[10];
    if (area <= 0) return;
    double inv = 1 / area;
    for (int c = 0; c < channels_; ++c) {
      const double* g = wq + 11 + 4 * c;
      // The reduction of channel c: G G^T / area.
      const Quadric r = Quadric::plane(g[0], g[1], g[2], g[3], 1.0);
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
  q += vx_[v].q;
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
      const D3 g = apply_a(q, mid) + bv;
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
      double dad = dot(d, apply_a(q, d));
      double slope = dot(d, apply_a(q, pa) + D3{q.b0, q.b1, q.b2});
      double best_t = eval(q, pa) <= eval(q, pb) ? 0.0 : 1.0;
      if (dad > 0) {
        double t = std::clamp(-slope / dad, 0.0, 1.0);
        if (eval(q, pa + d * t) < eval(q, pa + d * best_t)) best_t = t;
      }
      w = pa + d * best_t;
    }
  }
  out.u = u;
  out.v = v;
  out.w = w;
  out.cost = eval(q, w);
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
/// sliver test is reported as such: the caller defers it (see drain()).
template <bool kRegional>
Outcome Collapser::try_collapse(const Collapse& c, bool allow_slivers, Lane& lane, Marks& marks) {
  const std::uint32_t u = c.u, v = c.v;
  std::uint32_t s_common = 0;
  if (!link_condition<kRegional>(u, v, marks, s_common)) return Outcome::kRejected;
  const Outcome checked = check_fans<kRegional>(c, allow_slivers, lane, marks, s_common);
  if (checked != Outcome::kDone) return checked;
  // v's list may grow to nu + nv - 2 (see rewrite_triangle_lists()); a region
  // must have room.
  if (kRegional && tris_count(u) + tris_count(v) > lane.refs_end - lane.refs_next)
    return Outcome::kNoRoom;

  // Allowed: perform it.
  merge_wedges(u, v, lane);
  for (auto& [t, e] : lane.new_errors) tri_[t].error = e;
  rewrite_triangle_lists<kRegional>(u, v, lane);
  vx_[v].q += vx_[u].q;
  vx_[v].pos = c.w;
  ++version_[u];
  ++version_[v];
  if (attr_stride_ > 0) update_wedge_attributes(v);
  return Outcome::kDone;
}

/// The link condition: the vertices adjacent to both u and v must be exactly
/// the third corners of the triangles on the edge. Leaves those common
/// neighbours marked with `s_common` (for check_fans()).
template <bool kRegional>
bool Collapser::link_condition(std::uint32_t u, std::uint32_t v, Marks& marks,
                               std::uint32_t& s_common) {
  const std::uint32_t s_u = ++marks.stamp;
  s_common = ++marks.stamp;
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
  return edge_tris != 0 && common == edge_tris;
}

/// The geometry of the triangles that stay, after the link condition:
/// duplicates, flips, slivers and the error bound. kDone if allowed, with the
/// new bounds of the moved triangles in `lane.new_errors`.
template <bool kRegional>
Outcome Collapser::check_fans(const Collapse& c, bool allow_slivers, Lane& lane, Marks& marks,
                              std::uint32_t s_common) {
  const std::uint32_t u = c.u, v = c.v;
  const D3 w = c.w;
  const std::uint32_t* tu = tris_begin(u);
  const std::uint32_t* tvv = tris_begin(v);
  const std::uint32_t nu = vx_[u].ref_count, nv = vx_[v].ref_count;
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
  return sliver ? Outcome::kSliver : Outcome::kDone;
}

/// The wedges of a collapse of u into v: wedges of u merge into the wedges of
/// v they meet on the edge triangles (their attribute quadrics add up);
/// others move to v as they are.
void Collapser::merge_wedges(std::uint32_t u, std::uint32_t v, Lane& lane) {
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
}

/// Rewrites the triangle lists of a collapse of u into v: v's list becomes
/// its own triangles but the edge ones, then u's that stay (renamed to v);
/// the edge triangles die and leave the lists of their third corners too, so
/// that every list holds live triangles only.
template <bool kRegional>
void Collapser::rewrite_triangle_lists(std::uint32_t u, std::uint32_t v, Lane& lane) {
  const std::uint32_t* tu = tris_begin(u);
  const std::uint32_t* tvv = tris_begin(v);
  const std::uint32_t nu = vx_[u].ref_count, nv = vx_[v].ref_count;
  // Written through a pointer into scratch of room nu + nv, so that the
  // loops carry no growth checks.
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
/// too would drive the interiors far below the target, since the seams
/// stay.) run() then continues on the whole mesh (seams included) from a new
/// queue. The regions and rounds depend on the mesh and target only, so the
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

}  // namespace lodforge::detail::qem
