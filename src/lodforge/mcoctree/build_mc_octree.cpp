// The marching-cube octree of a mesh or of range scans.
//
// Paper: S.-H. Kim, "Level-of-detail mesh modeling using the marching cube
// octree" (thesis; chapters 4-6): leaves are marching cubes (corner signs and
// edge ratios from signed distances), parents are made bottom-up by the
// four-case corner rule with re-scaled ratios, every node gets a priority by
// repeatedly expanding the expandable node of largest LOD metric, and the
// accumulation table maps priorities to triangle counts.
//
// This file is the driver: it checks the input, takes the corner signs from
// a sign source (mesh_signs.h for meshes, scan_signs.h for range scans),
// gives the surface points their normals and colours from the same source,
// and lets octree_builder.h make, clean and number the tree. All of it runs
// in a task arena of options.threads.
#include "lodforge/mcoctree/build_mc_octree.h"

#include <fmt/format.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/mesh_signs.h"
#include "lodforge/mcoctree/octree_builder.h"
#include "lodforge/mcoctree/scan_signs.h"
#include "lodforge/mesh/coordinate_range.h"
#include "lodforge/mesh/weld.h"

namespace lodforge {
namespace {

using detail::Gap;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A surface point more than kRimGap cells beyond an open rim is invented.
constexpr float kRimGap = 0.25f;

// Throws DataError for a resolution out of range.
void check_options(const McBuildOptions& options) {
  if (options.resolution != 0 && (options.resolution < 2 || options.resolution > 1000))
    throw DataError("mcoctree: resolution must be 0 or in 2..1000");
}

// Runs fn in a task arena of `threads` worker threads (0: all cores), so
// that the build's parallelism is its own and not the process's.
template <class Fn>
auto with_threads(int threads, Fn&& fn) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  return arena.execute(std::forward<Fn>(fn));
}

void check_build_budget(const Box3& box, int resolution, const McBuildOptions& options) {
  check_memory_budget(mc_build_bytes(box, resolution), options.max_memory,
                      fmt::format("mcoctree: the lattice at resolution {}", resolution),
                      "use a lower resolution");
}

// Throws DataError for what the mesh build cannot use: no triangles, a
// triangle index out of range, colours not one per vertex, coordinates
// outside check_coordinate_range's range.
void check_mesh(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) throw DataError("mcoctree: the mesh has no triangles");
  const std::size_t nv = mesh.positions.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (auto v : mesh.triangles[t])
      if (v >= nv)
        throw DataError(fmt::format(
            "mcoctree: the mesh: triangle {} has vertex index {} out of range ({} vertices)", t, v,
            nv));
  if (mesh.has_colors() && mesh.colors.size() != nv)
    throw DataError(
        fmt::format("mcoctree: the mesh: {} colours for {} vertices", mesh.colors.size(), nv));
  check_coordinate_range(mesh, "mcoctree: the mesh");
}

// The surface the signed distances measure: positions, triangles and
// colours of `mesh` welded (pseudo-normals need shared vertices: OBJ seams,
// STL soup), wound outwards. Inside is where the triangles face away from:
// a mesh wound inwards (negative signed volume: horse.ply) is turned round,
// or every sign would be the wrong way and the root cube's boundary,
// outside, would fight it.
TriangleMesh distance_surface(const TriangleMesh& mesh) {
  TriangleMesh source;
  source.positions = mesh.positions;
  source.triangles = mesh.triangles;
  source.colors = mesh.colors;
  TriangleMesh welded = weld(source).mesh;
  double volume = 0;
  for (const auto& f : welded.triangles)
    volume += dot(welded.positions[f[0]], cross(welded.positions[f[1]], welded.positions[f[2]]));
  if (volume < 0)
    for (auto& f : welded.triangles) std::swap(f[1], f[2]);
  if (welded.triangles.empty()) throw DataError("mcoctree: the mesh has only degenerate triangles");
  return welded;
}

// How far a surface point whose closest input point is cp lies from the
// input: the distance, over kRimGap when cp is on an open rim (a crossing of
// a true sign change lies within a cell edge of the surface; beyond a rim a
// quarter of that is already a cap).
Gap mesh_gap(const detail::SignedDistance& sd, const ClosestPoint& cp) {
  float d = std::sqrt(cp.distance_squared);
  bool rim = sd.feature(cp).second;
  return Gap{rim ? d / kRimGap : d, rim};
}

// A mesh's surface point x: its normal and colour from the nearer of the
// triangles closest to its edge's ends (the closest point, or near it, which
// is all a normal and a colour need), or from the exact closest point where
// there is none or where the distance may decide a hole (the nearer
// triangle's distance is an upper bound).
Gap mesh_edge_point(const detail::SignedDistance& sd, float h, bool holes, const Vec3& x,
                    std::uint32_t& hint, const std::array<std::uint32_t, 2>& near, Vec3& normal,
                    Rgb8* color) {
  ClosestPoint cp;
  for (auto t : near)
    if (t != kNone) {
      ClosestPoint c = sd.on_triangle(x, t);
      if (c.distance_squared < cp.distance_squared) cp = c;
    }
  const float sure = kRimGap * h;
  if (!cp.found() || (holes && (cp.distance_squared > sure * sure || sd.feature(cp).second)))
    cp = sd.bvh().closest_point_lowest_index(x, cp.found() ? cp.triangle : hint);
  hint = cp.triangle;
  normal = sd.normal_at(cp);
  if (color) {
    const auto& f = sd.mesh().triangles[cp.triangle];
    Vec3 col{};
    for (int k = 0; k < 3; ++k) col += sd.mesh().colors[f[k]] * cp.barycentric[k];
    for (int k = 0; k < 3; ++k)
      (*color)[k] = static_cast<std::uint8_t>(std::lround(std::clamp(col[k], 0.0f, 1.0f) * 255.0f));
  }
  return holes ? mesh_gap(sd, cp) : Gap{};
}

