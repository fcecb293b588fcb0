// View-dependent extraction (Kim, "Level-of-detail mesh modeling using the
// marching cube octree": ch. 8 proposes extending the model to "simplify only
// the viewing area", ch. 7 claims O(log n) view dependency through the
// octree): the octree cut by the viewer's distance instead of one priority
// for the whole model, on the run-time model.
//
// The run-time model stores no tree: the nodes are recovered from it once.
// A cell's parent is the cell expanded at the priority of its group (the
// cells of group k are the children of the node of priority k); its level is
// its parent's plus one; a finest cell's coordinates are those of the lattice
// cube holding the centre of its triangles' box (its vertices are finest
// crossings, strictly inside its edges, and loop centroids of them, so the
// centre is strictly inside the cube), and a coarser cell's are its
// children's halved; each cell's neighbour tables are made from them once.
// The extraction then works on integers and arrays:
//
//   step                 | work per node
//   ---------------------+--------------------------------------------------
//   check a cell         | screen test (frustum planes, projected error),
//                        | then the crack rules of view_extract.h: 18
//                        | same-level neighbours read, priorities compared
//   expand a node        | its parent first, the neighbour rule's coarser
//                        | cells (a table), then its children and
//                        | neighbours are checked (again)
//   emit a cell          | N = largest priority among its parent and its
//                        | expanded neighbours; copy its interval at N
//
// Every step only adds expansions, so the checks reach a fixed point.
#include "lodforge/mcoctree/view_extract.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "lodforge/core/error.h"
#include "lodforge/metrics/closest_point_on_triangle.h"

namespace lodforge {
namespace {

constexpr std::uint32_t kNoCell = McNode::kNone;

// Offsets (dx, dy, dz) of the same-level neighbours sharing a face or an edge
// (those whose expansion splits one of a cell's faces or edges), first, then
// the corner neighbours (the neighbour rule reads all 26).
constexpr std::array<std::array<int, 3>, 26> kNear = [] {
  std::array<std::array<int, 3>, 26> out{};
  int k = 0;
  for (int moved = 1; moved <= 3; ++moved)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if ((dx != 0) + (dy != 0) + (dz != 0) == moved) out[k++] = {dx, dy, dz};
  return out;
}();
constexpr int kSplitting = 18;  // face and edge neighbours: kNear[0 .. 17]

std::uint64_t key(int level, std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return std::uint64_t(level) << 57 | x << 38 | y << 19 | z;
}

bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

// The camera's frame: the view direction, the four side planes' inward
// normals (the near plane is depth > 0) and the screen scale.
struct McViewExtractor::Frame {
  Vec3 eye, forward;
  std::array<Vec3, 4> sides;
  double scale = 0;  // pixels per model unit at depth 1

