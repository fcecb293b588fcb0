#include "lodforge/core/morton.h"

#include <algorithm>

#include "lodforge/core/radix_sort.h"

namespace lodforge {

std::vector<std::uint64_t> morton_sorted_keys(std::span<const Vec3> points) {
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  const Vec3 size = box.size();
  const auto n = std::uint32_t(points.size());
  std::vector<std::uint64_t> keyed(n), scratch(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint32_t q[3];
    for (int a = 0; a < 3; ++a) {
      const float u = size[a] > 0 ? (points[i][a] - box.lo[a]) / size[a] : 0.f;
      q[a] = std::uint32_t(std::clamp(u * 1023.f, 0.f, 1023.f));
    }
    keyed[i] = morton_code(q[0], q[1], q[2]) << 32 | i;
  }
  radix_sort(keyed, scratch, 32, 62);
  return keyed;
}

}  // namespace lodforge
