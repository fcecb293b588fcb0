#pragma once
/// Corner signs of the marching-cube octree's lattice from range scans:
/// tangent-plane distances near the data, lines of sight and the scans' vote
/// elsewhere (detail of build_mc_octree).
#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lodforge/core/progress.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/range_scan.h"
#include "lodforge/mcoctree/sign_lattice.h"

namespace lodforge::detail {

/// Range points merged from several scans (no zippering) in the world frame,
/// and the signed distance they define (Kim, sec. 4.2, after Hoppe et al.
/// 1992, "Surface reconstruction from unorganized points"): the distance of x
/// to the tangent plane of the nearest range point, whose normal comes from
/// its 4 lattice neighbours. One nearest point makes the sign flicker where
/// two scans overlap slightly out of register, and one point's normal is
/// noisy, so the distance is taken from the nearby points whose normals agree
/// with the nearest one's (same sheet), Gaussian-weighted by distance and by
/// how far each point is trusted (RangeScan::weights: grazing samples, the
/// rims of the data and stray points count little, as in Curless & Levoy
/// 1996).
class ScanField {
 public:
  /// Takes the points the scans' grids refer to. Throws DataError (naming
  /// the scan) for a grid that is not cols x rows, a grid index out of range,
  /// colours or confidences not one per point, a negative or non-finite
  /// confidence, a non-finite coordinate, or no point at all.
  explicit ScanField(const std::vector<RangeScan>& scans);
  const Box3& bounds() const { return bounds_; }
  bool colored() const { return colored_; }
  std::size_t size() const { return points_.size(); }
  const Vec3& point(std::size_t i) const { return points_[i]; }

  /// Buckets the points in cells of size h from `origin`; precedes
  /// cell_of() and estimate().
  void index(const Vec3& origin, float h);
  /// The cell of p (cell coordinates may be negative or beyond the lattice).
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const;

  struct Estimate {
    bool found = false;
    float distance = 0;  ///< signed: negative inside
    Vec3 normal;
    Vec3 color;  ///< 0..255 per channel (grey where the scans have no colours)
  };
  /// The signed distance at x from the points within `reach` cells (per
  /// axis) of x's cell: the mean of the distance to their weighted plane
  /// (weighted centroid, mean normal) and of their tangent planes' weighted
  /// distances; not found when there is none.
  Estimate estimate(const Vec3& x, int reach) const;

 private:
  static std::uint64_t key(const std::array<std::int64_t, 3>& c);
  template <class Fn>
  void visit(const std::array<std::int64_t, 3>& c, int reach, Fn&& fn) const;

  std::vector<Vec3> points_, normals_;
  std::vector<float> weights_, log_weights_;  // RangeScan::weights and their logarithms
  std::vector<Rgb8> colors_;
  bool colored_ = false;
  Box3 bounds_;
  Vec3 origin_;
  float h_ = 1;
  std::vector<std::uint32_t> order_;
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> cells_;
};

/// The sign lattice of range scans at `resolution` (empty_lattice over
/// field's bounds; indexes `field` on it). Within two cells of a range point:
/// the weighted tangent-plane distance. Elsewhere: outside on the lattice's
/// boundary and wherever a line of sight shows the space empty (space
/// carving), inside where more scans see the point behind a measured surface
/// than beyond their data, else outside; then enclosed voids are filled and
/// small inside regions dropped (sign_components.h), and outside band points
/// with 4 or more of their 6 neighbours inside while they lie within a cell
/// of the plane (lone corners: pits) are made inside. Fills
/// stats' band_points, carved_points, flooded_points, filled_voids,
/// dropped_parts and sign_flips; reports "signs" (layers) to `progress`. The result does not
/// depend on the threads.
Lattice make_scan_lattice(ScanField& field, const std::vector<RangeScan>& scans, int resolution,
                          McBuildStats& stats, const ProgressCallback& progress);

/// Cells twice the scans' median point spacing across the longest side of
/// `bounds` (2..1000; 64 when no scan has a spacing).
int scan_resolution(const std::vector<RangeScan>& scans, const Box3& bounds);

}  // namespace lodforge::detail
