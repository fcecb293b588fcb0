// Hausdorff distance by sampling plus local refinement. The distance from a
// point to a surface is 1-Lipschitz, so a sampled maximum is at most one
// sample spacing short of the true one; the shortfall is removed where it
// matters by climbing the distance function inside the triangles of the
// farthest samples (barycentric pattern search, step halved down to 1/512 of
// the triangle). Metro (Cignoni et al. 1998) samples only; the refinement
// makes the result stable across seeds and sample counts (tested on the
// corpus: a denser measurement stays below 1.1x this one).
#include "lodforge/lod/measure_deviation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <span>

#include "lodforge/core/morton.h"
#include "lodforge/metrics/sample_surface.h"
#include "lodforge/metrics/triangle_bvh.h"

namespace lodforge {
namespace {

// estimate() samples and refines this many times less than hausdorff().
constexpr std::size_t kEstimateThinning = 8;

// A surface's samples in Morton order of their positions: consecutive
// samples lie close together, so each search starts from the triangle the
// one before it found, and neighbouring searches walk the same nodes.
struct Samples {
  std::vector<Vec3> positions;
  std::vector<std::uint32_t> triangles;  // the triangle of the mesh each lies on
  std::size_t size() const { return positions.size(); }
};

Samples morton_ordered(const SurfaceSamples& s) {
  const std::vector<std::uint64_t> keyed = morton_sorted_keys(s.positions);
  const auto n = std::uint32_t(keyed.size());
  Samples out;
  out.positions.resize(n);
  out.triangles.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const auto i = std::uint32_t(keyed[k]);
    out.positions[k] = s.positions[i];
    out.triangles[k] = s.triangles[i];
  }
  return out;
}

struct Side {
  const TriangleMesh* mesh = nullptr;
  Samples samples;
  std::unique_ptr<TriangleBvh> bvh;
  /// The mean distance between neighbouring area samples, sqrt(area / count).
  double spacing = 0;
};

Side make_side(const TriangleMesh& m, std::size_t samples, std::uint64_t seed,
               bool with_bvh = true) {
  Side s;
  s.mesh = &m;
  const SurfaceSamples drawn = sample_surface(m, {.count = samples,
                                                  .seed = seed,
                                                  .vertices = true,
                                                  .edge_count = samples / 4,
                                                  .vertex_normals = false});
  s.spacing = std::sqrt(drawn.area / double(std::max<std::size_t>(samples, 1)));
  s.samples = morton_ordered(drawn);
  // Morton order: its build costs a fraction of SAH's, and the searches,
  // which start at a hinted triangle and mostly end near it, hardly feel its
  // looser boxes.
  if (with_bvh) s.bvh = std::make_unique<TriangleBvh>(m, BvhOptions{.build = BvhBuild::kMorton});
  return s;
}

// The distance from p to `to` if it is larger than `floor` (all of them for
// a negative floor), else -1. `hint` is a triangle of `to` likely to be near
// p; it becomes the one found. Exact whenever it is not -1, whatever the hint.
double distance_above(const TriangleBvh& to, const Vec3& p, double floor, std::uint32_t& hint) {
  const float stop = floor < 0 ? -1.0f : float(floor * floor);
  ClosestPoint c = to.closest_point_unless_within(p, stop, hint);
  if (!c.found()) return 0.0;
  hint = c.triangle;
  return c.distance_squared > stop ? std::sqrt(double(c.distance_squared)) : -1.0;
}

// Barycentric coordinates of p (on or near triangle abc).
std::array<double, 3> barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1);
  double d20 = dot(v2, v0), d21 = dot(v2, v1);
  double den = d00 * d11 - d01 * d01;
  if (std::fabs(den) < 1e-30) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1 - v - w, v, w};
}