  explicit Frame(const McCamera& c) {
    if (!finite(c.position) || !finite(c.look_at) || !finite(c.up))
      throw DataError("view extraction: camera, look-at and up must be finite");
    if (!(c.fov > 0 && c.fov < std::numbers::pi))
      throw DataError("view extraction: the field of view must be in (0, pi) radians");
    if (!(c.pixels > 0) || !std::isfinite(c.pixels) || !(c.aspect > 0) || !std::isfinite(c.aspect))
      throw DataError("view extraction: pixels and aspect must be finite and > 0");
    const Vec3 view = c.look_at - c.position;
    if (!(length(view) > 0)) throw DataError("view extraction: look-at equals the camera position");
    eye = c.position;
    forward = normalized(view);
    const Vec3 side = cross(forward, c.up);
    if (!(length(side) > 1e-6f * length(c.up)))
      throw DataError("view extraction: up is zero or parallel to the view direction");
    const Vec3 right = normalized(side), up = cross(right, forward);
    const auto tv = static_cast<float>(std::tan(c.fov / 2));
    const auto th = static_cast<float>(tv * c.aspect);
    sides = {forward * tv - up, forward * tv + up, forward * th - right, forward * th + right};
    scale = c.pixels / (2 * double{tv});
  }
  // Whether the box centre +- half is at least partly in the frustum.
  bool sees(const Vec3& centre, const Vec3& half) const {
    auto reach = [&](const Vec3& n) {
      return dot(n, centre - eye) + std::abs(n.x) * half.x + std::abs(n.y) * half.y +
             std::abs(n.z) * half.z;
    };
    if (reach(forward) <= 0) return false;
    return std::all_of(sides.begin(), sides.end(), [&](const Vec3& n) { return reach(n) >= 0; });
  }
  // The smallest depth of the box along the view direction.
  float depth(const Vec3& centre, const Vec3& half) const {
    return dot(forward, centre - eye) - std::abs(forward.x) * half.x -
           std::abs(forward.y) * half.y - std::abs(forward.z) * half.z;
  }
};

McViewExtractor::McViewExtractor(const McLodModel& model) : model_(model), compactor_(model) {
  if (model.depth > kMaxDepth)
    throw DataError("view extraction: the model is deeper than " + std::to_string(kMaxDepth) +
                    " levels");
  prepare_tree();
  prepare_neighbours();
  index_ = {};  // the walk reads the neighbour tables
  prepare_errors();
}

// Parents, levels and coordinates of the cells (file comment), and the
// (level, coordinates) -> cell table.
void McViewExtractor::prepare_tree() {
  const McLodModel& m = model_;
  const auto cells = static_cast<std::uint32_t>(m.cell_count());
  const std::uint32_t L = m.priorities();
  parent_.assign(cells, kNoCell);
  level_.assign(cells, 0);
  coords_.assign(cells, {kNoCell, kNoCell, kNoCell});
  if (cells == 0) return;
  std::vector<std::uint32_t> owner(L + 1, kNoCell);  // owner[k] = the cell of priority k
  for (std::uint32_t c = 0; c < cells; ++c) {
    const std::uint32_t until = m.cells[c].until;
    if (until != McLodModel::kNever && until > L)
      throw DataError("view extraction needs the whole model (this one ends at priority " +
                      std::to_string(L) + ")");
    if (until != McLodModel::kNever) owner[until] = c;
  }
  for (std::uint32_t k = 1; k <= L; ++k)
    for (std::uint32_t c = m.group[k]; c < m.group[k + 1]; ++c) {
      if (owner[k] == kNoCell || owner[k] >= c)
        throw DataError("view extraction: cells do not nest");
      parent_[c] = owner[k];
      level_[c] = static_cast<std::uint8_t>(level_[owner[k]] + 1);
      if (level_[c] > m.depth) throw DataError("view extraction: cells do not nest");
    }
  // Finest cells from their triangles' boxes, then up the parents.
  for (std::uint32_t c = cells; c-- > 0;) {
    if (m.cells[c].until == McLodModel::kNever) {
      if (level_[c] != m.depth) throw DataError("view extraction: a leaf above the finest level");
      const std::uint32_t a = m.intervals[m.cells[c].first_interval].first_triangle;
      const std::uint32_t b = m.intervals[m.cells[c + 1].first_interval].first_triangle;
      if (a == b) continue;  // over a hole of an open model: unlocated
      Box3 box;
      for (std::uint32_t t = a; t < b; ++t)
        for (auto v : m.triangles[t]) box.add(m.positions[v]);
      const Vec3 centre = (box.lo + box.hi) * 0.5f;
      for (int k = 0; k < 3; ++k)
        coords_[c][k] = static_cast<std::uint32_t>(
            std::clamp(std::floor((centre[k] - m.origin[k]) / m.cell_size), 0.0f,
                       static_cast<float>((1u << m.depth) - 1)));
    }
    const std::uint32_t p = parent_[c];
    if (p == kNoCell || !located(c)) continue;
    const std::array<std::uint32_t, 3> up{coords_[c][0] >> 1, coords_[c][1] >> 1,
                                          coords_[c][2] >> 1};
    if (coords_[p][0] == kNoCell)
      coords_[p] = up;
    else if (coords_[p] != up)
      throw DataError("view extraction: cells do not nest");
  }
  index_.reserve(cells);
  for (std::uint32_t c = 0; c < cells; ++c)
    if (located(c) &&
        !index_.emplace(key(level_[c], coords_[c][0], coords_[c][1], coords_[c][2]), c).second)
      throw DataError("view extraction: two cells at one place");
}

// error_[c] (header comment): each finest cell's vertices against each
// ancestor's triangles of every interval.
void McViewExtractor::prepare_errors() {
  const McLodModel& m = model_;
  const auto cells = static_cast<std::uint32_t>(m.cell_count());
  const int D = m.depth;
  auto triangles_of = [&](std::uint32_t c) {
    return std::pair{m.intervals[m.cells[c].first_interval].first_triangle,
                     m.intervals[m.cells[c + 1].first_interval].first_triangle};
  };
  // far[leaf * D + level]: the leaf's vertices' distance to its ancestor at `level`.
  std::vector<std::uint32_t> leaves;
  for (std::uint32_t c = 0; c < cells; ++c)
    if (m.cells[c].until == McLodModel::kNever) leaves.push_back(c);
  std::vector<float> far(leaves.size() * static_cast<std::size_t>(D), 0.0f);
  tbb::parallel_for(std::size_t{0}, leaves.size(), [&](std::size_t i) {
    const auto [a, b] = triangles_of(leaves[i]);
    for (std::uint32_t x = parent_[leaves[i]]; x != kNoCell; x = parent_[x]) {
      float worst = 0;
      for (std::uint32_t j = m.cells[x].first_interval; j < m.cells[x + 1].first_interval; ++j) {
        const std::uint32_t ta = m.intervals[j].first_triangle,
                            tb = m.intervals[j + 1].first_triangle;
        if (ta == tb) continue;  // no triangles: the cube's diagonal below
        for (std::uint32_t t = a; t < b; ++t)
          for (auto v : m.triangles[t]) {
            float best = std::numeric_limits<float>::max();
            for (std::uint32_t u = ta; u < tb && best > 0; ++u) {
              const Triangle& f = m.triangles[u];
              best = std::min(best, closest_point_on_triangle(m.positions[v], m.positions[f[0]],
                                                              m.positions[f[1]], m.positions[f[2]])
                                        .distance_squared);
            }
            worst = std::max(worst, best);
          }
      }
      far[i * D + level_[x]] = std::sqrt(worst);
    }
  });
  // A point of a finest triangle is within its longest edge / sqrt(3) of one
  // of its vertices (the circumradius of an acute triangle, at most half
  // the longest edge otherwise), and the distance to a set is 1-Lipschitz:
  // the leaf's reach is added to its vertices' distances.
  error_.assign(cells, 0.0f);
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const auto [a, b] = triangles_of(leaves[i]);
    float reach = 0;
    for (std::uint32_t t = a; t < b; ++t) {
      const Triangle& f = m.triangles[t];
      for (int k = 0; k < 3; ++k)
        reach = std::max(reach, length(m.positions[f[k]] - m.positions[f[(k + 1) % 3]]));
    }
    reach /= std::sqrt(3.0f);
    for (std::uint32_t x = parent_[leaves[i]]; x != kNoCell; x = parent_[x])
      error_[x] = std::max(error_[x], far[i * D + level_[x]] + reach);
  }
  for (std::uint32_t x = 0; x < cells; ++x) {
    const auto [a, b] = triangles_of(x);
    if (a == b && m.cells[x].until != McLodModel::kNever)
      error_[x] = std::numeric_limits<float>::infinity();
  }
}

std::uint32_t McViewExtractor::find(int level, std::int64_t x, std::int64_t y,
                                    std::int64_t z) const {
  const std::int64_t size = std::int64_t{1} << level;
  if (x < 0 || y < 0 || z < 0 || x >= size || y >= size || z >= size) return kNoCell;
  auto it = index_.find(key(level, static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y),
                            static_cast<std::uint64_t>(z)));
  return it == index_.end() ? kNoCell : it->second;
}

