// libFuzzer target for the range-grid PLY reader and the octree of one scan:
// any input must give a scan or a lodforge::DataError, and a small scan that
// reads must build (or be refused with a DataError), never a crash, a hang
// or another exception. The build exercises the line-of-sight signs
// (carving and the scans' vote) and the coarse levels' placed vertices.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/range_scan.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  lodforge::RangeScan scan;
  try {
    scan = lodforge::read_range_grid_data(text, "fuzz.ply");
  } catch (const lodforge::DataError&) {
    return 0;
  }
  if (scan.grid.size() != static_cast<std::size_t>(scan.rows) * scan.cols) __builtin_trap();
  for (std::int32_t g : scan.grid)
    if (g < -1 || g >= static_cast<std::int64_t>(scan.points.size())) __builtin_trap();
  for (const auto& p : scan.points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) __builtin_trap();
  if (!scan.confidence.empty() && scan.confidence.size() != scan.points.size()) __builtin_trap();
  for (float c : scan.confidence)
    if (!(c >= 0 && std::isfinite(c))) __builtin_trap();
  // Small scans only: a build is milliseconds at resolution 12. A scan whose
  // extent is thousands of its point spacings (stray points far away) gets
  // line-of-sight images of up to 4096 x 4096 pixels: a fraction of a second
  // in a release build, tens of seconds instrumented, so not here.
  if (scan.points.size() > 4096 || scan.grid.size() > 16384) return 0;
  lodforge::Box3 box;
  for (const auto& p : scan.points) box.add(p);
  const float spacing = scan.spacing();
  if (!scan.points.empty() && !(std::max(box.size().x, box.size().y) <= 256 * spacing)) return 0;
  try {
    auto r = lodforge::build_mc_octree({scan}, {.resolution = 12, .threads = 1});
    auto m = lodforge::extract_mc_mesh(r.tree, {.percent = 50}).mesh;
    for (const auto& t : m.triangles)
      for (std::uint32_t v : t)
        if (v >= m.vertex_count()) __builtin_trap();
    for (const auto& p : m.positions)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) __builtin_trap();
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