// Pattern search for a local maximum of the distance to `to` over one
// triangle of `from`, starting at `start`.
double climb(const TriangleMesh& from, std::uint32_t tri, const Vec3& start, const TriangleBvh& to,
             double best, std::uint32_t hint) {
  const Triangle& t = from.triangles[tri];
  const Vec3 a = from.positions[t[0]], b = from.positions[t[1]], c = from.positions[t[2]];
  auto at = [&](const std::array<double, 3>& w) {
    return Vec3{float(w[0] * a.x + w[1] * b.x + w[2] * c.x),
                float(w[0] * a.y + w[1] * b.y + w[2] * c.y),
                float(w[0] * a.z + w[1] * b.z + w[2] * c.z)};
  };
  std::array<double, 3> w = barycentric(a, b, c, start);
  const int moves[6][3] = {{1, -1, 0}, {-1, 1, 0}, {1, 0, -1}, {-1, 0, 1}, {0, 1, -1}, {0, -1, 1}};
  for (double h = 0.25; h >= 1.0 / 512; h /= 2) {
    bool moved = true;
    for (int guard = 0; moved && guard < 64; ++guard) {
      moved = false;
      for (const auto& m : moves) {
        std::array<double, 3> n = {w[0] + h * m[0], w[1] + h * m[1], w[2] + h * m[2]};
        if (n[0] < 0 || n[1] < 0 || n[2] < 0) continue;
        double d = distance_above(to, at(n), best, hint);
        if (d > best) {
          best = d;
          w = n;
          moved = true;
        }
      }
    }
  }
  return best;
}

// One direction: the farthest distance from `from`'s surface to `to`.
// Each search starts at the triangle the previous sample's search found (the
// samples are in Morton order), the first of a run at `near[f]` when given: a
// triangle of `to` near triangle f of `from` (from the simplifier's face
// map). Every
// kStride-th sample is measured exactly first; their largest distance is a
// floor under the answer, so each other sample only needs to know whether it
// is nearer than that, which most learn at the first triangle they try. The
// maximum is the one an exact distance for every sample gives; the samples
// whose neighbourhoods are searched are the farthest of those whose distance
// is known (all above the floor, and the strided ones).
double one_sided(const Side& from, const TriangleBvh& to, std::size_t refine,
                 std::span<const std::uint32_t> near, double known = 0) {
  constexpr std::size_t kStride = 32;
  const std::size_t n = from.samples.size();
  if (n == 0) return 0.0;
  const auto& at = from.samples.positions;
  auto start = [&](std::size_t i, std::uint32_t previous) {
    if (previous != ClosestPoint::kNone) return previous;
    return near.empty() ? ClosestPoint::kNone : near[from.samples.triangles[i]];
  };
  std::vector<double> d(n, -1.0);  // -1: nearer than the floor
  // Measures every stride-th sample not measured yet (`skip`: every
  // kStride-th is).
  auto measure = [&](std::size_t stride, double floor, bool skip) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, (n + stride - 1) / stride, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::uint32_t hint = ClosestPoint::kNone;
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          const std::size_t i = k * stride;
                          if (skip && i % kStride == 0) continue;
                          hint = start(i, hint);
                          d[i] = distance_above(to, at[i], floor, hint);
                        }
                      });
  };
  double floor = known;
  if (floor <= 0) {
    measure(kStride, -1, false);
    for (std::size_t i = 0; i < n; i += kStride) floor = std::max(floor, d[i]);
  }
  measure(1, floor, known <= 0);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i)
    if (d[i] >= 0) order.push_back(i);
  if (order.empty()) return known;  // no sample farther than the known distance
  const std::size_t k = std::min(refine, order.size());
  std::partial_sort(
      order.begin(), order.begin() + std::ptrdiff_t(k), order.end(),
      [&](std::size_t x, std::size_t y) { return d[x] > d[y] || (d[x] == d[y] && x < y); });
  double best = std::max(d[order[0]], known);
  std::vector<double> refined(k, 0.0);
  tbb::parallel_for(std::size_t(0), k, [&](std::size_t i) {
    const std::size_t s = order[i];
    refined[i] = climb(*from.mesh, from.samples.triangles[s], at[s], to, d[s],
                       start(s, ClosestPoint::kNone));
  });
  for (double r : refined) best = std::max(best, r);
  return best;
}

}  // namespace