// Per located cell, the neighbour tables the walk reads instead of looking
// cells up: its face and edge neighbours (kNear[0 .. 17], kNoCell where
// none), and the coarser cells the numbering's neighbour rule needs expanded
// before it (for each of the 26 positions around it, the finest cell
// coarser than it that holds the position; its parent included, duplicates
// dropped).
void McViewExtractor::prepare_neighbours() {
  const auto cells = static_cast<std::uint32_t>(model_.cell_count());
  near_.assign(static_cast<std::size_t>(kSplitting) * cells, kNoCell);
  needs_begin_.assign(cells + 1, 0);
  needs_.clear();
  for (std::uint32_t c = 0; c < cells; ++c) {
    needs_begin_[c] = static_cast<std::uint32_t>(needs_.size());
    if (!located(c)) continue;
    const int level = level_[c];
    const auto& q = coords_[c];
    for (int j = 0; j < 26; ++j) {
      const std::int64_t x = std::int64_t{q[0]} + kNear[j][0], y = std::int64_t{q[1]} + kNear[j][1],
                         z = std::int64_t{q[2]} + kNear[j][2];
      if (x < 0 || y < 0 || z < 0 || x >> level || y >> level || z >> level) continue;  // outside
      if (j < kSplitting) near_[kSplitting * std::size_t{c} + j] = find(level, x, y, z);
      for (int l = level - 1; l >= 0; --l)
        if (auto a = find(l, x >> (level - l), y >> (level - l), z >> (level - l)); a != kNoCell) {
          if (std::find(needs_.begin() + needs_begin_[c], needs_.end(), a) == needs_.end())
            needs_.push_back(a);
          break;
        }
    }
  }
  needs_begin_[cells] = static_cast<std::uint32_t>(needs_.size());
}

// Expands c after its parent and the coarser cells the neighbour rule needs
// expanded; its children and same-level neighbours are checked again.
void McViewExtractor::expand(std::uint32_t c, bool forced) {
  if (expanded_[c]) return;
  if (parent_[c] != kNoCell) expand(parent_[c], forced);
  for (std::uint32_t k = needs_begin_[c]; k < needs_begin_[c + 1]; ++k) expand(needs_[k], true);
  expanded_[c] = 1;
  expanded_list_.push_back(c);
  ++stats_->expanded;
  stats_->forced += forced;
  const std::uint32_t k = model_.cells[c].until;
  for (std::uint32_t child = model_.group[k]; child < model_.group[k + 1]; ++child)
    queue_.push_back(child);
  for (int j = 0; j < kSplitting; ++j)
    if (auto n = neighbour(c, j); n != kNoCell) queue_.push_back(n);
}

