#include "lodforge/mcoctree/sign_lattice.h"

#include <cmath>

#include "lodforge/core/error.h"

namespace lodforge::detail {

Lattice empty_lattice(const Box3& box, int resolution) {
  Vec3 size = box.size();
  float extent = std::max({size.x, size.y, size.z});
  if (!(extent > 0)) throw DataError("mcoctree: all vertices of the mesh are at one point");
  Lattice lat;
  lat.depth = 1;
  while ((1 << lat.depth) < resolution + 2) ++lat.depth;
  lat.h = extent / static_cast<float>(resolution);
  const std::int64_t side = std::int64_t{1} << lat.depth;
  lat.root = box.center() - Vec3{1, 1, 1} * (lat.h * static_cast<float>(side) * 0.5f);
  for (int a = 0; a < 3; ++a) {
    auto lo = static_cast<std::int64_t>(std::floor((box.lo[a] - lat.root[a]) / lat.h)) - 1;
    auto hi = static_cast<std::int64_t>(std::ceil((box.hi[a] - lat.root[a]) / lat.h)) + 1;
    lat.offset[a] = std::max<std::int64_t>(0, lo);
    lat.dim[a] = std::min(side, hi) - lat.offset[a] + 1;
  }
  lat.origin = lat.point(0);
  lat.state.assign(static_cast<std::size_t>(lat.plane() * lat.dim[2]), 0);
  return lat;
}

}  // namespace lodforge::detail
