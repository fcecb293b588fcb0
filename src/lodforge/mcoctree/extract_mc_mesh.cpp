// Extraction of a level of detail (Kim, "Level-of-detail mesh modeling using
// the marching cube octree", ch. 6.1-6.2): for N, walk the LOD array from N
// down to 1 and triangulate the children of each node that are not expanded
// themselves. The thesis marks nodes 'expanded' during the walk; a child is
// expanded exactly when its priority is <= N, so a comparison replaces the
// mark and nothing has to be reset between calls.
//
// The triangulation itself was done at compile time (mc_lod_model.cpp), per
// cell and per interval of constant neighbour split state; the children of
// the nodes of priority 1..N are stored one after another (grouped by their
// parent's priority), so the walk is a forward scan of a prefix of one array:
//
//   cell                        | action
//   ----------------------------+-------------------------------------------
//   until <= N (expanded)       | skip: its children are further on
//   otherwise                   | the last interval with from <= N: copy its
//                               | triangles (index triples) to the output
//
// The order differs from the thesis's N-down-to-1, which only matters for
// the order of the output triangles.
#include "lodforge/mcoctree/extract_mc_mesh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "lodforge/core/error.h"

namespace lodforge {
namespace {

std::uint32_t clamp_priority(const McLodModel& m, std::uint32_t priority) {
  return std::min(priority, m.priorities());
}

// The priority an options struct asks for.
McExtractResult resolve(const std::vector<std::uint64_t>& accumulated,
                        const McExtractOptions& options) {
  int set = (options.priority >= 0) + (options.triangles >= 0) + (options.percent >= 0);
  if (set > 1) throw DataError("mcoctree: set one of priority, triangles, percent");
  if (options.percent >= 0 && !std::isfinite(options.percent))
    throw DataError("mcoctree: percent must be finite");
  McExtractResult result;
  const auto max_priority =
      accumulated.empty() ? std::int64_t{0} : static_cast<std::int64_t>(accumulated.size() - 1);
  const std::uint64_t full = accumulated.empty() ? 0 : accumulated.back();
  if (options.priority >= 0) {
    result.clamped = options.priority > max_priority;
    result.priority = static_cast<std::uint32_t>(std::min(options.priority, max_priority));
  } else if (options.triangles >= 0 || options.percent >= 0) {
    double want = options.triangles >= 0 ? static_cast<double>(options.triangles)
                                         : options.percent / 100.0 * static_cast<double>(full);
    result.clamped = want > static_cast<double>(full) || (options.percent > 100);
    want = std::clamp(want, 0.0, static_cast<double>(full));
    result.requested = static_cast<std::uint64_t>(std::llround(want));
    result.priority = priority_for_triangles(accumulated, result.requested);
  } else {
    result.priority = static_cast<std::uint32_t>(max_priority);
  }
  return result;
}

}  // namespace

std::uint32_t priority_for_triangles(const std::vector<std::uint64_t>& accumulated,
                                     std::uint64_t triangles) {
  std::uint32_t best = 0;
  std::uint64_t best_diff = UINT64_MAX;
  for (std::size_t n = 0; n < accumulated.size(); ++n) {
    std::uint64_t a = accumulated[n];
    std::uint64_t diff = a > triangles ? a - triangles : triangles - a;
    if (diff < best_diff) best_diff = diff, best = static_cast<std::uint32_t>(n);
  }
  return best;
}

std::size_t extract_mc_indices(const McLodModel& m, std::uint32_t priority,
                               std::vector<Triangle>& out) {
  if (m.group.empty() || m.cells.empty()) {
    out.clear();
    return 0;
  }
  const std::uint32_t N = clamp_priority(m, priority);
  const auto count = static_cast<std::size_t>(m.accumulated[N]);
  // Room for one fixed-size block copy past the end.
  out.resize(count + McLodModel::kCopyBlock);
  Triangle* w = out.data();
  const McLodCell* cell = m.cells.data();
  const McLodInterval* iv = m.intervals.data();
  const Triangle* tri = m.triangles.data();
  const std::uint32_t end = m.group[N + 1];
  for (std::uint32_t c = 0; c < end; ++c) {
    if (cell[c].until <= N) continue;
    std::uint32_t j = cell[c].first_interval;
    const std::uint32_t last = cell[c + 1].first_interval - 1;
    while (j < last && iv[j + 1].from <= N) ++j;
    const std::uint32_t b = iv[j].first_triangle, n = iv[j + 1].first_triangle - b;
    // Most cells have 1 to 4 triangles: one fixed-size copy (the model and
    // the output are padded for it) instead of a variable-length one.
    if (n <= McLodModel::kCopyBlock)
      std::memcpy(static_cast<void*>(w), tri + b, McLodModel::kCopyBlock * sizeof(Triangle));
    else
      std::memcpy(static_cast<void*>(w), tri + b, n * sizeof(Triangle));
    w += n;
  }
  assert(static_cast<std::size_t>(w - out.data()) == count);
  out.resize(count);
  return count;
}

McExtractor::McExtractor(const McOctree& tree)
    : owned_(std::make_unique<const McLodModel>(compile_mc_lod(tree))), model_(owned_.get()) {}

McExtractor::McExtractor(const McLodModel& model) : model_(&model) {}

std::size_t McExtractor::extract(std::uint32_t priority, TriangleMesh& out) {
  extract_mc_indices(*model_, priority, indices_);
  return mesh_of(indices_, out);
}

std::size_t McExtractor::mesh_of(const std::vector<Triangle>& indices, TriangleMesh& out) {
  const McLodModel& m = *model_;
  out.positions.clear();
  out.normals.clear();
  out.colors.clear();
  out.triangles.clear();
  out.texcoords.clear();
  out.materials.clear();
  out.lines.clear();
  centroids_ = 0;
  if (seen_.size() != m.positions.size()) {
    seen_.assign(m.positions.size(), {0, 0});
    epoch_ = 0;
  }
  if (++epoch_ == 0) {
    std::fill(seen_.begin(), seen_.end(), Seen{0, 0});
    epoch_ = 1;
  }
  // Three passes without a data-dependent branch (a "first time seen?" test
  // per corner mispredicts about once a triangle): mark the used vertices,
  // number and copy them in table order (vertices are in order of first use,
  // so all used ones lie below the largest index, and the walk is
  // sequential), then renumber the triangles.
  Seen* seen = seen_.data();
  std::uint32_t end = 0;
  for (const auto& t : indices)
    for (auto v : t) {
      seen[v].epoch = epoch_;
      end = std::max(end, v + 1);
    }
  const bool colored = !m.colors.empty();
  const Vec3* positions = m.positions.data();
  const std::uint32_t* normals = m.normals.data();
  // One spare slot: an unused vertex writes to the slot of the next used one.
  out.positions.resize(end + 1);
  out.normals.resize(end + 1);
  if (colored) out.colors.resize(end + 1);
  std::uint32_t next = 0;
  for (std::uint32_t v = 0; v < end; ++v) {
    seen[v].index = next;
    out.positions[next] = positions[v];
    out.normals[next] = decode_normal(normals[v]);
    if (colored)
      out.colors[next] =
          Vec3{m.colors[v][0] / 255.0f, m.colors[v][1] / 255.0f, m.colors[v][2] / 255.0f};
    next += seen[v].epoch == epoch_;
  }
  out.positions.resize(next);
  out.normals.resize(next);
  if (colored) out.colors.resize(next);
  out.triangles.resize(indices.size());
  for (std::size_t i = 0; i < indices.size(); ++i)
    for (int k = 0; k < 3; ++k) out.triangles[i][k] = seen[indices[i][k]].index;
  for (auto v : m.centroids) centroids_ += seen_[v].epoch == epoch_;
  return out.triangles.size();
}

McExtractResult extract_mc_mesh(const McLodModel& model, const McExtractOptions& options) {
  McExtractResult result = resolve(model.accumulated, options);
  McExtractor extractor(model);
  extractor.extract(result.priority, result.mesh);
  result.centroid_vertices = extractor.centroid_vertices();
  return result;
}

McExtractResult extract_mc_mesh(const McOctree& tree, const McExtractOptions& options) {
  resolve(tree.accumulated, options);  // bad options throw before the compilation
  return extract_mc_mesh(compile_mc_lod(tree), options);
}

}  // namespace lodforge
