// The set-up of quadric_collapse: welding, wedges, triangle lists, working
// units, attribute channels, vertex kinds and quadrics, and the snapshot of
// the current mesh as a result.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "lodforge/simplify/detail/collapser.h"

namespace lodforge::detail::qem {

void Collapser::build() {
  check_simplify_input(mesh_, "quadric_collapse");
  const Welding welding = weld_positions();
  make_wedges(welding);
  const std::vector<std::uint8_t> used = collect_triangles(welding);
  const double diagonal = normalise_units(used);
  build_triangle_lists();
  set_up_channels(diagonal);
  compute_kinds();
  compute_quadrics();
  seq_.wedge_pairs.reserve(16);
  seq_.new_errors.reserve(64);
  seq_.new_list.resize(64);
}

/// Welds by position with an open-addressing hash.
Collapser::Welding Collapser::weld_positions() const {
  const std::size_t nv = mesh_.positions.size();
  std::size_t cap = 1;
  while (cap < 2 * nv + 1) cap <<= 1;
  std::vector<std::uint32_t> table(cap, kNone);
  auto bits = [](float f) {
    f = f == 0.0f ? 0.0f : f;  // +0 == -0
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
  };
  Welding welding;
  welding.vertex_position.resize(nv);
  std::vector<std::uint32_t>& first = welding.position_first_input;
  for (std::uint32_t i = 0; i < nv; ++i) {
    const Vec3& p = mesh_.positions[i];
    std::uint32_t h = bits(p.x) * 73856093u ^ bits(p.y) * 19349663u ^ bits(p.z) * 83492791u;
    std::size_t slot = (h ^ (h >> 15)) & (cap - 1);
    while (table[slot] != kNone && !(mesh_.positions[first[table[slot]]] == p))
      slot = (slot + 1) & (cap - 1);
    if (table[slot] == kNone) {
      table[slot] = static_cast<std::uint32_t>(first.size());
      first.push_back(i);
    }
    welding.vertex_position[i] = table[slot];
  }
  return welding;
}

/// The wedges: input vertices of one position with equal attributes share
/// one. Also sizes the positions' records and sets their coordinates.
void Collapser::make_wedges(const Welding& welding) {
  const std::size_t nv = mesh_.positions.size();
  const std::size_t np = welding.position_first_input.size();
  auto same_attributes = [&](std::uint32_t i, std::uint32_t j) {
    if (mesh_.has_normals() && !(mesh_.normals[i] == mesh_.normals[j])) return false;
    if (mesh_.has_texcoords() && !(mesh_.texcoords[i] == mesh_.texcoords[j])) return false;
    if (mesh_.has_colors() && !(mesh_.colors[i] == mesh_.colors[j])) return false;
    return true;
  };
  vx_.resize(np);
  version_.assign(np, 0);
  input_wedge_.assign(nv, kNone);
  std::vector<std::uint32_t> next_same_position(nv, kNone);
  std::vector<std::uint32_t> last_input(np, kNone);
  for (std::uint32_t i = 0; i < nv; ++i) {
    std::uint32_t p = welding.vertex_position[i];
    // Look for an earlier input vertex of the same position and attributes.
    for (std::uint32_t j = welding.position_first_input[p]; j != kNone && j != i;
         j = next_same_position[j])
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
    const Vec3& q = mesh_.positions[welding.position_first_input[p]];
    vx_[p].pos = {q.x, q.y, q.z};
  }
}

/// The triangles in positions and wedges; those using a position twice are
/// dead from the start. Returns per position whether a live triangle uses it.
std::vector<std::uint8_t> Collapser::collect_triangles(const Welding& welding) {
  const std::size_t nf = mesh_.triangles.size();
  tri_.assign(nf, Tri{{0, 0, 0}, {0, 0, 0}, 0.0f, 0});
  std::vector<std::uint8_t> used(vx_.size(), 0);
  for (std::size_t t = 0; t < nf; ++t) {
    for (int k = 0; k < 3; ++k) {
      std::uint32_t i = mesh_.triangles[t][k];
      tri_[t].v[k] = welding.vertex_position[i];
      tri_[t].w[k] = input_wedge_[i];
    }
    std::uint32_t a = tri_[t].v[0], b = tri_[t].v[1], c = tri_[t].v[2];
    if (a != b && b != c && c != a) {
      tri_[t].alive = 1;
      ++seq_.live;
      for (int k = 0; k < 3; ++k) used[tri_[t].v[k]] = 1;
    }
  }
  return used;
}

/// Moves to power-of-two units in which the bounding box's longest side is
/// in [0.5, 1): multiplying by a power of two is exact, so every decision is
/// the same at any scale (costs are fourth powers of lengths: in model units
/// they overflow or underflow float keys beyond about 2^+-30), and the output
/// is scaled back exactly. Returns the box's diagonal in working units (1 if
/// the box is empty or flat to a point).
double Collapser::normalise_units(const std::vector<std::uint8_t>& used) {
  const std::size_t np = vx_.size();
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
  if (!(side > 0 && std::isfinite(side))) return 1.0;
  int exponent = 0;
  std::frexp(side, &exponent);
  scale_ = std::ldexp(1.0, -exponent);
  for (std::size_t p = 0; p < np; ++p) vx_[p].pos = vx_[p].pos * scale_;
  return std::sqrt(norm2(hi - lo)) * scale_;
}

/// Position -> live triangle lists (CSR in triangle order; a collapse
/// rewrites a list by appending).
void Collapser::build_triangle_lists() {
  const std::size_t np = vx_.size(), nf = tri_.size();
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
}

/// The attribute channels (normals, texture coordinates, colours), scaled so
/// that a unit difference costs like a displacement of weight x `diagonal`,
/// and each wedge's values.
void Collapser::set_up_channels(double diagonal) {
  auto add_channels = [&](bool present, int count, float weight) {
    if (!present) return;
    for (int i = 0; i < count; ++i)
      channel_scale_[channels_++] = std::max(double(weight), 1e-4) * diagonal;
  };
  add_channels(mesh_.has_normals(), 3, options_.normal_weight);
  add_channels(mesh_.has_texcoords(), 2, options_.texcoord_weight);
  add_channels(mesh_.has_colors(), 3, options_.color_weight);
  attr_stride_ = channels_ > 0 ? 11 + 4 * channels_ : 0;
  if (channels_ == 0) return;
  const std::size_t nw = wedge_origin_.size();
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

// The vertices are cut into ranges, one task each: a task goes through all
// triangles and adds what a triangle gives to the vertices (and their wedges)
// of its range only, so every sum is added up in triangle order, as one pass
// would, however many ranges there are (the result does not depend on the
// thread count). Vertex numbers follow the mesh, so few triangles reach into
// two ranges and are worked out twice. Every range scans the whole triangle
// array, so there are as many ranges as the arena has threads (more would
// only add scans), and one for a small mesh, where a scan costs more than
// the work it shares.
void Collapser::compute_quadrics() {
  if (attr_stride_ > 0) wedge_quadric_.assign(wedge_origin_.size() * attr_stride_, 0.0);
  const auto np = static_cast<std::uint32_t>(vx_.size());
  const std::uint32_t parts =
      tri_.size() < 16384
          ? 1u
          : static_cast<std::uint32_t>(std::max(tbb::this_task_arena::max_concurrency(), 1));
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
    Quadric q{};
    q.add_plane(n.x, n.y, n.z, -dot(n, p[0]), area);
    for (int k = 0; k < 3; ++k)
      if (mine(corners[k])) vx_[corners[k]].q += q;

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
        Quadric pq{};
        pq.add_plane(m.x, m.y, m.z, -dot(m, vx_[a].pos), border_weight * l2);
        if (mine(a)) vx_[a].q += pq;
        if (mine(b)) vx_[b].q += pq;
      }
    }

