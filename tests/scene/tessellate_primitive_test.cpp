// Primitive tessellation: closed, outward-facing, the right size.
#include "lodforge/scene/tessellate_primitive.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lodforge/core/error.h"
#include "lodforge/mesh/weld.h"

namespace lodforge::scene {
namespace {

Node node(std::string type) {
  return Node{.type = std::move(type)};
}

// Signed volume (divergence theorem): positive when triangles face outwards.
double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    v += dot(a, cross(b, c)) / 6.0;
  }
  return v;
}

TEST(TessellatePrimitive, CubeIsTwelveOutwardTrianglesOfTheRightVolume) {
  Node cube = node("Cube");
  cube.set("width", make_float(4));
  TriangleMesh m = tessellate_primitive(cube);
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_NEAR(signed_volume(m), 4.0 * 2 * 2, 1e-4);
  Box3 b = m.bounds();
  EXPECT_EQ(b.lo, (Vec3{-2, -1, -1}));
  EXPECT_EQ(b.hi, (Vec3{2, 1, 1}));
}

TEST(TessellatePrimitive, SphereConvergesToTheBallVolume) {
  Node s = node("Sphere");
  s.set("radius", make_float(2));
  double exact = 4.0 / 3.0 * kPi * 8;
  double coarse = signed_volume(tessellate_primitive(s, {.segments = 8}));
  double fine = signed_volume(tessellate_primitive(s, {.segments = 64}));
  EXPECT_GT(coarse, 0);
  EXPECT_LT(coarse, fine);
  EXPECT_NEAR(fine, exact, exact * 0.01);
}

TEST(TessellatePrimitive, SphereCylinderAndConeAreClosedAndOutward) {
  for (const char* type : {"Cylinder", "Cone", "Sphere"}) {
    Node n = node(type);
    TriangleMesh m = tessellate_primitive(n, {.segments = 96});
    double exact = std::string(type) == "Cylinder" ? kPi * 1 * 2
                   : std::string(type) == "Cone"   ? kPi * 2 / 3
                                                   : 4 * kPi / 3;
    EXPECT_NEAR(signed_volume(m), exact, exact * 0.01) << type;
    // Welded, every edge has exactly two triangles: a closed surface.
    WeldResult w = weld(m);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const auto& t : w.mesh.triangles)
      for (int i = 0; i < 3; ++i) {
        auto a = t[i], b = t[(i + 1) % 3];
        ++edges[{std::min(a, b), std::max(a, b)}];
      }
    for (const auto& [e, count] : edges) EXPECT_EQ(count, 2) << type;
  }
}

TEST(TessellatePrimitive, PartsSelectSidesAndCaps) {
  Node cyl = node("Cylinder");
  FieldValue parts;
  parts.type = {FieldKind::kBitMask, false};
  parts.strings = {"SIDES"};
  cyl.set("parts", parts);
  TriangleMesh sides = tessellate_primitive(cyl, {.segments = 10});
  EXPECT_EQ(sides.triangle_count(), 20u);
  parts.strings = {"TOP", "BOTTOM"};
  cyl.set("parts", parts);
  EXPECT_EQ(tessellate_primitive(cyl, {.segments = 10}).triangle_count(), 20u);
}

TEST(TessellatePrimitive, NegativeSizeIsItsAbsoluteValueAndNanIsAnError) {
  Node s = node("Sphere");
  s.first_line = 7;
  s.set("radius", make_float(-2));
  EXPECT_FLOAT_EQ(tessellate_primitive(s).bounds().hi.y, 2.f);
  s.set("radius", make_float(std::nanf("")));
  try {
    tessellate_primitive(s);
    FAIL();
  } catch (const DataError& e) {
    EXPECT_STREQ(e.what(), "line 7: Sphere field 'radius' must be a finite size, got nan");
  }
}

}  // namespace
}  // namespace lodforge::scene
