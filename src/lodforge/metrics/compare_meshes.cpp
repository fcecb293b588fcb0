// Mesh comparison after Metro: P. Cignoni, C. Rocchini, R. Scopigno, "Metro:
// measuring error on simplified surfaces", Computer Graphics Forum 17(2),
// 1998, with the measures of the LODCreator thesis §5.2 (after M. Roy's Mesh comparison
// tool): for samples p on S1, e(p, S2) = min over q in S2 of |p - q|; the
// one-sided distance is the max of e, Hausdorff the larger of the two
// one-sided distances, and mean / variance are taken over the samples. The
// normal deviation n(p, S2) is the angle between the normal at p and at its
// closest point on S2; among equally close points the smallest angle counts
// (definition 5.2.6), which TriangleBvh's normal-preferring query implements.
//
// Sampling replaces the integral over S1; the exact closest point
// (Ericson's region method) under a bounding volume hierarchy makes each
// e(p, S2) exact, so the only approximation is which points are sampled.
// Angles use atan2(|n1 x n2|, n1 . n2), which is accurate near 0 where acos of
// a rounded dot product is not (acos(1 - 6e-8) is already 3e-4 rad).
#include "lodforge/metrics/compare_meshes.h"

#include <fmt/core.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <memory>

#include "lodforge/core/error.h"
#include "lodforge/metrics/sample_surface.h"
#include "lodforge/metrics/triangle_bvh.h"

namespace lodforge {
namespace {

constexpr std::size_t kSamplesPerTriangle = 10;
constexpr std::size_t kMinDefaultSamples = 100'000;
constexpr std::size_t kMaxDefaultSamples = 4'000'000;
constexpr float kNoiseUlps = 16;

void validate(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) {
    throw DataError(
        fmt::format("compare: {} has no triangles, so there is no surface to measure", name));
  }
  const std::size_t n = mesh.positions.size();
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::uint32_t v : mesh.triangles[f]) {
      if (v >= n) {
        throw DataError(
            fmt::format("compare: {}: triangle {} uses vertex {} of only {}", name, f, v, n));
      }
      if (!is_finite(mesh.positions[v])) {
        throw DataError(fmt::format("compare: {}: vertex {} has a non-finite coordinate", name, v));
      }
    }
  }
}

// Box of the vertices the triangles use (unused ones may be anything).
Box3 used_bounds(const TriangleMesh& mesh) {
  Box3 box;
  for (const auto& t : mesh.triangles) {
    for (std::uint32_t v : t) box.add(mesh.positions[v]);
  }
  return box;
}

float max_abs_coordinate(const Box3& box) {
  if (box.empty()) return 0;
  float m = 0;
  for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(box.lo[k]), std::abs(box.hi[k])});
  return m;
}

// Area-weighted vertex normals: the sum of the unnormalised face normals
// (|cross| = twice the area) around each vertex.
TriangleMesh with_estimated_normals(const TriangleMesh& mesh) {
  TriangleMesh out = mesh;
  std::vector<Vec3> sum(mesh.positions.size());
  for (const auto& t : mesh.triangles) {
    const auto& p = mesh.positions;
    Vec3 n = cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
    for (std::uint32_t v : t) sum[v] += n;
  }
  out.normals.resize(sum.size());
  for (std::size_t v = 0; v < sum.size(); ++v) out.normals[v] = normalized(sum[v]);
  return out;
}

// Per-sample results of one direction.
struct Measured {
  std::vector<float> distance;
  std::vector<float> angle;  // NaN where a normal is undefined
  std::vector<float> color;  // empty unless both surfaces have colours
};

// Samples are processed in fixed blocks; within a block each query starts
// from the previous answer's triangle (samples come in triangle order, so
// neighbours are near), which prunes most of the hierarchy at once. Fixed
// blocks keep the hints, hence the tie choices, independent of the threads.
constexpr std::size_t kBlock = 256;

// Progress: every 64 blocks (16 384 samples).
constexpr std::uint64_t kProgressStep = 64 * kBlock;

