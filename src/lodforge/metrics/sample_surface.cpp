// Surface sampling for Metro-style mesh comparison: P. Cignoni, C. Rocchini,
// R. Scopigno, "Metro: measuring error on simplified surfaces", Computer
// Graphics Forum 17(2), 1998 — the surface is represented by its vertices,
// optionally points on its edges, and points spread over its faces in
// proportion to area. Uniform placement inside a triangle uses the square-root
// warp of Osada et al., "Shape distributions" (ACM TOG 21(4), 2002, §4.2):
// for r1, r2 uniform in [0,1), (1 - sqrt(r1), sqrt(r1)(1 - r2), sqrt(r1) r2)
// are uniformly distributed barycentric coordinates.
//
// Why stratified rather than independent draws: with independent draws a
// triangle's sample count is binomial, so small triangles can be missed
// entirely; slicing the cumulative area into `count` equal strata gives every
// triangle floor or ceil of its share, which lowers the variance of the
// estimated mean deviation at no cost.
#include "lodforge/metrics/sample_surface.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <numeric>

namespace lodforge {
namespace {

// SplitMix64 finaliser (Steele, Lea, Flood, "Fast splittable pseudorandom
// number generators", OOPSLA 2014): a bijective mixer, so hashing (seed, i)
// gives an independent-looking stream addressable by index.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Two uniform numbers in [0,1) from one 64-bit hash (24 bits each: floats).
struct Uniform2 {
  double a, b;
};
Uniform2 uniform2(std::uint64_t h) {
  constexpr double kScale = 1.0 / (1u << 24);
  return {double((h >> 40) & 0xffffffu) * kScale, double((h >> 16) & 0xffffffu) * kScale};
}

struct Faces {
  const TriangleMesh& mesh;
  bool smooth;               // interpolate vertex normals
  std::vector<Vec3> normal;  // unit face normals, zero when degenerate

  Faces(const TriangleMesh& m, bool vertex_normals)
      : mesh(m), smooth(vertex_normals && m.has_normals()), normal(m.triangles.size()) {
    for (std::size_t f = 0; f < m.triangles.size(); ++f) {
      const auto& t = m.triangles[f];
      const auto& p = m.positions;
      assert(t[0] < p.size() && t[1] < p.size() && t[2] < p.size());
      normal[f] = normalized(cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]));
    }
  }

  // Colour at barycentric (u, v, w) of triangle f (the mesh has colours).
  Vec3 color_at(std::uint32_t f, float u, float v, float w) const {
    const auto& t = mesh.triangles[f];
    const auto& c = mesh.colors;
    return c[t[0]] * u + c[t[1]] * v + c[t[2]] * w;
  }

  // Normal at barycentric (u, v, w) of triangle f.
  Vec3 at(std::uint32_t f, float u, float v, float w) const {
    if (!smooth) return normal[f];
    const auto& t = mesh.triangles[f];
    const auto& n = mesh.normals;
    Vec3 s = normalized(n[t[0]] * u + n[t[1]] * v + n[t[2]] * w);
    // Opposite vertex normals can cancel; the face normal is the honest answer.
    return length_squared(s) > 0 ? s : normal[f];
  }
};

void add_vertex_samples(const Faces& faces, SurfaceSamples& out) {
  const TriangleMesh& mesh = faces.mesh;
  constexpr std::uint32_t kUnused = ~0u;
  std::vector<std::uint32_t> first(mesh.positions.size(), kUnused);
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::uint32_t v : mesh.triangles[f]) {
      if (first[v] == kUnused) first[v] = f;
    }
  }
  for (std::uint32_t v = 0; v < first.size(); ++v) {
    if (first[v] == kUnused) continue;
    out.positions.push_back(mesh.positions[v]);
    out.normals.push_back(faces.smooth ? normalized(mesh.normals[v]) : faces.normal[first[v]]);
    if (length_squared(out.normals.back()) == 0) out.normals.back() = faces.normal[first[v]];
    out.triangles.push_back(first[v]);
    if (mesh.has_colors()) out.colors.push_back(mesh.colors[v]);
    ++out.vertex_samples;
  }
}

