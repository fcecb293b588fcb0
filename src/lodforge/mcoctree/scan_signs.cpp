// Corner signs of the marching-cube octree from range scans (Kim, "Level-of-
// detail mesh modeling using the marching cube octree", ch. 4): signed
// distances to the range points' tangent planes near the data, and space
// carving along the scanner's lines of sight (Curless & Levoy 1996, "A
// volumetric method for building complex models from range images")
// elsewhere.
#include "lodforge/mcoctree/scan_signs.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/sign_components.h"

namespace lodforge::detail {
namespace {

// An inside region smaller than this many lattice points, or than this
// fraction of the largest, is a bubble (see clean_scan_signs).
constexpr std::size_t kMinScanPart = 64;
constexpr double kMinScanPartFraction = 0.01;

// The points of `s` its grid refers to (1) and the others (0). Throws
// DataError for a grid that does not fit the scan.
std::vector<std::uint8_t> used_points(const RangeScan& s) {
  if (s.cols < 0 || s.rows < 0 || s.grid.size() != static_cast<std::size_t>(s.cols) * s.rows)
    throw DataError("mcoctree: " + s.name + ": grid size is not num_cols x num_rows");
  if (!s.colors.empty() && s.colors.size() != s.points.size())
    throw DataError("mcoctree: " + s.name + ": " + std::to_string(s.colors.size()) +
                    " colours for " + std::to_string(s.points.size()) + " points");
  if (!s.confidence.empty() && s.confidence.size() != s.points.size())
    throw DataError("mcoctree: " + s.name + ": " + std::to_string(s.confidence.size()) +
                    " confidences for " + std::to_string(s.points.size()) + " points");
  for (float c : s.confidence)
    if (!(c >= 0 && std::isfinite(c)))
      throw DataError("mcoctree: " + s.name + ": a negative or non-finite confidence");
  std::vector<std::uint8_t> used(s.points.size(), 0);
  for (auto g : s.grid) {
    if (g >= 0 && static_cast<std::size_t>(g) >= s.points.size())
      throw DataError("mcoctree: " + s.name + ": grid index " + std::to_string(g) +
                      " out of range (" + std::to_string(s.points.size()) + " points)");
    if (g >= 0) used[static_cast<std::size_t>(g)] = 1;
  }
  return used;
}

}  // namespace

ScanField::ScanField(const std::vector<RangeScan>& scans) {
  for (const auto& s : scans) {
    const std::vector<std::uint8_t> used = used_points(s);
    std::vector<Vec3> n = s.normals();
    std::vector<float> w = s.weights(n);
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      if (!used[i]) continue;
      if (!is_finite(s.points[i]))
        throw DataError("mcoctree: " + s.name + ": a non-finite coordinate");
      points_.push_back(s.to_world(s.points[i]));
      normals_.push_back(normalized(s.rotate(n[i])));
      weights_.push_back(w[i]);
      log_weights_.push_back(std::log(w[i]));
      colored_ = colored_ || !s.colors.empty();
      colors_.push_back(s.colors.empty() ? Rgb8{200, 200, 200} : s.colors[i]);
    }
  }
  if (points_.empty()) throw DataError("mcoctree: the range scans hold no point");
  for (const auto& p : points_) bounds_.add(p);
}

void ScanField::index(const Vec3& origin, float h) {
  origin_ = origin, h_ = h;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points_.size());
  for (std::uint32_t i = 0; i < points_.size(); ++i) keyed[i] = {key(cell_of(points_[i])), i};
  std::sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    order_[i] = keyed[i].second;
    if (i == 0 || keyed[i].first != keyed[i - 1].first)
      cells_[keyed[i].first] = {static_cast<std::uint32_t>(i), 0};
    ++cells_[keyed[i].first].second;
  }
}

std::array<std::int64_t, 3> ScanField::cell_of(const Vec3& p) const {
  return {static_cast<std::int64_t>(std::floor((p.x - origin_.x) / h_)),
          static_cast<std::int64_t>(std::floor((p.y - origin_.y) / h_)),
          static_cast<std::int64_t>(std::floor((p.z - origin_.z) / h_))};
}

std::uint64_t ScanField::key(const std::array<std::int64_t, 3>& c) {
  return static_cast<std::uint64_t>(c[0] & 0x1fffff) |
         static_cast<std::uint64_t>(c[1] & 0x1fffff) << 21 |
         static_cast<std::uint64_t>(c[2] & 0x1fffff) << 42;
}

