// Connected regions of the sign lattice by breadth-first labelling (one
// pass over the lattice, a queue of indices), then whole regions flipped.
// Used for range scans only: a mesh may have real internal cavities and
// separate small parts, which its exact signed distance already resolves.
#include "lodforge/mcoctree/sign_components.h"

#include <algorithm>
#include <cassert>
#include <limits>

namespace lodforge::detail {

SignCleanup clean_scan_signs(std::vector<std::uint8_t>& state,
                             const std::array<std::int64_t, 3>& dim, std::uint8_t inside_bit,
                             std::size_t min_part, double min_part_fraction) {
  const std::int64_t count = dim[0] * dim[1] * dim[2];
  assert(static_cast<std::int64_t>(state.size()) == count);
  assert(count < std::numeric_limits<std::uint32_t>::max());
  constexpr std::uint32_t kUnlabelled = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> label(static_cast<std::size_t>(count), kUnlabelled);
  struct Region {
    bool inside = false;
    bool border = false;  // reaches the lattice's border
    std::size_t points = 0;
  };
  std::vector<Region> regions;
  std::vector<std::uint32_t> queue;
  const std::int64_t plane = dim[0] * dim[1];
  for (std::int64_t seed = 0; seed < count; ++seed) {
    if (label[seed] != kUnlabelled) continue;
    const auto id = static_cast<std::uint32_t>(regions.size());
    Region r{.inside = (state[seed] & inside_bit) != 0};
    queue.assign(1, static_cast<std::uint32_t>(seed));
    label[seed] = id;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::int64_t idx = queue[head];
      const std::int64_t x = idx % dim[0], y = (idx / dim[0]) % dim[1], z = idx / plane;
      r.border |=
          x == 0 || y == 0 || z == 0 || x + 1 == dim[0] || y + 1 == dim[1] || z + 1 == dim[2];
      auto visit = [&](bool ok, std::int64_t q) {
        if (!ok || label[q] != kUnlabelled || ((state[q] & inside_bit) != 0) != r.inside) return;
        label[q] = id;
        queue.push_back(static_cast<std::uint32_t>(q));
      };
      visit(x > 0, idx - 1);
      visit(x + 1 < dim[0], idx + 1);
      visit(y > 0, idx - dim[0]);
      visit(y + 1 < dim[1], idx + dim[0]);
      visit(z > 0, idx - plane);
      visit(z + 1 < dim[2], idx + plane);
    }
    r.points = queue.size();
    regions.push_back(r);
  }
  std::size_t largest = 0;
  for (const Region& r : regions)
    if (r.inside) largest = std::max(largest, r.points);
  const auto keep = std::max(
      min_part, static_cast<std::size_t>(min_part_fraction * static_cast<double>(largest)));
  SignCleanup out;
  std::vector<std::uint8_t> flip(regions.size(), 0);
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const Region& r = regions[i];
    if (!r.inside && !r.border) {
      flip[i] = 1, ++out.filled_voids, out.filled_points += r.points;
    } else if (r.inside && r.points < keep) {
      flip[i] = 1, ++out.dropped_parts, out.dropped_points += r.points;
    }
  }
  if (out.filled_voids + out.dropped_parts == 0) return out;
  for (std::int64_t idx = 0; idx < count; ++idx)
    if (flip[label[idx]]) state[idx] ^= inside_bit;
  return out;
}

}  // namespace lodforge::detail
