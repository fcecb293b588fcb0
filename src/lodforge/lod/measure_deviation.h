#pragma once
/// The geometric error of LOD levels: the two-sided Hausdorff distance
/// between level 0 and a simplified level, measured by sampling and then
/// refined where it is largest, so the switching ranges rest on the real
/// maximum and not on where samples happened to fall.
#include <cstddef>
#include <memory>
#include <span>

#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct DeviationOptions {
  /// Area samples of the reference's side (plus vertices and edges); a
  /// level's side in hausdorff() takes one per level triangle, at least
  /// min(20 000, this) and at most this; distance_to_reference() this many.
  std::size_t samples = 20000;
  std::uint64_t seed = 1;
  /// The farthest samples of each direction whose neighbourhood is searched
  /// for a larger distance (hill climbing inside their triangle).
  std::size_t refine = 64;
};

/// Measures many levels against one reference (level 0); the reference's
/// samples and search structure are built once. Thread-safe for concurrent
/// hausdorff() calls.
class DeviationMeter {
 public:
  /// `reference` must outlive the meter.
  DeviationMeter(const TriangleMesh& reference, const DeviationOptions& options = {});
  ~DeviationMeter();
  DeviationMeter(const DeviationMeter&) = delete;
  DeviationMeter& operator=(const DeviationMeter&) = delete;

  /// Two-sided Hausdorff distance between the reference and `level`, in model
  /// units; 0 if either has no triangles. `face_map` (optional: the
  /// simplifier's SimplifyResult::face_map, one reference triangle per level
  /// triangle) only tells where each search starts: the result is the same
  /// with or without it, found faster with it. A map of the wrong size or
  /// with an index out of range is ignored. `known`: a distance from a point
  /// of the reference to `level` already measured (estimate() of the same
  /// level, say); the result is at least it, and the search, which then only
  /// looks for farther points, ends sooner.
  double hausdorff(const TriangleMesh& level, std::span<const std::uint32_t> face_map = {},
                   double known = 0) const;

  /// One-sided: the largest distance from a point of `level` to the
  /// reference, in model units; 0 if either has no triangles. Cheaper than
  /// hausdorff() (no search structure of `level` is built). `face_map` as
  /// for hausdorff().
  double distance_to_reference(const TriangleMesh& level,
                               std::span<const std::uint32_t> face_map = {}) const;

  /// A quick estimate of hausdorff() for choosing among candidate levels:
  /// the one-sided distance from every eighth of the reference's samples to
  /// `level`, refined an eighth as much. Not a bound: it sees one direction,
  /// thinly; it is the direction that holds the maximum on coarse levels (a
  /// cut-off ear, a flattened ridge), and costs no sampling of `level`.
  double estimate(const TriangleMesh& level) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lodforge