template <class Fn>
void ScanField::visit(const std::array<std::int64_t, 3>& c, int reach, Fn&& fn) const {
  for (auto k = c[2] - reach; k <= c[2] + reach; ++k)
    for (auto j = c[1] - reach; j <= c[1] + reach; ++j)
      for (auto i = c[0] - reach; i <= c[0] + reach; ++i) {
        if (i < 0 || j < 0 || k < 0) continue;
        auto it = cells_.find(key({i, j, k}));
        if (it == cells_.end()) continue;
        for (std::uint32_t a = 0; a < it->second.second; ++a) fn(order_[it->second.first + a]);
      }
}

// The reference point is the one of largest Gaussian weight times trust,
// exp(-d^2 / h^2) w, i.e. least d^2 - h^2 ln w: the nearest point unless a
// more trusted one is about as near (a stray or grazing sample nearest to x
// otherwise picks the sheet and its noisy normal). Within `reach` cells (per
// axis), the points of its sheet (normals within 60 degrees of its) weighted
// by exp(-(d^2 - d_ref^2) / h^2) w, up to 4 h^2 beyond the reference, give
// the distance as the mean of two estimates:
//
// | estimate                                   | normal noise | curvature 1/R       |
// |--------------------------------------------|--------------|---------------------|
// | to the plane through the weighted centroid | averaged     | + mean s^2 / 2R     |
// |   along the weighted mean normal           |              |                     |
// | weighted mean of the distances to each     | kept         | - mean s^2 / 2R     |
// |   point's own tangent plane                |              |                     |
//
// (s: a point's offset along the surface from x's foot). The mean halves the
// normals' noise, which moved a corner two cells off the surface by a fair
// part of a cell (the spikes and pits of a mesh from the Stanford bunny's
// scans), and cancels the curvature terms to second order (the plane alone
// pushed a coarse lattice's torus off its tube).
ScanField::Estimate ScanField::estimate(const Vec3& x, int reach) const {
  auto c = cell_of(x);
  const float h2 = h_ * h_;
  float best = INFINITY, score = INFINITY;
  std::uint32_t ref = 0;
  visit(c, reach, [&](std::uint32_t i) {
    const float d2 = length_squared(points_[i] - x);
    const float sc = d2 - h2 * log_weights_[i];
    if (sc < score) score = sc, best = d2, ref = i;
  });
  Estimate e;
  if (best == INFINITY) return e;
  e.found = true;
  const Vec3 n0 = normals_[ref];
  double wsum = 0, dsum = 0;
  Vec3 nsum{}, psum{}, csum{};
  visit(c, reach, [&](std::uint32_t i) {
    if (dot(normals_[i], n0) <= 0.5f) return;
    const float d2 = length_squared(points_[i] - x);
    if (d2 > best + 4 * h2) return;
    const float w = std::exp(-(d2 - best) / h2) * weights_[i];
    wsum += w;
    nsum += normals_[i] * w;
    psum += points_[i] * w;
    dsum += w * dot(x - points_[i], normals_[i]);
    csum += Vec3{colors_[i][0] * 1.0f, colors_[i][1] * 1.0f, colors_[i][2] * 1.0f} * w;
  });
  const float inv = static_cast<float>(1 / wsum);
  e.normal = normalized(nsum);
  e.distance = 0.5f * (dot(x - psum * inv, e.normal) + static_cast<float>(dsum / wsum));
  e.color = csum * inv;
  return e;
}

namespace {

// Line-of-sight carving (Curless & Levoy 1996's space carving, reduced to
// signs): each scan is resampled as a depth image in its own frame (the
// sensor looks down -z, lines of sight parallel: the Stanford Cyberware
// scans and mco scan's are), from its grid triangles without the depth
// jumps. What the scans say of a point (seen_at):
//
// | the scans' lines through it                                 | the point is      |
// |-------------------------------------------------------------|-------------------|
// | one reaches its surface behind the point (by > `margin`)    | empty (outside)   |
// | else more meet a surface before it than pass beyond the     | occluded (inside) |
// |   scan's data (background: farther than `margin` from every |                   |
// |   pixel with data, or outside the scan's window)            |                   |
// | else                                                        | unseen (outside)  |
//
// Only measured depth carves for sure. A pixel without data inside the
// silhouette (a gap at a grazing angle) says nothing: carving along those
// lines made the bunny a shell, an inner wall wherever one scan had a gap.
// Background lines only vote: the Cyberware scans are partial (a limited
// window; the chin and ear scans are close-ups), so beyond one scan's data
// may lie the object that eight others see behind their surfaces, while
// space that one scan sees behind an ear and the others beyond their data
// is air (with "occluded" alone, such space made blobs 2 cm across).
class SightCarver {
 public:
  enum class Seen { kUnseen, kEmpty, kOccluded };
  SightCarver(const std::vector<RangeScan>& scans, float margin) : margin_(margin) {
    for (const auto& s : scans) add(s);
  }
  Seen seen_at(const Vec3& world) const {
    int occluded = 0, background = 0;
    for (const auto& im : images_) {
      Vec3 q = im.scan->to_scan(world);
      auto i = static_cast<std::int64_t>(std::floor((q.x - im.x0) / im.s));
      auto j = static_cast<std::int64_t>(std::floor((q.y - im.y0) / im.s));
      if (i < 0 || j < 0 || i >= im.w || j >= im.h) {
        ++background;  // beyond the scan's window
        continue;
      }
      const std::size_t px = static_cast<std::size_t>(j) * im.w + i;
      const float depth = im.depth[px];
      if (!std::isfinite(depth)) {
        background += im.background[px];
        continue;
      }
      if (q.z > depth + margin_) return Seen::kEmpty;
      occluded += q.z < depth - margin_;
    }
    return occluded > background ? Seen::kOccluded : Seen::kUnseen;
  }