void add_edge_samples(const Faces& faces, std::size_t count, std::uint64_t seed,
                      SurfaceSamples& out) {
  const TriangleMesh& mesh = faces.mesh;
  // Unique undirected edges, each with the first triangle that has it (and the
  // slot of its first corner there, to interpolate normals).
  struct Edge {
    std::uint64_t key;
    std::uint32_t triangle;
    std::uint8_t corner;
  };
  std::vector<Edge> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (std::uint8_t k = 0; k < 3; ++k) {
      std::uint64_t a = t[k], b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b) << 32 | std::max(a, b), f, k});
    }
  }
  std::stable_sort(edges.begin(), edges.end(),
                   [](const Edge& x, const Edge& y) { return x.key < y.key; });
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const Edge& x, const Edge& y) { return x.key == y.key; }),
              edges.end());
  std::vector<double> cumulative(edges.size());
  double total = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& t = mesh.triangles[edges[e].triangle];
    int k = edges[e].corner;
    total += length(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]);
    cumulative[e] = total;
  }
  if (!(total > 0)) return;
  std::size_t base = out.positions.size();
  out.positions.resize(base + count);
  out.normals.resize(base + count);
  out.triangles.resize(base + count);
  if (mesh.has_colors()) out.colors.resize(base + count);
  out.edge_samples = count;
  std::uint64_t stream = mix(seed ^ 0x6564676573ull);  // "edges"
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      Uniform2 r = uniform2(mix(stream + i));
      double target = (double(i) + r.a) / double(count) * total;
      std::size_t e = std::min<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin(),
          edges.size() - 1);
      double start = e ? cumulative[e - 1] : 0.0;
      double span = cumulative[e] - start;
      float s = span > 0 ? float(std::clamp((target - start) / span, 0.0, 1.0)) : 0.f;
      const auto& t = mesh.triangles[edges[e].triangle];
      int k = edges[e].corner;
      std::array<float, 3> w{};
      w[k] = 1 - s;
      w[(k + 1) % 3] = s;
      const auto& p = mesh.positions;
      out.positions[base + i] = p[t[0]] * w[0] + p[t[1]] * w[1] + p[t[2]] * w[2];
      out.normals[base + i] = faces.at(edges[e].triangle, w[0], w[1], w[2]);
      out.triangles[base + i] = edges[e].triangle;
      if (mesh.has_colors())
        out.colors[base + i] = faces.color_at(edges[e].triangle, w[0], w[1], w[2]);
    }
  });
}

void add_area_samples(const Faces& faces, std::size_t count, std::uint64_t seed,
                      SurfaceSamples& out) {
  const TriangleMesh& mesh = faces.mesh;
  std::vector<double> cumulative(mesh.triangles.size());
  double total = 0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const auto& p = mesh.positions;
    total += 0.5 * double(length(cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]])));
    cumulative[f] = total;
  }
  out.area = total;
  if (!(total > 0) || count == 0) return;
  // Rounding can put a target at `total`; it then goes to the last triangle
  // with area, never to a trailing degenerate one.
  std::size_t last = cumulative.size() - 1;
  while (last > 0 && cumulative[last - 1] == total) --last;
  std::size_t base = out.positions.size();
  out.positions.resize(base + count);
  out.normals.resize(base + count);
  out.triangles.resize(base + count);
  if (mesh.has_colors()) out.colors.resize(base + count);
  std::uint64_t stream = mix(seed);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      std::uint64_t h = mix(stream + 2 * i);
      Uniform2 slice = uniform2(h);
      Uniform2 place = uniform2(mix(stream + 2 * i + 1));
      double target = (double(i) + slice.a) / double(count) * total;
      // upper_bound skips zero-area triangles: their cumulative value equals
      // the previous one, so no target lands strictly inside them.
      auto f = std::uint32_t(std::min<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin(),
          last));
      double r = std::sqrt(place.a);
      auto u = float(1 - r), v = float(r * (1 - place.b)), w = float(r * place.b);
      const auto& t = mesh.triangles[f];
      const auto& p = mesh.positions;
      out.positions[base + i] = p[t[0]] * u + p[t[1]] * v + p[t[2]] * w;
      out.normals[base + i] = faces.at(f, u, v, w);
      out.triangles[base + i] = f;
      if (mesh.has_colors()) out.colors[base + i] = faces.color_at(f, u, v, w);
    }
  });
}

}  // namespace

SurfaceSamples sample_surface(const TriangleMesh& mesh, const SampleOptions& options) {
  SurfaceSamples out;
  Faces faces(mesh, options.vertex_normals);
  std::size_t reserve =
      options.count + options.edge_count + (options.vertices ? mesh.positions.size() : 0);
  out.positions.reserve(reserve);
  out.normals.reserve(reserve);
  out.triangles.reserve(reserve);
  if (mesh.has_colors()) out.colors.reserve(reserve);
  if (options.vertices) add_vertex_samples(faces, out);
  if (options.edge_count) add_edge_samples(faces, options.edge_count, options.seed, out);
  add_area_samples(faces, options.count, options.seed, out);
  return out;
}

}  // namespace lodforge