struct DeviationMeter::Impl {
  DeviationOptions options;
  Side reference;
  // Every kEstimateThinning-th of the reference's samples (still in Morton
  // order and spread over the whole surface), for estimate().
  Side thin_reference;
};

DeviationMeter::DeviationMeter(const TriangleMesh& reference, const DeviationOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->reference = make_side(reference, options.samples, options.seed);
  Side& thin = impl_->thin_reference;
  thin.mesh = &reference;
  const Samples& all = impl_->reference.samples;
  for (std::size_t i = 0; i < all.size(); i += kEstimateThinning) {
    thin.samples.positions.push_back(all.positions[i]);
    thin.samples.triangles.push_back(all.triangles[i]);
  }
}

DeviationMeter::~DeviationMeter() = default;

namespace {

// Area samples of a level's side: one per level triangle, at least
// kFewestLevelSamples, at most the reference's count (a coarse level needs
// no sampling as dense as level 0's: its samples are many per triangle, and
// the hill climbing from the farthest ones finds the peaks; checked against
// 10^6-sample measurements by bench/lod_error_check.py).
constexpr std::size_t kFewestLevelSamples = 20000;

std::size_t level_samples(const TriangleMesh& level, std::size_t reference_samples) {
  return std::clamp<std::size_t>(
      level.triangle_count(), std::min(kFewestLevelSamples, reference_samples), reference_samples);
}

// A face map fit to start searches from: one reference triangle per level
// triangle, each in range; empty otherwise.
std::span<const std::uint32_t> level_to_reference(std::span<const std::uint32_t> face_map,
                                                  const TriangleMesh& level,
                                                  const TriangleMesh& reference) {
  if (face_map.size() != level.triangles.size()) return {};
  for (std::uint32_t f : face_map)
    if (f >= reference.triangles.size()) return {};
  return face_map;
}

}  // namespace

double DeviationMeter::hausdorff(const TriangleMesh& level, std::span<const std::uint32_t> face_map,
                                 double known) const {
  const TriangleMesh& reference = *impl_->reference.mesh;
  if (reference.triangles.empty() || level.triangles.empty()) return 0.0;
  Side other = make_side(level, level_samples(level, impl_->options.samples), impl_->options.seed);
  const auto to_reference = level_to_reference(face_map, level, reference);
  // The other way: a level triangle descended from each reference triangle.
  std::vector<std::uint32_t> to_level;
  if (!to_reference.empty()) {
    to_level.assign(reference.triangles.size(), ClosestPoint::kNone);
    for (std::uint32_t t = 0; t < to_reference.size(); ++t) to_level[to_reference[t]] = t;
  }
  const double ab = one_sided(impl_->reference, *other.bvh, impl_->options.refine, to_level, known);
  // Only a distance beyond ab changes the answer. Every point of the level
  // lies within about a sample spacing of a sample, and the distance is
  // 1-Lipschitz, so only samples within two spacings of ab can lead (by
  // refinement) beyond it: that is the other way's floor.
  const double ba = one_sided(other, *impl_->reference.bvh, impl_->options.refine, to_reference,
                              std::max(0.0, ab - 2 * other.spacing));
  return std::max(ab, ba);
}

double DeviationMeter::distance_to_reference(const TriangleMesh& level,
                                             std::span<const std::uint32_t> face_map) const {
  const TriangleMesh& reference = *impl_->reference.mesh;
  if (reference.triangles.empty() || level.triangles.empty()) return 0.0;
  const Side other = make_side(level, impl_->options.samples, impl_->options.seed, false);
  return one_sided(other, *impl_->reference.bvh, impl_->options.refine,
                   level_to_reference(face_map, level, reference));
}

double DeviationMeter::estimate(const TriangleMesh& level) const {
  if (impl_->reference.mesh->triangles.empty() || level.triangles.empty()) return 0.0;
  const TriangleBvh to(level, {.build = BvhBuild::kMorton});
  return one_sided(impl_->thin_reference, to,
                   std::max<std::size_t>(impl_->options.refine / kEstimateThinning, 1), {});
}

}  // namespace lodforge