 private:
  struct Image {
    const RangeScan* scan;
    float x0, y0, s;
    int w, h;
    std::vector<float> depth;              // nearest surface (largest z); -inf: none
    std::vector<std::uint8_t> background;  // no data within margin of the line
  };
  void add(const RangeScan& scan) {
    float s = scan.spacing();
    if (!(s > 0)) return;
    Box3 box;
    for (auto g : scan.grid)
      if (g >= 0) box.add(scan.points[g]);
    Vec3 size = box.size();
    // At most 4096 pixels a side: coarser pixels for a very wide scan.
    s = std::max(s, std::max(size.x, size.y) / 4090.0f);
    Image im{&scan, box.lo.x - 2 * s, box.lo.y - 2 * s, s, 0, 0, {}, {}};
    im.w = static_cast<int>(std::ceil(size.x / s)) + 5;
    im.h = static_cast<int>(std::ceil(size.y / s)) + 5;
    im.depth.assign(static_cast<std::size_t>(im.w) * im.h, -INFINITY);
    const float limit2 = 16 * scan.spacing() * scan.spacing();
    auto at = [&](int r, int c) { return scan.grid[static_cast<std::size_t>(r) * scan.cols + c]; };
    auto raster = [&](std::int32_t ia, std::int32_t ib, std::int32_t ic) {
      if (ia < 0 || ib < 0 || ic < 0) return;
      const Vec3 &a = scan.points[ia], &b = scan.points[ib], &c = scan.points[ic];
      if (length_squared(a - b) > limit2 || length_squared(b - c) > limit2 ||
          length_squared(c - a) > limit2)
        return;
      float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (!(std::abs(area) > 0)) return;
      auto px = [&](float v, float o) { return (v - o) / im.s - 0.5f; };
      int c0 = std::max(0, static_cast<int>(std::ceil(px(std::min({a.x, b.x, c.x}), im.x0))));
      int c1 =
          std::min(im.w - 1, static_cast<int>(std::floor(px(std::max({a.x, b.x, c.x}), im.x0))));
      int r0 = std::max(0, static_cast<int>(std::ceil(px(std::min({a.y, b.y, c.y}), im.y0))));
      int r1 =
          std::min(im.h - 1, static_cast<int>(std::floor(px(std::max({a.y, b.y, c.y}), im.y0))));
      for (int r = r0; r <= r1; ++r)
        for (int cc = c0; cc <= c1; ++cc) {
          float x = im.x0 + (static_cast<float>(cc) + 0.5f) * im.s;
          float y = im.y0 + (static_cast<float>(r) + 0.5f) * im.s;
          float l1 = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
          float l2 = ((a.x - x) * (b.y - y) - (b.x - x) * (a.y - y)) / area;
          float l0 = 1 - l1 - l2;
          if (l0 < -1e-4f || l1 < -1e-4f || l2 < -1e-4f) continue;
          float z = l0 * a.z + l1 * b.z + l2 * c.z;
          auto& d = im.depth[static_cast<std::size_t>(r) * im.w + cc];
          d = std::max(d, z);
        }
    };
    for (int r = 0; r + 1 < scan.rows; ++r)
      for (int c = 0; c + 1 < scan.cols; ++c) {
        raster(at(r, c), at(r, c + 1), at(r + 1, c + 1));
        raster(at(r, c), at(r + 1, c + 1), at(r + 1, c));
      }
    // Background: pixels farther than the margin from every pixel with
    // data (chamfer distance, two passes), the outside of the silhouette;
    // nearer ones may be a gap in the object's surface.
    const int reach = std::max(1, static_cast<int>(std::ceil(margin_ / im.s)));
    std::vector<int> dist(im.depth.size());
    for (std::size_t k = 0; k < dist.size(); ++k)
      dist[k] = std::isfinite(im.depth[k]) ? 0 : reach + 1;
    auto relax = [&](int r, int c, int dr, int dc) {
      const int rr = r + dr, cc = c + dc;
      if (rr < 0 || cc < 0 || rr >= im.h || cc >= im.w) return;
      int& d = dist[static_cast<std::size_t>(r) * im.w + c];
      d = std::min(d, dist[static_cast<std::size_t>(rr) * im.w + cc] + 1);
    };
    for (int r = 0; r < im.h; ++r)
      for (int c = 0; c < im.w; ++c) {
        relax(r, c, -1, -1);
        relax(r, c, -1, 0);
        relax(r, c, -1, 1);
        relax(r, c, 0, -1);
      }
    for (int r = im.h - 1; r >= 0; --r)
      for (int c = im.w - 1; c >= 0; --c) {
        relax(r, c, 1, 1);
        relax(r, c, 1, 0);
        relax(r, c, 1, -1);
        relax(r, c, 0, 1);
      }
    im.background.resize(dist.size());
    for (std::size_t k = 0; k < dist.size(); ++k) im.background[k] = dist[k] > reach;
    images_.push_back(std::move(im));
  }
  float margin_;
  std::vector<Image> images_;
};

// An outside band point whose sign disagrees with at least this many of its
// 6 lattice neighbours, and whose distance is under this many cells, is a
// lone corner (see flip_lone_corners).
constexpr int kLoneDisagreeing = 4;
constexpr float kLoneWeak = 1.0f;

// Lone corners: an outside band point sunk into the inside (4 or more of its
// 6 neighbours inside: sharper than the corner of a cube, where 3 are) while
// the plane is within a cell of it. Such a corner is a pit a cell deep in an
// otherwise smooth surface (noise between overlapping scans flips one
// estimate); it is made inside. The mirror case, a lone inside corner, is
// left alone: it is also the tip of a feature thinner than a cell (a
// horse's ear scanned by mco scan lost its tip, 0.9 -> 1.4 % of the
// diagonal away, when those flipped too), and the weighted distance already
// removes most spikes. On the Stanford bunny's scans (per-point tangent
// planes), flips at 5 or more disagreeing neighbours left a normal deviation
// from bun_zipper of 0.19 rad where 4 or more left 0.165; 3 or more flips
// corners of slanted surfaces too and roughened it (0.37). The decision is
// made for every point against the signs as they are, then applied, so it
// does not depend on the order:
//
// | sign    | neighbours inside    | |distance| < kLoneWeak cells | the point    |
// |---------|----------------------|------------------------------|--------------|
// | outside | >= kLoneDisagreeing  | yes                          | made inside  |
// | any     | otherwise            | either                       | kept         |
//
// On the lattice's border nothing flips (outside by construction). Returns
// the number of points flipped.
std::size_t flip_lone_corners(Lattice& lat) {
  std::vector<std::uint8_t> flip(lat.distance.size(), 0);
  const float weak = kLoneWeak * lat.h;
  tbb::parallel_for(std::size_t{0}, lat.distance.size(), [&](std::size_t i) {
    const Lattice::Exact& e = lat.distance[i];
    if (lat.inside(e.idx) || std::abs(e.distance) >= weak || lat.on_border(e.idx)) return;
    int other = 0;
    lattice_neighbours(lat, e.idx, [&](std::int64_t q) { other += lat.inside(q); });
    flip[i] = other >= kLoneDisagreeing;
  });
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < flip.size(); ++i)
    if (flip[i]) lat.state[lat.distance[i].idx] ^= kInside, ++flipped;
  return flipped;
}

}  // namespace

