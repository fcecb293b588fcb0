// Writes a large closed mesh as a binary little-endian PLY: a torus with a
// bumpy tube, tessellated into a grid of U x V quads (2 U V triangles,
// U V vertices, no seam). The input of the out-of-core tests and benchmark:
// its size is chosen on the command line, and it is written in one pass
// with constant memory, so it can be far larger than what reads it may use.
//
//   make_big_ply OUT.ply TRIANGLES
//
// The triangle count is rounded up to an even grid; the torus has radii
// 1 and 0.4 and a relief of 5 % of the tube radius, so the surface has
// curvature at every scale a simplifier keeps.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

template <class T>
void put(std::vector<char>& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}

bool flush(std::FILE* f, std::vector<char>& out) {
  const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
  out.clear();
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_big_ply OUT.ply TRIANGLES\n");
    return 2;
  }
  const double want = std::strtod(argv[2], nullptr);
  if (!(want >= 8) || want > 4e9) {
    std::fprintf(stderr, "make_big_ply: TRIANGLES must be in [8, 4e9]\n");
    return 2;
  }
  // U quads around the ring, V around the tube: U = 2.5 V (the radii's ratio).
  const auto v_count = static_cast<std::uint64_t>(std::max(2.0, std::round(std::sqrt(want / 5))));
  const auto u_count = static_cast<std::uint64_t>(std::ceil(want / 2 / double(v_count)));
  std::FILE* f = std::fopen(argv[1], "wb");
  if (!f) {
    std::perror(argv[1]);
    return 1;
  }
  std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment bumpy torus by make_big_ply\n"
      "element vertex " +
      std::to_string(u_count * v_count) +
      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
      std::to_string(2 * u_count * v_count) +
      "\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<char> out(header.begin(), header.end());
  bool ok = true;
  for (std::uint64_t i = 0; i < u_count; ++i) {
    const double u = 2 * kPi * double(i) / double(u_count);
    for (std::uint64_t j = 0; j < v_count; ++j) {
      const double v = 2 * kPi * double(j) / double(v_count);
      const double relief = 0.05 * std::sin(7 * u) * std::sin(5 * v) +
                            0.02 * std::sin(41 * u + 3 * v) * std::cos(23 * v);
      const double r = 0.4 * (1 + relief);
      put(out, static_cast<float>((1 + r * std::cos(v)) * std::cos(u)));
      put(out, static_cast<float>((1 + r * std::cos(v)) * std::sin(u)));
      put(out, static_cast<float>(r * std::sin(v)));
    }
    if (out.size() > (1u << 22)) ok &= flush(f, out);
  }
  for (std::uint64_t i = 0; i < u_count; ++i) {
    const std::uint64_t i1 = (i + 1) % u_count;
    for (std::uint64_t j = 0; j < v_count; ++j) {
      const std::uint64_t j1 = (j + 1) % v_count;
      const auto a = static_cast<std::int32_t>(i * v_count + j);
      const auto b = static_cast<std::int32_t>(i1 * v_count + j);
      const auto c = static_cast<std::int32_t>(i1 * v_count + j1);
      const auto d = static_cast<std::int32_t>(i * v_count + j1);
      put(out, std::uint8_t{3}), put(out, a), put(out, b), put(out, c);
      put(out, std::uint8_t{3}), put(out, a), put(out, c), put(out, d);
    }
    if (out.size() > (1u << 22)) ok &= flush(f, out);
  }
  ok &= flush(f, out);
  ok &= std::fclose(f) == 0;
  if (!ok) {
    std::fprintf(stderr, "make_big_ply: cannot write %s\n", argv[1]);
    return 1;
  }
  std::printf("%s: %llu vertices, %llu triangles\n", argv[1],
              static_cast<unsigned long long>(u_count * v_count),
              static_cast<unsigned long long>(2 * u_count * v_count));
  return 0;
}