template <typename Query>
void for_each_in_blocks(std::size_t n, ProgressCounter& progress, Query&& query) {
  tbb::parallel_for(std::size_t(0), (n + kBlock - 1) / kBlock, [&](std::size_t block) {
    std::uint32_t hint = ClosestPoint::kNone;
    const std::size_t first = block * kBlock, end = std::min(n, first + kBlock);
    for (std::size_t i = first; i < end; ++i) {
      hint = query(i, hint);
    }
    progress.add(end - first);
  });
}

Measured measure(const SurfaceSamples& samples, const TriangleMesh& other_mesh,
                 const TriangleBvh& other, float noise, ProgressCounter& progress) {
  Measured m;
  m.distance.resize(samples.size());
  m.angle.resize(samples.size());
  const bool colors = !samples.colors.empty() && other_mesh.has_colors();
  if (colors) m.color.resize(samples.size());
  for_each_in_blocks(samples.size(), progress, [&](std::size_t i, std::uint32_t hint) {
    const Vec3& n1 = samples.normals[i];
    ClosestPoint c = other.closest_point(samples.positions[i], n1, hint);
    float d = std::sqrt(c.distance_squared);
    m.distance[i] = d <= noise ? 0.f : d;
    Vec3 n2 = other.normal_at(c);
    if (length_squared(n1) > 0 && length_squared(n2) > 0) {
      m.angle[i] = std::atan2(length(cross(n1, n2)), dot(n1, n2));
    } else {
      m.angle[i] = std::numeric_limits<float>::quiet_NaN();
    }
    if (colors) {
      const auto& t = other_mesh.triangles[c.triangle];
      const auto& col = other_mesh.colors;
      const auto& w = c.barycentric;
      Vec3 there = col[t[0]] * w[0] + col[t[1]] * w[1] + col[t[2]] * w[2];
      m.color[i] = length(samples.colors[i] - there);
    }
    return c.triangle;
  });
  return m;
}

// Sums run serially in double over the stored per-sample values, so the
// statistics do not depend on how the work was split between threads.
Deviation summarise(const Measured& m, std::size_t first_area, double diagonal) {
  Deviation out;
  const std::size_t n = m.distance.size();
  out.samples = n;
  if (n == 0) return out;
  if (first_area >= n) first_area = 0;
  out.min = *std::min_element(m.distance.begin(), m.distance.end());
  out.max = *std::max_element(m.distance.begin(), m.distance.end());
  double sum = 0, sum2 = 0;
  for (std::size_t i = first_area; i < n; ++i) {
    sum += m.distance[i];
    sum2 += double(m.distance[i]) * m.distance[i];
  }
  double count = double(n - first_area);
  out.mean = sum / count;
  out.rms = std::sqrt(sum2 / count);
  double var = 0;
  for (std::size_t i = first_area; i < n; ++i) {
    double e = m.distance[i] - out.mean;
    var += e * e;
  }
  out.variance = var / count;
  if (diagonal > 0) {
    out.max_pct = 100 * out.max / diagonal;
    out.mean_pct = 100 * out.mean / diagonal;
    out.rms_pct = 100 * out.rms / diagonal;
  }

  NormalDeviation& nd = out.normal;
  double asum = 0;
  std::size_t acount = 0;
  for (std::size_t i = 0; i < n; ++i) {
    float a = m.angle[i];
    if (std::isnan(a)) continue;
    nd.max = std::max(nd.max, double(a));
    if (i >= first_area) {
      asum += a;
      ++acount;
    }
  }
  nd.samples = acount;
  if (acount) {
    nd.mean = asum / double(acount);
    double avar = 0;
    for (std::size_t i = first_area; i < n; ++i) {
      if (std::isnan(m.angle[i])) continue;
      double e = m.angle[i] - nd.mean;
      avar += e * e;
    }
    nd.variance = avar / double(acount);
  }

  if (!m.color.empty()) {
    ColorDeviation& cd = out.color;
    cd.samples = n;
    cd.max = *std::max_element(m.color.begin(), m.color.end());
    double csum = 0, csum2 = 0;
    for (std::size_t i = first_area; i < n; ++i) {
      csum += m.color[i];
      csum2 += double(m.color[i]) * m.color[i];
    }
    cd.mean = csum / count;
    cd.rms = std::sqrt(csum2 / count);
  }
  return out;
}

