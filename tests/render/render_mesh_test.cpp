#include "lodforge/render/render_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/render/texture_image.h"
#include "lodforge/render/write_png.h"
#include "mesh/test_meshes.h"
#include "render/pixel_checks.h"

namespace lodforge {
namespace {

using test::make_centered_cube;
using test::make_seamed_sphere;
using test::pixel_stats;
using test::with_color;

TEST(RenderMesh, CubeIsLitAndNotBlank) {
  const RenderResult r = render_mesh(make_centered_cube(), {.width = 200, .height = 150});
  write_png(r.image, test::output_dir() + "/cube.png");
  ASSERT_EQ(r.image.width, 200);
  ASSERT_EQ(r.image.height, 150);
  EXPECT_EQ(r.triangles_drawn, 12u);
  const auto s = pixel_stats(r.image);
  EXPECT_GT(s.covered_fraction, 0.15);
  EXPECT_LT(s.covered_fraction, 0.8);
  // Three visible faces lit differently, plus antialiased edges.
  EXPECT_GE(s.distinct_colors, 4u);
}

TEST(RenderMesh, SphereIsCentredAndFillsTheView) {
  const RenderResult r = render_mesh(make_seamed_sphere(), {.width = 160, .height = 160});
  write_png(r.image, test::output_dir() + "/sphere.png");
  const auto s = pixel_stats(r.image);
  // The framed sphere (4 % margin) is a disc of diameter ~0.96 of the picture.
  EXPECT_GT(s.covered_fraction, 0.55);
  EXPECT_LT(s.covered_fraction, 0.78);
  EXPECT_NEAR(s.center_x, 80, 2);
  EXPECT_NEAR(s.center_y, 80, 2);
  EXPECT_GE(s.distinct_colors, 20u);  // smooth shading gives a gradient
}

TEST(RenderMesh, LightComesFromAboveSoTopIsBrighter) {
  const Image img =
      render_mesh(make_seamed_sphere(), {.width = 100, .height = 100, .elevation = 0}).image;
  const auto top = pixel_stats(img, 0, 0, 100, 50);
  const auto bottom = pixel_stats(img, 0, 50, 100, 50);
  EXPECT_GT(top.mean_r + top.mean_g + top.mean_b, bottom.mean_r + bottom.mean_g + bottom.mean_b);
}

TEST(RenderMesh, PictureIsNotUpsideDownNorMirrored) {
  // +Y red, -Y blue; at azimuth 0 also +X must appear on the right.
  TriangleMesh m = make_seamed_sphere();
  for (const auto& p : m.positions)
    m.colors.push_back(p.y > 0 ? Vec3{1, 0, 0} : (p.x > 0 ? Vec3{0, 1, 0} : Vec3{0, 0, 1}));
  const Image img =
      render_mesh(m, {.width = 100, .height = 100, .azimuth = 0, .elevation = 0}).image;
  write_png(img, test::output_dir() + "/orientation.png");
  const auto top = pixel_stats(img, 0, 0, 100, 40);
  EXPECT_GT(top.mean_r, 3 * (top.mean_g + top.mean_b) / 2);
  const auto bottom_right = pixel_stats(img, 55, 60, 45, 40);
  EXPECT_GT(bottom_right.mean_g, 2 * bottom_right.mean_b);
  const auto bottom_left = pixel_stats(img, 0, 60, 45, 40);
  EXPECT_GT(bottom_left.mean_b, 2 * bottom_left.mean_g);

  // Azimuth 90: the camera is on +X, so -Z is on the right.
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    m.colors[i] = m.positions[i].z < 0 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  const Image side =
      render_mesh(m, {.width = 100, .height = 100, .azimuth = 90, .elevation = 0}).image;
  const auto right = pixel_stats(side, 60, 0, 40, 100);
  EXPECT_GT(right.mean_r, 2 * right.mean_b);
}

TEST(RenderMesh, VertexColoursShow) {
  const Image img =
      render_mesh(with_color(make_centered_cube(), {1, 0, 0}), {.width = 120, .height = 120}).image;
  write_png(img, test::output_dir() + "/red_cube.png");
  const auto s = pixel_stats(img);
  EXPECT_GT(s.covered_fraction, 0.1);
  EXPECT_GT(s.mean_r, 2 * s.mean_g);
  EXPECT_GT(s.mean_r, 2 * s.mean_b);
}

TEST(RenderMesh, NoColoursIgnoresVertexColours) {
  const Image img = render_mesh(with_color(make_centered_cube(), {1, 0, 0}),
                                {.width = 120, .height = 120, .use_colors = false})
                        .image;
  const auto s = pixel_stats(img);
  EXPECT_NEAR(s.mean_r, s.mean_b, 30);
}

TEST(RenderMesh, DifferentMeshesAndViewsGiveDifferentPictures) {
  const RenderOptions o{.width = 120, .height = 90};
  const Image a = render_mesh(make_centered_cube(), o).image;
  const Image b = render_mesh(make_seamed_sphere(), o).image;
  RenderOptions other_view = o;
  other_view.azimuth = 75;
  other_view.elevation = -30;
  const Image c = render_mesh(make_centered_cube(), other_view).image;
  EXPECT_GT(test::difference_fraction(a, b), 0.05);
  EXPECT_GT(test::difference_fraction(a, c), 0.05);
  // Deterministic: the same input gives the same picture.
  EXPECT_EQ(render_mesh(make_centered_cube(), o).image.pixels, a.pixels);
}

TEST(RenderMesh, FlatAndSmoothShadingDiffer) {
  const TriangleMesh coarse = make_seamed_sphere(1, 6, 12);
  const Image smooth = render_mesh(coarse, {.width = 100, .height = 100}).image;
  const Image flat =
      render_mesh(coarse, {.width = 100, .height = 100, .shading = Shading::kFlat}).image;
  write_png(flat, test::output_dir() + "/flat_sphere.png");
  EXPECT_GT(test::difference_fraction(smooth, flat), 0.1);
  // Flat shading: few distinct colours inside the faces, far more when smooth.
  EXPECT_LT(pixel_stats(flat).distinct_colors, pixel_stats(smooth).distinct_colors);
}

TEST(RenderMesh, GivenNormalsAreUsed) {
  TriangleMesh m = make_seamed_sphere(1, 8, 16);
  const Image computed = render_mesh(m, {.width = 80, .height = 80}).image;
  m.normals.assign(m.positions.size(), Vec3{0, 0, 1});  // all facing the default camera
  const Image given = render_mesh(m, {.width = 80, .height = 80}).image;
  EXPECT_GT(test::difference_fraction(computed, given), 0.1);
}

TEST(RenderMesh, ComputedNormalsAreSmoothAcrossRepeatedVertices) {
  const RenderOptions o{.width = 100, .height = 100};
  const Image indexed = render_mesh(make_seamed_sphere(), o).image;
  const Image triangle_soup = render_mesh(test::as_soup(make_seamed_sphere()), o).image;
  EXPECT_LT(test::difference_fraction(indexed, triangle_soup), 0.01);
  // ... while a cube keeps its sharp edges: each visible face is one colour.
  const Image box =
      render_mesh(make_centered_cube(), {.width = 100, .height = 100, .azimuth = 0, .elevation = 0})
          .image;
  EXPECT_EQ(pixel_stats(box, 35, 35, 30, 30).distinct_colors, 1u);
}

TEST(RenderMesh, WireframeAddsDarkEdges) {
  const RenderOptions o{.width = 150, .height = 150};
  RenderOptions wire = o;
  wire.wireframe = true;
  const Image plain = render_mesh(make_seamed_sphere(1, 8, 16), o).image;
  const Image edges = render_mesh(make_seamed_sphere(1, 8, 16), wire).image;
  write_png(edges, test::output_dir() + "/wireframe.png");
  EXPECT_GT(test::difference_fraction(plain, edges), 0.03);
  EXPECT_LT(pixel_stats(edges).mean_r, pixel_stats(plain).mean_r);
}

TEST(RenderMesh, LineSegmentsAreDrawn) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 1}};
  m.lines = {{0, 1}, {1, 2}, {2, 3}};
  const RenderResult r = render_mesh(m, {.width = 100, .height = 100});
  EXPECT_EQ(r.lines_drawn, 3u);
  EXPECT_EQ(r.triangles_drawn, 0u);
  const auto s = pixel_stats(r.image);
  EXPECT_GT(s.covered_fraction, 0.01);
  EXPECT_LT(s.covered_fraction, 0.2);
}

