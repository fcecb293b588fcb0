// Tessellation of the VRML 1.0 primitive shapes. Cube: 12 triangles with
// face normals; Sphere: UV sphere; Cone and Cylinder: side, and caps as the
// `parts` bit mask selects. All are centred at the origin, axis along +Y.
#include "lodforge/scene/tessellate_primitive.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lodforge/core/error.h"
#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

float float_field(const Node& n, std::string_view name) {
  const FieldValue* v = field_or_default(n, name);
  float f = (v && !v->floats.empty()) ? v->floats[0] : 0.f;
  if (!std::isfinite(f))
    throw DataError(fmt::format("line {}: {} field '{}' must be a finite size, got {}",
                                n.first_line, n.type, name, f));
  // A negative size draws the same surface (mirrored, as Coin does): take |f|.
  return std::fabs(f);
}

bool has_part(const Node& n, std::string_view part) {
  const FieldValue* v = field_or_default(n, "parts");
  if (!v) return true;
  for (const auto& s : v->strings)
    if (s == "ALL" || s == part) return true;
  return false;
}

// Point i of `seg` on the unit circle; i and i + seg give the same bits, so
// seams weld exactly, and there are no negative zeros.
Vec2 circle(int i, int seg) {
  int k = i % seg;
  if ((4 * k) % seg == 0) {  // quarter turns exactly, so poles and axes are exact
    const Vec2 quarter[4] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
    return quarter[(4 * k) / seg];
  }
  double a = 2 * kPi * k / seg;
  return {float(std::sin(a)) + 0.f, float(std::cos(a)) + 0.f};
}

class Builder {
 public:
  TriangleMesh mesh;
  std::uint32_t vertex(Vec3 p, Vec3 n, Vec2 uv) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(normalized(n));
    mesh.texcoords.push_back(uv);
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
  }
  void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh.triangles.push_back({a, b, c});
  }
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    tri(a, b, c);
    tri(a, c, d);
  }

  // A disc cap at height y facing `up` (+1 or -1).
  void cap(float y, float r, int seg, float up) {
    std::uint32_t center = vertex({0, y, 0}, {0, up, 0}, {0.5f, 0.5f});
    for (int i = 0; i <= seg; ++i) {
      auto [s, c] = circle(i, seg);
      std::uint32_t v = vertex({r * s + 0.f, y, r * c + 0.f}, {0, up, 0},
                               {0.5f + 0.5f * s, 0.5f - 0.5f * c * up});
      if (i == 0) continue;
      if (up > 0)
        tri(center, v - 1, v);
      else
        tri(center, v, v - 1);
    }
  }

  // Side of a frustum from radius r0 at y0 to r1 at y1.
  void side(float y0, float r0, float y1, float r1, int seg) {
    float h = y1 - y0;
    for (int i = 0; i <= seg; ++i) {
      auto [s, c] = circle(i, seg);
      Vec3 n{s * h, r0 - r1, c * h};
      float u = float(i) / float(seg);
      vertex({r0 * s + 0.f, y0, r0 * c + 0.f}, n, {u, 0});
      vertex({r1 * s + 0.f, y1, r1 * c + 0.f}, n, {u, 1});
    }
    std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size()) - 2 * (seg + 1);
    for (int i = 0; i < seg; ++i) {
      std::uint32_t a = base + 2 * i, b = a + 2, top_a = a + 1, top_b = a + 3;
      if (r1 == 0)
        tri(a, b, top_a);
      else if (r0 == 0)
        tri(a, top_b, top_a);
      else
        quad(a, b, top_b, top_a);
    }
  }
};

}  // namespace

int segments_for_complexity(float complexity) {
  const float c = std::isfinite(complexity) ? std::clamp(complexity, 0.f, 1.f) : 0.5f;
  return std::max(4, int(std::lround(48 * c)));
}

int segments_of(const TessellateOptions& options) {
  return options.segments > 0 ? std::max(options.segments, 3)
                              : segments_for_complexity(options.complexity);
}

TriangleMesh tessellate_primitive(const Node& node, const TessellateOptions& options) {
  int seg = segments_of(options);
  Builder b;
  const std::string& t = node.type;
  if (t == "Cube") {
    Vec3 h{float_field(node, "width") / 2, float_field(node, "height") / 2,
           float_field(node, "depth") / 2};
    auto scaled = [&](Vec3 v) { return Vec3{v.x * h.x, v.y * h.y, v.z * h.z}; };
    for (int axis = 0; axis < 3; ++axis) {
      for (float sign : {1.f, -1.f}) {
        Vec3 n{}, u{};
        n[axis] = sign;
        u[(axis + 1) % 3] = 1;
        Vec3 v = cross(n, u);  // u x v = n: counter-clockwise seen from outside
        Vec3 c = scaled(n), du = scaled(u), dv = scaled(v);
        std::uint32_t a = b.vertex(c - du - dv, n, {0, 0});
        std::uint32_t bb = b.vertex(c + du - dv, n, {1, 0});
        std::uint32_t cc = b.vertex(c + du + dv, n, {1, 1});
        std::uint32_t d = b.vertex(c - du + dv, n, {0, 1});
        b.quad(a, bb, cc, d);
      }
    }
    return b.mesh;
  }
  if (t == "Sphere") {
    float r = float_field(node, "radius");
    int rings = std::max(seg / 2, 2);
    for (int j = 0; j <= rings; ++j) {
      // Ring j at polar angle pi*j/rings, from the circle of 2*rings points.
      Vec2 ring = circle(j, 2 * rings);
      for (int i = 0; i <= seg; ++i) {
        auto [s, c] = circle(i, seg);
        Vec3 n{ring.x * s + 0.f, ring.y, ring.x * c + 0.f};
        b.vertex(n * r, n, {float(i) / float(seg), 1 - float(j) / float(rings)});
      }
    }
    auto at = [&](int j, int i) { return std::uint32_t(j * (seg + 1) + i); };
    for (int j = 0; j < rings; ++j)
      for (int i = 0; i < seg; ++i) {
        if (j > 0) b.tri(at(j, i), at(j + 1, i), at(j, i + 1));
        if (j < rings - 1) b.tri(at(j, i + 1), at(j + 1, i), at(j + 1, i + 1));
      }
    return b.mesh;
  }
  if (t == "Cone") {
    float r = float_field(node, "bottomRadius"), h = float_field(node, "height");
    if (has_part(node, "SIDES")) b.side(-h / 2, r, h / 2, 0, seg);
    if (has_part(node, "BOTTOM")) b.cap(-h / 2, r, seg, -1);
    return b.mesh;
  }
  if (t == "Cylinder") {
    float r = float_field(node, "radius"), h = float_field(node, "height");
    if (has_part(node, "SIDES")) b.side(-h / 2, r, h / 2, r, seg);
    if (has_part(node, "TOP")) b.cap(h / 2, r, seg, 1);
    if (has_part(node, "BOTTOM")) b.cap(-h / 2, r, seg, -1);
    return b.mesh;
  }
  throw DataError(fmt::format("line {}: {} is not a primitive shape", node.first_line, t));
}

}  // namespace lodforge::scene
