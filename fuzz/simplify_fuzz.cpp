// libFuzzer target for the three simplifiers (quadric collapse and its chain,
// vertex clustering, vertex decimation and its chain) on small random meshes:
// triangle soups with duplicate and coincident vertices, degenerate and
// repeated triangles, non-manifold edges, line segments, attribute seams and
// materials. Every result must keep the SimplifyResult invariants below, and
// vertex decimation must not depend on the model's unit (power-of-two scaled
// copies); a violation traps. lodforge::DataError is an allowed answer.
//
// Input bytes:
//
// | bytes        | meaning                                                      |
// |--------------|--------------------------------------------------------------|
// | 0            | flags: 1 materials, 2 colours, 4 texcoords, 8 normals,       |
// |              | 16 lines, 32 qem lock_border, 64 decimation keeps features,  |
// |              | 128 decimation by distance                                   |
// | 1            | bits 0-1: scale (1e-3, 1, 1e3, 1e-6); bit 2: 2 bytes per     |
// |              | coordinate (else 1: a 16^3 grid, many coincident points);    |
// |              | bits 3-7: vertex clustering min_diff / 32                    |
// | 2            | vertex count - 3 (3..66)                                     |
// | 3            | target parameter (triangle count, ratio, error budget)       |
// | then         | 3 coordinates per vertex                                     |
// | rest         | 3 bytes per triangle (index = byte mod #V), at most 1024;    |
// |              | with the lines flag every 5th becomes a segment              |
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/simplify/quadric_collapse.h"
#include "lodforge/simplify/vertex_clustering.h"
#include "lodforge/simplify/vertex_decimation.h"

namespace {

using namespace lodforge;

void check(bool ok) {
  if (!ok) __builtin_trap();
}

/// Reads bytes from the input, then zeros.
struct Bytes {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t pos = 0;
  std::uint8_t next() { return pos < size ? data[pos++] : 0; }
  bool done() const { return pos >= size; }
};

TriangleMesh mesh_from(Bytes& in, std::uint8_t flags, std::uint8_t mode) {
  static constexpr float kScales[] = {1e-3f, 1.0f, 1e3f, 1e-6f};
  const float scale = kScales[mode & 3];
  const bool wide = mode & 4;
  const int nv = 3 + in.next() % 64;
  TriangleMesh m;
  for (int i = 0; i < nv; ++i) {
    Vec3 p;
    for (float* c : {&p.x, &p.y, &p.z}) {
      if (wide) {
        auto v = std::int16_t(std::uint16_t(in.next() | (in.next() << 8)));
        *c = float(v) / 256.0f * scale;
      } else {
        *c = float(in.next() % 16) * scale;
      }
    }
    m.positions.push_back(p);
  }
  std::size_t index = 0;
  while (!in.done() && m.triangles.size() < 1024) {
    Triangle t{std::uint32_t(in.next() % nv), std::uint32_t(in.next() % nv),
               std::uint32_t(in.next() % nv)};
    if ((flags & 16) && index++ % 5 == 4)
      m.lines.push_back({t[0], t[1]});
    else
      m.triangles.push_back(t);
  }
  // Attributes vary by vertex index, so that coincident vertices make seams.
  for (int i = 0; i < nv; ++i) {
    if (flags & 2) m.colors.push_back({float(i % 3) / 2, float(i % 5) / 4, 0.5f});
    if (flags & 4) m.texcoords.push_back({float(i % 4) / 4, float(i % 7) / 7});
    if (flags & 8) {
      static constexpr Vec3 kNormals[] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}};
      m.normals.push_back(kNormals[i % 4]);
    }
  }
  if (flags & 1)
    for (std::size_t f = 0; f < m.triangles.size(); ++f) m.materials.push_back(f % 3 == 0 ? 1 : 0);
  return m;
}