    if (attr_stride_ > 0)
      add_attribute_quadrics(static_cast<std::uint32_t>(t), area, e1, e2, lo, hi);
  }
}

// Hoppe's attribute quadrics: per channel the in-plane gradient g and offset
// d with g.p_i + d = s_i at the three corners; the wedge quadric sums
// area (g.p + d)^2 as a quadric in p, and the area-weighted g and d.
/// Adds triangle t's attribute quadrics (face area `area`, edges e1 = p1 - p0
/// and e2 = p2 - p0) to the wedges of its corners at the positions in [lo, hi).
void Collapser::add_attribute_quadrics(std::uint32_t t, double area, D3 e1, D3 e2, std::uint32_t lo,
                                       std::uint32_t hi) {
  const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  if (det <= 1e-30 * g11 * g22) return;
  const D3 p0 = position_of_corner(t, 0);
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
    off[c] = s0 - dot(grad[c], p0);
  }
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t corner = tri_[t].v[k];
    if (corner < lo || corner >= hi) continue;
    double* wq = &wedge_quadric_[std::size_t{tri_[t].w[k]} * attr_stride_];
    // The first ten doubles of a wedge quadric are a Quadric.
    Quadric* qp = reinterpret_cast<Quadric*>(wq);
    static_assert(sizeof(Quadric) == 10 * sizeof(double));
    for (int c = 0; c < channels_; ++c) {
      const D3 g = grad[c];
      const double d = off[c];
      qp->add_plane(g.x, g.y, g.z, d, area);
      double* ch = wq + 11 + 4 * c;
      ch[0] += area * g.x;
      ch[1] += area * g.y;
      ch[2] += area * g.z;
      ch[3] += area * d;
    }
    wq[10] += area;
  }
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
}  // namespace lodforge::detail::qem