// The N whose split state is cell c's: the largest priority among its
// parent's and its expanded face and edge neighbours'.
std::uint32_t McViewExtractor::split_priority(std::uint32_t c) const {
  std::uint32_t N = parent_[c] == kNoCell ? 0 : model_.cells[parent_[c]].until;
  for (int j = 0; j < kSplitting; ++j)
    if (auto n = neighbour(c, j); n != kNoCell && expanded_[n])
      N = std::max(N, model_.cells[n].until);
  return N;
}

// Cell c's error bound projected on the screen (pixels; infinite when its
// cube reaches the camera plane), or -1 when c is outside the frustum: its
// cube grown by its error (which covers the surface under it) and a quarter
// of its size (which covers its placed vertices) is outside a plane.
double McViewExtractor::on_screen(std::uint32_t c, const Frame& frame) const {
  const float size = model_.cell_size * static_cast<float>(1u << (model_.depth - level_[c]));
  const Vec3 half{size / 2, size / 2, size / 2};
  const Vec3 centre =
      model_.origin +
      Vec3{float(coords_[c][0]), float(coords_[c][1]), float(coords_[c][2])} * size + half;
  const float margin = (std::isfinite(error_[c]) ? error_[c] : 0.0f) + size / 4;
  if (!frame.sees(centre, half + Vec3{margin, margin, margin})) return -1;
  if (error_[c] == 0) return 0;
  const double depth = frame.depth(centre, half);
  return depth <= 0 ? HUGE_VAL : error_[c] * frame.scale / depth;
}

// One cell of the cut (its parent expanded, itself not): the screen test,
// then the crack rules.
void McViewExtractor::check(std::uint32_t c, const Frame& frame, double pixel_error) {
  if (expanded_[c] || !located(c) || (parent_[c] != kNoCell && !expanded_[parent_[c]])) return;
  const std::uint32_t until = model_.cells[c].until;
  if (until != McLodModel::kNever && on_screen(c, frame) > pixel_error) return expand(c, false);
  const std::uint32_t N = split_priority(c);
  if (N > until) return expand(c, true);
  for (int j = 0; j < kSplitting; ++j)
    if (auto n = neighbour(c, j); n != kNoCell && !expanded_[n] && model_.cells[n].until < N)
      expand(n, true);
}

// Copies the triangles of every cell of the cut at its split state, and
// measures the projected error bounds of those in view.
void McViewExtractor::emit(const Frame& frame, McViewResult& result) {
  const McLodModel& m = model_;
  indices_.clear();
  auto take = [&](std::uint32_t c) {
    const std::uint32_t N = located(c) ? split_priority(c) : 0;
    std::uint32_t j = m.cells[c].first_interval;
    const std::uint32_t last = m.cells[c + 1].first_interval - 1;
    while (j < last && m.intervals[j + 1].from <= N) ++j;
    indices_.insert(indices_.end(), m.triangles.begin() + m.intervals[j].first_triangle,
                    m.triangles.begin() + m.intervals[j + 1].first_triangle);
    const double pixels = located(c) ? on_screen(c, frame) : 0;
    if (pixels < 0)
      result.culled += error_[c] > 0;
    else
      result.pixel_error = std::max(result.pixel_error, pixels);
  };
  if (!expanded_[0]) return take(0);
  for (auto x : expanded_list_) {
    const std::uint32_t k = m.cells[x].until;
    for (std::uint32_t c = m.group[k]; c < m.group[k + 1]; ++c)
      if (!expanded_[c]) take(c);
  }
}

McViewResult McViewExtractor::extract(const McViewOptions& options) {
  const Frame frame(options.camera);
  if (!(options.pixel_error > 0) || !std::isfinite(options.pixel_error))
    throw DataError("view extraction: the pixel error must be finite and > 0");
  McViewResult result;
  if (model_.cell_count() == 0) return result;
  stats_ = &result;
  expanded_.assign(model_.cell_count(), 0);
  expanded_list_.clear();
  queue_.assign(1, 0);
  // The queue grows while it is read: index, not iterators.
  for (std::size_t i = 0; i < queue_.size(); ++i) check(queue_[i], frame, options.pixel_error);
  emit(frame, result);
  compactor_.mesh_of(indices_, result.mesh);
  stats_ = nullptr;
  return result;
}

McViewResult extract_mc_view(const McLodModel& model, const McViewOptions& options) {
  McViewExtractor extractor(model);
  return extractor.extract(options);
}

}  // namespace lodforge