CompareResult run(const TriangleMesh& a, const TriangleMesh& b, const CompareOptions& options) {
  CompareResult result;
  Box3 box_a = used_bounds(a);
  result.diagonal = box_a.diagonal();
  result.samples =
      options.samples
          ? options.samples
          : std::clamp(kSamplesPerTriangle * std::max(a.triangle_count(), b.triangle_count()),
                       kMinDefaultSamples, kMaxDefaultSamples);
  // Each sample holds a position, a normal, a triangle, a colour and its
  // measured distance and angle: 64 bytes is an upper bound.
  constexpr double kBytesPerSample = 64;
  const double per_direction = double(result.samples) + double(options.edge_samples) +
                               double(std::max(a.vertex_count(), b.vertex_count()));
  check_memory_budget(2 * per_direction * kBytesPerSample, options.max_memory,
                      fmt::format("comparing with {} area samples per direction", result.samples),
                      "use fewer samples");
  result.vertex_normals = a.has_normals() && b.has_normals();
  Box3 box_ab = box_a;
  box_ab.add(used_bounds(b));
  float noise = options.snap_noise ? kNoiseUlps * FLT_EPSILON * max_abs_coordinate(box_ab) : 0.f;

  SampleOptions sample_a{.count = result.samples,
                         .seed = options.seed,
                         .vertices = options.vertices,
                         .edge_count = options.edge_samples,
                         .vertex_normals = result.vertex_normals};
  SampleOptions sample_b = sample_a;
  sample_b.seed = options.seed + 1;
  BvhOptions bvh{.vertex_normals = result.vertex_normals};

  SurfaceSamples samples_a, samples_b;
  std::unique_ptr<TriangleBvh> bvh_a, bvh_b;
  tbb::parallel_invoke([&] { samples_a = sample_surface(a, sample_a); },
                       [&] { samples_b = sample_surface(b, sample_b); },
                       [&] { bvh_a = std::make_unique<TriangleBvh>(a, bvh); },
                       [&] { bvh_b = std::make_unique<TriangleBvh>(b, bvh); });

  auto area_start = [](const SurfaceSamples& s) { return s.vertex_samples + s.edge_samples; };
  ProgressCounter a_to_b(options.progress, "A to B", samples_a.size(), kProgressStep);
  result.a_to_b = summarise(measure(samples_a, b, *bvh_b, noise, a_to_b), area_start(samples_a),
                            result.diagonal);
  ProgressCounter b_to_a(options.progress, "B to A", samples_b.size(), kProgressStep);
  result.b_to_a = summarise(measure(samples_b, a, *bvh_a, noise, b_to_a), area_start(samples_b),
                            result.diagonal);
  result.hausdorff = std::max(result.a_to_b.max, result.b_to_a.max);
  result.hausdorff_pct = result.diagonal > 0 ? 100 * result.hausdorff / result.diagonal : 0;

  if (options.per_vertex) {
    result.vertex_deviation.resize(a.positions.size());
    ProgressCounter vertices(options.progress, "vertices", a.positions.size(), kProgressStep);
    for_each_in_blocks(a.positions.size(), vertices, [&](std::size_t v, std::uint32_t hint) {
      const Vec3& p = a.positions[v];
      // Unused vertices may hold anything; they get 0.
      if (!is_finite(p)) {
        result.vertex_deviation[v] = 0;
        return hint;
      }
      ClosestPoint c = bvh_b->closest_point(p, hint);
      float d = std::sqrt(c.distance_squared);
      result.vertex_deviation[v] = d <= noise ? 0.f : d;
      return c.triangle;
    });
  }
  return result;
}

}  // namespace

CompareResult compare_meshes(const TriangleMesh& a, const TriangleMesh& b,
                             const CompareOptions& options) {
  validate(a, options.a_name);
  validate(b, options.b_name);
  if (options.estimate_normals && !(a.has_normals() && b.has_normals())) {
    CompareOptions again = options;
    again.estimate_normals = false;
    return compare_meshes(a.has_normals() ? a : with_estimated_normals(a),
                          b.has_normals() ? b : with_estimated_normals(b), again);
  }
  if (options.threads > 0) {
    tbb::task_arena arena(options.threads);
    return arena.execute([&] { return run(a, b, options); });
  }
  return run(a, b, options);
}

}  // namespace lodforge