TEST(RenderMesh, EmptyMeshGivesTheBackground) {
  const RenderResult r =
      render_mesh(TriangleMesh{}, {.width = 30, .height = 20, .background = {0, 0, 1}});
  ASSERT_EQ(r.image.pixels.size(), 30u * 20 * 4);
  EXPECT_EQ(pixel_stats(r.image).distinct_colors, 1u);
  EXPECT_EQ(r.image.at(5, 5)[2], 255);
  EXPECT_EQ(r.image.at(5, 5)[0], 0);
}

TEST(RenderMesh, DegenerateInputDoesNotCrash) {
  TriangleMesh m = make_centered_cube();
  m.positions.push_back({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  m.triangles.push_back({0, 1, 8});  // uses the NaN vertex: skipped
  m.triangles.push_back({0, 0, 0});  // zero area
  const RenderResult r = render_mesh(m, {.width = 64, .height = 64});
  EXPECT_EQ(r.triangles_drawn, 12u);
  EXPECT_GT(pixel_stats(r.image).covered_fraction, 0.1);

  TriangleMesh point;
  point.positions = {{5, 5, 5}, {5, 5, 5}, {5, 5, 5}};
  point.triangles = {{0, 1, 2}};
  EXPECT_NO_THROW(render_mesh(point, {.width = 16, .height = 16}));
}

TEST(RenderMesh, LookingStraightDownWorks) {
  const auto s = pixel_stats(
      render_mesh(make_centered_cube(), {.width = 64, .height = 64, .elevation = 90}).image);
  EXPECT_GT(s.covered_fraction, 0.2);
}

TEST(RenderMesh, ExplicitCameraShowsTheTruePerspective) {
  // A unit sphere seen from d with a vertical angle of 45 degrees: a disc of
  // radius focal * tan(asin(1 / d)) pixels, focal = (height / 2) / tan(22.5).
  const TriangleMesh s = make_seamed_sphere();
  const auto from = [&](Vec3 eye, Vec3 target = {}) {
    return pixel_stats(
        render_mesh(s,
                    {.width = 200, .height = 100, .camera = LookAt{.eye = eye, .target = target}})
            .image);
  };
  const auto disc = [](double d) {
    const double r = 50 / std::tan(kPi / 8) * std::tan(std::asin(1 / d));
    return kPi * r * r / (200 * 100);
  };
  const auto near = from(view_direction(0, 0) * 10), far = from({0, 0, 20});
  EXPECT_NEAR(near.covered_fraction, disc(10), 0.1 * disc(10));
  EXPECT_NEAR(far.covered_fraction, disc(20), 0.15 * disc(20));
  EXPECT_NEAR(near.center_x, 100, 1);
  EXPECT_NEAR(near.center_y, 50, 1);
  // Looking to the right of the sphere puts it left of the centre.
  EXPECT_LT(from({0, 0, 10}, {2, 0, 0}).center_x, 80);
  // Straight down is defined too.
  EXPECT_NEAR(from({0, 10, 0}).covered_fraction, disc(10), 0.1 * disc(10));
}

TEST(RenderMesh, BadDataThrowsDataError) {
  TriangleMesh m = make_centered_cube();
  m.triangles.push_back({0, 1, 99});
  EXPECT_THROW(render_mesh(m), DataError);
  TriangleMesh c = make_centered_cube();
  c.colors.assign(3, Vec3{1, 0, 0});
  EXPECT_THROW(render_mesh(c), DataError);
  TriangleMesh l = make_centered_cube();
  l.lines.push_back({0, 8});
  try {
    render_mesh(l);
    FAIL() << "no exception";
  } catch (const DataError& e) {
    EXPECT_STREQ(e.what(), "render: line segment 0 uses vertex 8, the mesh has 8 vertices");
  }
}

TEST(RenderMesh, BoundingSphereOfUsedVertices) {
  TriangleMesh m = make_centered_cube(1, {10, 0, 0});
  m.positions.push_back({1000, 1000, 1000});  // unused: ignored
  const FrameSphere s = bounding_sphere(m);
  EXPECT_NEAR(s.center.x, 10, 1e-5);
  EXPECT_NEAR(s.radius, std::sqrt(3.f), 1e-5);
  EXPECT_EQ(bounding_sphere(TriangleMesh{}).radius, 0);
}

// A unit square facing +Z with texture coordinates (0,0)..(1,1), one texture.
TriangleMesh textured_square() {
  TriangleMesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.materials = {0, 0};
  return m;
}

TEST(RenderMesh, TextureReplacesTheVertexColourAndIsLit) {
  const Texture green = sfimage_texture(std::vector<std::int32_t>{1, 1, 3, 0x00ff00});
  const TriangleMesh m = test::with_color(textured_square(), {1, 0, 0});
  RenderOptions o{.width = 64, .height = 64, .azimuth = 0, .elevation = 0};
  o.appearance.textures = std::span(&green, 1);
  const Image img = render_mesh(m, o).image;
  EXPECT_GT(test::fraction_shaded_like(img, {0, 1, 0}), 0.3);
  EXPECT_EQ(test::fraction_shaded_like(img, {1, 0, 0}), 0);
  // An intensity texture scales the colour; an index out of range and
  // --no-colors draw without the texture.
  const Texture half_grey = sfimage_texture(std::vector<std::int32_t>{1, 1, 1, 0x80});
  o.appearance.textures = std::span(&half_grey, 1);
  EXPECT_GT(test::fraction_shaded_like(render_mesh(m, o).image, {1, 0, 0}), 0.3);
  o.appearance.textures = std::span(&green, 1);
  TriangleMesh other = m;
  other.materials = {5, 5};
  EXPECT_GT(test::fraction_shaded_like(render_mesh(other, o).image, {1, 0, 0}), 0.3);
  o.use_colors = false;
  EXPECT_EQ(test::fraction_shaded_like(render_mesh(m, o).image, {0, 1, 0}), 0);
}

TEST(RenderMesh, TextureIsNotMirrored) {
  // 2x1 image: left texel red, right texel blue (SFImage rows bottom up).
  const Texture tex = sfimage_texture(std::vector<std::int32_t>{2, 1, 3, 0xff0000, 0x0000ff});
  RenderOptions o{.width = 64, .height = 64, .azimuth = 0, .elevation = 0};
  o.appearance.textures = std::span(&tex, 1);
  const Image img = render_mesh(textured_square(), o).image;
  EXPECT_TRUE(test::shaded_like(img.at(22, 32), {1, 0, 0}));
  EXPECT_TRUE(test::shaded_like(img.at(42, 32), {0, 0, 1}));
}

TEST(RenderMesh, TransparentSurfaceShowsWhatIsBehind) {
  // A red square in front of a blue one, the red one 75 % transparent.
  TriangleMesh front = test::with_color(textured_square(), {1, 0, 0});
  TriangleMesh back = test::with_color(textured_square(), {0, 0, 1});
  for (auto& p : back.positions) p.z = -1;
  TriangleMesh both = front;
  for (const auto& p : back.positions) both.positions.push_back(p);
  for (const auto& c : back.colors) both.colors.push_back(c);
  for (const auto& t : back.triangles) both.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  both.texcoords.clear();
  both.materials.clear();
  const std::vector<float> opacity = {0.25f, 0.25f, 0.25f, 0.25f, 1, 1, 1, 1};
  RenderOptions o{.width = 64, .height = 64, .azimuth = 0, .elevation = 0};
  const Image opaque = render_mesh(both, o).image;
  o.appearance.opacity = opacity;
  const Image blended = render_mesh(both, o).image;
  const std::uint8_t* a = opaque.at(32, 32);
  const std::uint8_t* b = blended.at(32, 32);
  EXPECT_GT(a[0], 3 * a[2]);  // red in front
  EXPECT_GT(b[2], b[0]);      // mostly the blue behind
  EXPECT_GT(b[0], 10);        // with some red
}

}  // namespace
}  // namespace lodforge
