#include "lodforge/simplify/regions.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>

namespace lodforge::regions {

int part_count(std::size_t triangles) {
  return static_cast<int>(
      std::clamp<std::size_t>(std::bit_floor(triangles / kTrianglesPerPart), 2, kMaxParts));
}

std::vector<std::uint8_t> kd_partition(const std::vector<float>& centre,
                                       const std::vector<std::uint8_t>& use, int parts) {
  const std::size_t nf = use.size();
  std::vector<std::uint8_t> region(nf, 0);
  constexpr int kBins = 1024;
  for (int cells = 1; cells < parts; cells *= 2) {
    // Per cell: its box, then a histogram along its longest side.
    std::vector<std::array<float, 6>> box(
        cells, {FLT_MAX, FLT_MAX, FLT_MAX, -FLT_MAX, -FLT_MAX, -FLT_MAX});
    for (std::size_t t = 0; t < nf; ++t)
      if (use[t]) {
        auto& b = box[region[t]];
        for (int k = 0; k < 3; ++k) {
          b[k] = std::min(b[k], centre[3 * t + k]);
          b[3 + k] = std::max(b[3 + k], centre[3 * t + k]);
        }
      }
    std::vector<int> axis(cells);
    std::vector<float> lo(cells), to_bin(cells);
    for (int c = 0; c < cells; ++c) {
      const auto& b = box[c];
      int ax = 0;
      for (int k = 1; k < 3; ++k)
        if (b[3 + k] - b[k] > b[3 + ax] - b[ax]) ax = k;
      axis[c] = ax;
      lo[c] = b[ax];
      const float extent = b[3 + ax] - b[ax];
      to_bin[c] = extent > 0 ? (kBins - 1) / extent : 0.0f;
    }
    auto bin_of = [&](std::size_t t) {
      const int c = region[t];
      return std::clamp(int((centre[3 * t + axis[c]] - lo[c]) * to_bin[c]), 0, kBins - 1);
    };
    std::vector<std::size_t> hist(std::size_t(cells) * kBins, 0), total(cells, 0);
    for (std::size_t t = 0; t < nf; ++t)
      if (use[t]) {
        ++hist[std::size_t(region[t]) * kBins + bin_of(t)];
        ++total[region[t]];
      }
    std::vector<int> cut(cells, kBins);
    for (int c = 0; c < cells; ++c) {
      std::size_t sum = 0;
      for (int i = 0; i < kBins; ++i) {
        sum += hist[std::size_t(c) * kBins + i];
        if (2 * sum >= total[c]) {
          cut[c] = i;
          break;
        }
      }
    }
    // Cell c splits into 2c (bins up to the cut) and 2c + 1.
    for (std::size_t t = 0; t < nf; ++t)
      if (use[t]) {
        const int c = region[t];
        region[t] = static_cast<std::uint8_t>(2 * c + int{bin_of(t) > cut[c]});
      }
  }
  return region;
}

std::uint32_t next_limit(std::uint32_t limit, std::size_t remaining, std::size_t goal, int shift) {
  const std::uint32_t exponents = remaining > 8 * goal ? 4u : remaining > 2 * goal ? 2u : 1u;
  const std::uint32_t step = exponents << (23 + shift);
  return limit > 0xffffffffu - step ? 0xffffffffu : limit + step;
}

}  // namespace lodforge::regions
