#include "lodforge/mesh/coordinate_range.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lodforge/core/error.h"

namespace lodforge {

void check_coordinate_range(const TriangleMesh& mesh, const std::string& name) {
  check_coordinate_range(mesh.positions, name);
}

void check_coordinate_range(std::span<const Vec3> points, const std::string& name) {
  if (points.empty()) return;
  const std::string range = fmt::format(
      "lodforge works with coordinates of magnitude at most {:g} and models at least {:g} "
      "across (rescale the model)",
      kMaxCoordinate, kMinExtent);
  float largest = 0;
  Box3 box;
  for (const Vec3& p : points) {
    if (!is_finite(p))
      throw DataError(
          fmt::format("{}: a vertex position is not finite ({} {} {})", name, p.x, p.y, p.z));
    largest = std::max({largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    box.add(p);
  }
  if (largest > kMaxCoordinate)
    throw DataError(fmt::format("{}: a coordinate of magnitude {:g}; {}", name, largest, range));
  const Vec3 size = box.size();
  const float extent = std::max({size.x, size.y, size.z});
  if (extent > 0 && extent < kMinExtent)
    throw DataError(fmt::format("{}: the model is only {:g} across; {}", name, extent, range));
}

}  // namespace lodforge