// The sign lattice of range scans. Band: the lattice points within two cells
// of a range point get the weighted tangent-plane distance. Outside: the
// box's outer faces (the root cube has a free cell all round) and every point
// a line of sight shows empty (SightCarver, 2 cells of margin). Every other
// point (inside the object, in a gap of the data, or seen by no scan: under
// the Stanford bunny, which stood on the turntable) by the scans' vote
// (SightCarver::seen_at), which closes the unseen region with a cap where
// the vote changes.
Lattice make_scan_lattice(ScanField& field, const std::vector<RangeScan>& scans, int resolution,
                          McBuildStats& stats, const ProgressCallback& progress) {
  Lattice lat = empty_lattice(field.bounds(), resolution);
  field.index(lat.origin, lat.h);
  std::vector<std::int64_t> band;
  for (std::size_t i = 0; i < field.size(); ++i) {
    auto c = field.cell_of(field.point(i));
    for (auto k = c[2] - 1; k <= c[2] + 2; ++k)
      for (auto j = c[1] - 1; j <= c[1] + 2; ++j)
        for (auto a = c[0] - 1; a <= c[0] + 2; ++a) {
          if (a < 0 || j < 0 || k < 0 || a >= lat.dim[0] || j >= lat.dim[1] || k >= lat.dim[2])
            continue;
          auto idx = lat.index(a, j, k);
          if (lat.state[idx] & kAssigned) continue;
          lat.state[idx] = kAssigned;
          band.push_back(idx);
        }
  }
  std::sort(band.begin(), band.end());
  std::vector<ScanField::Estimate> est(band.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        est[i] = field.estimate(lat.point(band[i]), 2);
                    });
  std::size_t measured = 0;
  for (std::size_t i = 0; i < band.size(); ++i) {
    if (!est[i].found) {
      lat.state[band[i]] = 0;
      continue;
    }
    float d = est[i].distance == 0 ? 1e-6f * lat.h : est[i].distance;
    // The lattice's boundary (a cell beyond the points) is outside: a
    // parent reaching past it would give the empty region beyond a sign
    // change its children cannot carry.
    if (lat.on_border(band[i])) d = std::abs(d);
    lat.state[band[i]] = kExact | kAssigned | (d < 0 ? kInside : 0);
    lat.distance.push_back({band[i], d, kNone});
    ++measured;
  }
  stats.band_points = measured;
  // Every other point from what the lines of sight say (SightCarver):
  // empty or unseen is outside, occluded inside. No flood fill: a flood from
  // the carved space under the unseen bottom rose into the body (nearer to
  // it than the walls' band), hollowing it from below.
  SightCarver carver(scans, 2 * lat.h);
  std::vector<std::uint8_t> seen(lat.state.size(), 0);
  ProgressCounter layers(progress, "signs", static_cast<std::uint64_t>(lat.dim[2]), 1);
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, lat.dim[2]), [&](const auto& r) {
    for (std::int64_t k = r.begin(); k != r.end(); ++k)
      for (std::int64_t j = 0; j < lat.dim[1]; ++j)
        for (std::int64_t i = 0; i < lat.dim[0]; ++i) {
          auto idx = lat.index(i, j, k);
          if (lat.state[idx] & kAssigned) continue;
          seen[idx] = static_cast<std::uint8_t>(
              lat.on_border(idx) ? SightCarver::Seen::kEmpty : carver.seen_at(lat.point(idx)));
        }
    layers.add(static_cast<std::uint64_t>(r.size()));
  });
  for (std::size_t idx = 0; idx < seen.size(); ++idx) {
    if (lat.state[idx] & kAssigned) continue;
    const auto how = static_cast<SightCarver::Seen>(seen[idx]);
    lat.state[idx] = kAssigned | (how == SightCarver::Seen::kOccluded ? kInside : 0);
    stats.carved_points += how == SightCarver::Seen::kEmpty;
    stats.flooded_points += how != SightCarver::Seen::kEmpty;
  }
  // Voids inside the object and bubbles around stray points (sign_components.h).
  const SignCleanup cleanup =
      clean_scan_signs(lat.state, lat.dim, kInside, kMinScanPart, kMinScanPartFraction);
  stats.filled_voids = cleanup.filled_voids;
  stats.dropped_parts = cleanup.dropped_parts;
  stats.sign_flips = flip_lone_corners(lat);
  for (auto& e : lat.distance)  // a flipped point's distance keeps its magnitude
    if ((e.distance < 0) != lat.inside(e.idx)) e.distance = -e.distance;
  std::sort(lat.distance.begin(), lat.distance.end());
  return lat;
}

// Range scans: cells twice the median point spacing (Kim sec. 4.4: finer
// cells leave holes between the range points).
int scan_resolution(const std::vector<RangeScan>& scans, const Box3& bounds) {
  std::vector<float> spacing;
  for (const auto& s : scans)
    if (float d = s.spacing(); d > 0) spacing.push_back(d);
  if (spacing.empty()) return 64;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  Vec3 size = bounds.size();
  double extent = std::max({size.x, size.y, size.z});
  // Clamped before rounding: a stray point far from its row can make the
  // ratio huge.
  const double cells = extent / (2.0 * spacing[spacing.size() / 2]);
  return cells >= 2 ? static_cast<int>(std::lround(std::min(cells, 1000.0))) : 2;
}

}  // namespace lodforge::detail