/// The invariants of every SimplifyResult against its input.
void check_result(const TriangleMesh& input, const SimplifyResult& r, std::size_t count_target) {
  const TriangleMesh& m = r.mesh;
  const std::size_t nv = m.vertex_count();
  check(m.triangle_count() <= input.triangle_count());
  for (const Triangle& t : m.triangles) {
    for (std::uint32_t v : t) check(v < nv);
    check(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
  }
  for (const Segment& s : m.lines)
    for (std::uint32_t v : s) check(v < nv);
  check(r.vertex_map.size() == nv);
  for (std::uint32_t v : r.vertex_map) check(v < input.vertex_count());
  check(r.face_map.size() == m.triangle_count());
  for (std::uint32_t f : r.face_map) check(f < input.triangle_count());
  for (const Vec3& p : m.positions)
    check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  check(m.normals.empty() || m.normals.size() == nv);
  check(m.texcoords.empty() || m.texcoords.size() == nv);
  check(m.colors.empty() || m.colors.size() == nv);
  check(m.materials.empty() || m.materials.size() == m.triangle_count());
  check(r.error >= 0 && std::isfinite(r.error));
  if (count_target > 0 && r.stop_reason == StopReason::kTargetReached)
    check(m.triangle_count() <= count_target);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return 0;
  Bytes in{data, size};
  const std::uint8_t flags = in.next();
  const std::uint8_t mode = in.next();
  TriangleMesh mesh = mesh_from(in, flags, mode);
  const std::size_t nf = mesh.triangle_count();
  const std::uint8_t param = data[3];
  // A few targets: a count, a ratio, an error budget alone, both, and "all the way".
  const float extent = (mode & 4) ? 128.0f : 16.0f;
  const float scale = (mode & 3) == 0   ? 1e-3f
                      : (mode & 3) == 1 ? 1
                      : (mode & 3) == 2 ? 1e3f
                                        : 1e-6f;
  const std::vector<SimplifyTarget> targets = {
      {.triangles = 1 + std::size_t(param) % (nf + 1)},
      {.ratio = float(param) / 255.0f},
      {.max_error = float(param) / 255.0f * extent * scale},
      {.triangles = 1, .max_error = float(param) / 1024.0f * extent * scale},
      {.triangles = 1},
  };
  try {
    for (const SimplifyTarget& target : targets) {
      const std::size_t count =
          (target.triangles > 0 || target.ratio > 0) ? target.triangle_target(nf) : 0;
      check_result(
          mesh, quadric_collapse(mesh, {.target = target, .lock_border = bool(flags & 32)}), count);
      VertexDecimationOptions d{.target = target,
                                .preserve_feature_edges = bool(flags & 64),
                                .priority = (flags & 128) ? DecimationPriority::kDistance
                                                          : DecimationPriority::kErrorVolume};
      check_result(mesh, vertex_decimation(mesh, d), count);
      for (const SimplifyResult& r : vertex_decimation_chain(mesh, d)) check_result(mesh, r, 0);
      std::vector<SimplifyResult> chain =
          vertex_clustering(mesh, {.min_diff = float(mode >> 3) / 32.0f, .target = target});
      check(!chain.empty());
      for (const SimplifyResult& r : chain) check_result(mesh, r, 0);
      check_result(mesh, chain.back(), count);
    }
    std::vector<SimplifyResult> levels = quadric_collapse_chain(
        mesh, {},
        {std::max<std::size_t>(nf * 3 / 4, 1), std::max<std::size_t>(nf / 2, 1),
         std::max<std::size_t>(nf / 4, 1), 1});
    check(levels.size() == 4);
    for (std::size_t i = 0; i < levels.size(); ++i) {
      check_result(mesh, levels[i], 0);
      if (i > 0) check(levels[i].mesh.triangle_count() <= levels[i - 1].mesh.triangle_count());
    }
    // Decimation's decisions do not depend on the model's unit: a copy scaled
    // by 2^40 or 2^-40 (exact in float) gives the same triangles and exactly
    // the scaled error (it did nothing at all at such scales before its
    // criteria were computed in normalised units).
    for (int e : {40, -40}) {
      TriangleMesh scaled = mesh;
      for (Vec3& p : scaled.positions) p = p * std::ldexp(1.0f, e);
      const VertexDecimationOptions d{.target = targets[0]};
      const SimplifyResult a = vertex_decimation(mesh, d);
      const SimplifyResult b = vertex_decimation(scaled, d);
      check(a.mesh.triangles == b.mesh.triangles);
      check(b.error == std::ldexp(a.error, e));
    }
  } catch (const DataError&) {
  }
  return 0;
}