McBuildResult build_from_mesh(const TriangleMesh& mesh, const McBuildOptions& options) {
  McBuildResult result;
  auto t0 = Clock::now();
  const detail::SignedDistance sd(distance_surface(mesh));
  result.stats.resolution =
      options.resolution ? options.resolution : detail::mesh_resolution(sd.mesh());
  // An open mesh's repairs and holes need the hierarchy: build it on another
  // worker while the triangle scan runs. (Safe while TriangleBvh's build
  // runs no TBB tasks: a thread waiting inside it could steal a task that
  // calls bvh() and re-enter the call_once.)
  tbb::task_group hierarchy;
  if (sd.has_rims()) hierarchy.run([&] { sd.bvh(); });
  check_build_budget(sd.mesh().bounds(), result.stats.resolution, options);
  const detail::Lattice lat =
      detail::make_mesh_lattice(sd, result.stats.resolution, result.stats, options.progress);
  hierarchy.wait();
  result.stats.seconds_signs = since(t0);

  auto t1 = Clock::now();
  detail::OctreeBuilder builder(result.tree, result.stats, options.place_coarse_vertices,
                                options.progress);
  // Closed inputs invent nothing (every sign change is a crossing of the
  // surface); not testing them keeps them closed whatever the rounding.
  const bool holes = options.holes == McHoles::kOpen && sd.has_rims();
  builder.build_tree(lat, sd.mesh().has_colors(),
                     [&](const Vec3& x, std::uint32_t& hint,
                         const std::array<std::uint32_t, 2>& near, Vec3& normal, Rgb8* color) {
                       return mesh_edge_point(sd, lat.h, holes, x, hint, near, normal, color);
                     });
  result.stats.seconds_tree = since(t1);

  auto t2 = Clock::now();
  if (holes)
    builder.mark_holes(
        [&](const Vec3& x) { return mesh_gap(sd, sd.bvh().closest_point_lowest_index(x)).gap; });
  builder.number(options.metric);
  result.stats.seconds_priorities = since(t2);
  return result;
}

// A range scans' surface point x: the weighted normal and colour of the
// range points near it; a cap far from the data keeps the edge's direction.
Gap scan_edge_point(const detail::ScanField& field, const Vec3& x, Vec3& normal, Rgb8* color) {
  auto e = field.estimate(x, 2);
  if (!e.found) e = field.estimate(x, 4);
  if (!e.found) return Gap{};
  normal = e.normal;
  if (color)
    for (int k = 0; k < 3; ++k)
      (*color)[k] = static_cast<std::uint8_t>(std::lround(std::clamp(e.color[k], 0.0f, 255.0f)));
  return Gap{};
}

McBuildResult build_from_scans(const std::vector<RangeScan>& scans, const McBuildOptions& options) {
  McBuildResult result;
  auto t0 = Clock::now();
  detail::ScanField field(scans);
  result.stats.resolution =
      options.resolution ? options.resolution : detail::scan_resolution(scans, field.bounds());
  check_build_budget(field.bounds(), result.stats.resolution, options);
  const detail::Lattice lat = detail::make_scan_lattice(field, scans, result.stats.resolution,
                                                        result.stats, options.progress);
  result.stats.seconds_signs = since(t0);

  auto t1 = Clock::now();
  detail::OctreeBuilder builder(result.tree, result.stats, options.place_coarse_vertices,
                                options.progress);
  builder.build_tree(
      lat, field.colored(),
      [&](const Vec3& x, std::uint32_t&, const std::array<std::uint32_t, 2>&, Vec3& normal,
          Rgb8* color) { return scan_edge_point(field, x, normal, color); });
  result.stats.seconds_tree = since(t1);

  auto t2 = Clock::now();
  builder.number(options.metric);
  result.stats.seconds_priorities = since(t2);
  return result;
}

}  // namespace

double mc_build_bytes(const Box3& box, int resolution) {
  constexpr double kBytesPerPoint = 5;
  const Vec3 size = box.size();
  const double extent = std::max({size.x, size.y, size.z});
  if (!(extent > 0) || resolution <= 0) return 0;
  double points = 1;
  for (int a = 0; a < 3; ++a) points *= double(size[a]) / extent * resolution + 3;
  return kBytesPerPoint * points;
}

McBuildResult build_mc_octree(const TriangleMesh& mesh, const McBuildOptions& options) {
  check_options(options);
  check_mesh(mesh);
  return with_threads(options.threads, [&] { return build_from_mesh(mesh, options); });
}

McBuildResult build_mc_octree(const std::vector<RangeScan>& scans, const McBuildOptions& options) {
  check_options(options);
  if (scans.empty()) throw DataError("mcoctree: no range scans");
  for (const auto& s : scans) {
    std::vector<Vec3> world;
    world.reserve(s.points.size());
    for (const auto& p : s.points) world.push_back(s.to_world(p));
    check_coordinate_range(world, s.name);
  }
  return with_threads(options.threads, [&] { return build_from_scans(scans, options); });
}

std::size_t McOctree::memory_bytes() const {
  return positions.size() * sizeof(Vec3) + normals.size() * sizeof(Vec3) +
         colors.size() * sizeof(Rgb8) + nodes.size() * sizeof(McNode) +
         lod.size() * sizeof(std::uint32_t) + accumulated.size() * sizeof(std::uint64_t);
}

}  // namespace lodforge
