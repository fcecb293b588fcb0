// `lodforge render` end to end: runs the built executable (skipped when it has
// not been built, since test_render does not depend on it).
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "lodforge/render/texture_image.h"
#include "mesh/test_meshes.h"
#include "render/pixel_checks.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

class CmdRender : public ::testing::Test {
 protected:
  void SetUp() override {
    exe_ = std::string(LODFORGE_BINARY_DIR) + "/lodforge";
    ASSERT_TRUE(fs::exists(exe_)) << exe_ << " not built";
    // One folder per test: ctest runs the tests as parallel processes, and a
    // shared folder was wiped by one test's SetUp under another's feet.
    dir_ = test::output_dir() + "/cmd_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  // Exit code of `lodforge render <args>`; standard error into `err` if given.
  int lodforge_render(const std::string& args, std::string* err = nullptr) {
    const std::string err_file = dir_ + "/stderr.txt";
    const int status =
        std::system((exe_ + " render " + args + " >/dev/null 2>" + err_file).c_str());
    if (err) {
      std::ifstream in(err_file);
      err->assign(std::istreambuf_iterator<char>(in), {});
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  // An ASCII PLY of a cube with every vertex red.
  std::string red_cube_ply() {
    const TriangleMesh m = test::make_centered_cube();
    const std::string path = dir_ + "/red_cube.ply";
    std::ofstream out(path);
    out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
           "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
           "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : m.positions) out << p.x << ' ' << p.y << ' ' << p.z << " 255 0 0\n";
    for (const auto& t : m.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return path;
  }
  // Writes `vrml` to NAME.wrl, renders it to NAME.png with `args`; the picture
  // (empty when the command failed).
  Image render_text(const std::string& name, const std::string& vrml, const std::string& args) {
    std::ofstream(dir_ + "/" + name + ".wrl") << vrml;
    const std::string png = dir_ + "/" + name + ".png";
    if (lodforge_render(dir_ + "/" + name + ".wrl -o " + png + " " + args) != 0) return {};
    return load(png);
  }
  Image load(const std::string& png) {
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load(png.c_str(), &w, &h, &n, 4);
    Image img(std::max(w, 0), std::max(h, 0));
    if (data) img.pixels.assign(data, data + static_cast<std::size_t>(w) * h * 4);
    stbi_image_free(data);
    return img;
  }
  std::string exe_, dir_;
};

TEST_F(CmdRender, WritesAPngOfTheRequestedSizeWithTheMeshColours) {
  const std::string png = dir_ + "/out.png";
  ASSERT_EQ(lodforge_render(red_cube_ply() + " -o " + png + " --size 120x90 --view 45,30"), 0);
  int w = 0, h = 0, n = 0;
  stbi_uc* data = stbi_load(png.c_str(), &w, &h, &n, 4);
  ASSERT_NE(data, nullptr);
  Image img(w, h);
  img.pixels.assign(data, data + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(data);
  EXPECT_EQ(w, 120);
  EXPECT_EQ(h, 90);
  const auto s = test::pixel_stats(img);
  EXPECT_GT(s.covered_fraction, 0.1);
  EXPECT_GT(s.mean_r, 2 * s.mean_g);

  const std::string grey = dir_ + "/grey.png";
  ASSERT_EQ(lodforge_render(red_cube_ply() + " -o " + grey + " --no-colors --wireframe"), 0);
  EXPECT_TRUE(fs::exists(grey));
}

TEST_F(CmdRender, BadUsageIsExitCode2AndBadInputExitCode1WithoutOutput) {
  const std::string mesh = red_cube_ply(), png = dir_ + "/never.png";
  EXPECT_EQ(lodforge_render(mesh + " -o " + png + " --size 100"), 2);
  EXPECT_EQ(lodforge_render(mesh + " -o " + png + " --size 0x50"), 2);
  EXPECT_EQ(lodforge_render(mesh + " -o " + png + " --size 100x50x3"), 2);
  EXPECT_EQ(lodforge_render(mesh + " -o " + png + " --view 10"), 2);
  EXPECT_EQ(lodforge_render(mesh + " -o " + png + " --view 10,91"), 2);
  EXPECT_EQ(lodforge_render(mesh), 2);  // no -o
  EXPECT_EQ(lodforge_render(dir_ + "/missing.ply -o " + png), 1);
  std::ofstream(dir_ + "/bad.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  EXPECT_EQ(lodforge_render(dir_ + "/bad.off -o " + png), 1);
  EXPECT_FALSE(fs::exists(png));
}

TEST_F(CmdRender, RendersAVrmlSceneAndEachLodLevel) {
  const std::string scene = dir_ + "/lod.wrl";
  std::ofstream(scene) << "#VRML V1.0 ascii\nSeparator {\n LOD { range [ 5, 10 ]\n"
                          "  Sphere { radius 1 }\n  Cube { }\n  Cone { }\n }\n}\n";
  const std::string level0 = dir_ + "/level0.png", level2 = dir_ + "/level2.png";
  ASSERT_EQ(lodforge_render(scene + " -o " + level0 + " --size 100x100"), 0);
  ASSERT_EQ(lodforge_render(scene + " -o " + level2 + " --size 100x100 --level 2"), 0);
  const Image a = load(level0), b = load(level2);
  EXPECT_GT(test::pixel_stats(a).covered_fraction, 0.1);
  EXPECT_GT(test::pixel_stats(b).covered_fraction, 0.1);
  EXPECT_NE(a.pixels, b.pixels);  // a sphere, then a cone

  const std::string sheet = dir_ + "/levels.png";
  ASSERT_EQ(lodforge_render(scene + " -o " + sheet + " --size 100x100 --levels"), 0);
  const Image all = load(sheet);
  EXPECT_EQ(all.width, 3 * 100 + 4 * 8);  // three levels side by side
  EXPECT_EQ(lodforge_render(scene + " -o " + sheet + " --levels --level 1"), 2);
  EXPECT_EQ(lodforge_render(red_cube_ply() + " -o " + dir_ + "/x.png --levels"), 1);
}

TEST_F(CmdRender, DistancesGiveARowPerDistanceOfLodChoiceBesideLevelZero) {
  // Two LOD nodes 100 apart, a sphere switching to a small cube at 200. With
  // --view 0,0 the eye is on +Z of the centre (50 0 0), so from d = 150 both
  // are 158 away (spheres in both cells) and from d = 400 both are 403 away
  // (cubes on the left, spheres on the right).
  const std::string scene = dir_ + "/two_lods.wrl", png = dir_ + "/distances.png";
  std::ofstream(scene) << "#VRML V1.0 ascii\nSeparator {\n"
                          " DEF L LOD { range [200] Sphere { radius 5 }"
                          " Cube { width 4 height 4 depth 4 } }\n"
                          " Translation { translation 100 0 0 }\n USE L\n}\n";
  ASSERT_EQ(
      lodforge_render(scene + " -o " + png + " --size 200x200 --view 0,0 --distances 150,400"), 0);
  const Image img = load(png);
  EXPECT_EQ(img.width, 2 * 200 + 3 * 8);
  // Per row: the picture, half a gap, two label lines of 12 pixels, a gap.
  EXPECT_EQ(img.height, 8 + 2 * (200 + 4 + 2 * 12 + 8));
  const auto cell = [&](int row, int column) {
    Image c(200, 200);
    for (int y = 0; y < 200; ++y)
      for (int x = 0; x < 200; ++x)
        std::copy_n(img.at(8 + column * 208 + x, 8 + row * 236 + y), 4, c.at(x, y));
    return c;
  };
  EXPECT_GT(test::pixel_stats(cell(0, 0)).covered_fraction, 0.001);
  EXPECT_EQ(cell(0, 0).pixels, cell(0, 1).pixels);  // nothing switched
  EXPECT_NE(cell(1, 0).pixels, cell(1, 1).pixels);  // both switched to cubes
  // Farther is smaller.
  EXPECT_LT(test::pixel_stats(cell(1, 1)).covered_fraction,
            test::pixel_stats(cell(0, 1)).covered_fraction / 2);
}

TEST_F(CmdRender, BadDistancesAreExitCode1WithAMessage) {
  const std::string scene = dir_ + "/lod.wrl", png = dir_ + "/never.png";
  std::ofstream(scene) << "#VRML V1.0 ascii\nLOD { range [5] Sphere {} Cube {} }\n";
  std::string err;
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances 2,far", &err), 1);
  EXPECT_NE(err.find("--distances: 'far' is not a number"), std::string::npos) << err;
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances=2,-1", &err), 1);
  EXPECT_NE(err.find("-1 is not a distance > 0"), std::string::npos) << err;
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances 0", &err), 1);
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances 1,,2", &err), 1);
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances ''", &err), 1);
  EXPECT_NE(err.find("the list is empty"), std::string::npos) << err;
  EXPECT_EQ(lodforge_render(red_cube_ply() + " -o " + png + " --distances 2"), 1);
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances 2 --levels"), 2);
  EXPECT_EQ(lodforge_render(scene + " -o " + png + " --distances 2 --level 1"), 2);
  EXPECT_FALSE(fs::exists(png));
}

TEST_F(CmdRender, ColouredComparisonShowsWhereTheErrorIs) {
  // A sphere against a flattened copy of itself: the deviation is zero at the
  // equator (blue) and largest at the poles (red); the picture shows both.
  const std::string a = dir_ + "/a.wrl", b = dir_ + "/b.wrl";
  std::ofstream(a) << "#VRML V1.0 ascii\nSphere { radius 1 }\n";
  std::ofstream(b) << "#VRML V1.0 ascii\nScale { scaleFactor 1 0.5 1 }\nSphere { radius 1 }\n";
  const std::string colored = dir_ + "/deviation.ply", png = dir_ + "/deviation.png";
  ASSERT_EQ(
      std::system((exe_ + " compare " + a + " " + b + " --colored " + colored + " >/dev/null 2>&1")
                      .c_str()),
      0);
  ASSERT_EQ(lodforge_render(colored + " -o " + png + " --size 160x160 --view 0,0"), 0);
  const Image img = load(png);
  const auto s = test::pixel_stats(img);
  EXPECT_GT(s.covered_fraction, 0.2);
  // Both ends of the scale are on screen: reddish pixels and bluish pixels.
  int red = 0, blue = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      if (p[0] > 2 * p[2] && p[0] > 2 * p[1]) ++red;
      if (p[2] > 2 * p[0] && p[2] > p[1]) ++blue;
    }
  EXPECT_GT(red, 50);
  EXPECT_GT(blue, 50);
}

TEST_F(CmdRender, RendersTheExampleScene) {
  const std::string png = dir_ + "/example.png";
  ASSERT_EQ(
      lodforge_render(std::string(LODFORGE_EXAMPLES) + "/scene.wrl -o " + png + " --size 160x120"),
      0);
  EXPECT_GT(test::pixel_stats(load(png)).covered_fraction, 0.1);
}

// ---- Scenes in their own colours (materials, bindings, textures) ----

const std::string kCastleDemo =
    std::string(LODFORGE_SHARED_DATA) + "/vrml1/castle-engine__demo-models";

TEST_F(CmdRender, PerFaceMaterialBindingColoursEachFace) {
  // Two squares side by side, one face each: red on the left, blue on the right.
  const std::string scene =
      "#VRML V1.0 ascii\nSeparator {\n Material { diffuseColor [1 0 0, 0 0 1] }\n"
      " MaterialBinding { value PER_FACE }\n"
      " Coordinate3 { point [-2 -1 0, 0 -1 0, 0 1 0, -2 1 0, 2 -1 0, 2 1 0] }\n"
      " IndexedFaceSet { coordIndex [0, 1, 2, 3, -1, 1, 4, 5, 2, -1] }\n}\n";
  const Image img = render_text("per_face", scene, "--size 160x80 --view 0,0");
  ASSERT_EQ(img.width, 160);
  const auto half = [&](int x0) {
    Image h(80, 80);
    for (int y = 0; y < 80; ++y) std::copy_n(img.at(x0, y), 80 * 4, h.at(0, y));
    return h;
  };
  const Image left = half(0), right = half(80);
  // Each square covers about a sixth of its half of the picture.
  EXPECT_GT(test::fraction_shaded_like(left, {1, 0, 0}), 0.12);
  EXPECT_LT(test::fraction_shaded_like(left, {0, 0, 1}), 0.01);
  EXPECT_GT(test::fraction_shaded_like(right, {0, 0, 1}), 0.12);
  EXPECT_LT(test::fraction_shaded_like(right, {1, 0, 0}), 0.01);
  // --no-colors draws them grey.
  EXPECT_LT(test::fraction_shaded_like(
                render_text("grey", scene, "--size 160x80 --view 0,0 --no-colors"), {1, 0, 0}),
            0.01);
}

TEST_F(CmdRender, InlineImageTextureShowsItsFourColours) {
  // A square under a 2x2 SFImage: red, green (bottom row), blue, white (top).
  const Image img = render_text("sfimage",
                                "#VRML V1.0 ascii\nSeparator {\n"
                                " Texture2 { image 2 2 3 0xFF0000 0x00FF00 0x0000FF 0xFFFFFF }\n"
                                " Coordinate3 { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }\n"
                                " TextureCoordinate2 { point [0 0, 1 0, 1 1, 0 1] }\n"
                                " IndexedFaceSet { coordIndex [0, 1, 2, 3, -1] }\n}\n",
                                "--size 120x120 --view 0,0");
  ASSERT_EQ(img.width, 120);
  // The square's extent on screen.
  int x0 = img.width, x1 = 0, y0 = img.height, y1 = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.at(x, y)[0] < 250 || img.at(x, y)[1] < 250 || img.at(x, y)[2] < 250) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  ASSERT_GT(x1 - x0, 40);
  // Texel centres, a quarter of the way in from each corner, are pure (bilinear
  // filtering blends in between): red bottom left, green bottom right, blue
  // top left, white top right.
  const auto at = [&](double s, double t) {
    return img.at(x0 + int(s * (x1 - x0)), y1 - int(t * (y1 - y0)));
  };
  EXPECT_TRUE(test::shaded_like(at(0.25, 0.25), {1, 0, 0}));
  EXPECT_TRUE(test::shaded_like(at(0.75, 0.25), {0, 1, 0}));
  EXPECT_TRUE(test::shaded_like(at(0.25, 0.75), {0, 0, 1}));
  EXPECT_TRUE(test::shaded_like(at(0.75, 0.75), {1, 1, 1}));
}

TEST_F(CmdRender, MissingTextureIsAWarningAndTheSurfaceColour) {
  const std::string scene = dir_ + "/missing_texture.wrl", png = dir_ + "/missing_texture.png";
  std::ofstream(scene) << "#VRML V1.0 ascii\nSeparator {\n"
                          " Material { diffuseColor 0 1 0 }\n"
                          " Texture2 { filename \"no_such_image.png\" }\n Cube {}\n}\n";
  std::string err;
  ASSERT_EQ(lodforge_render(scene + " -o " + png + " --size 100x100", &err), 0);
  EXPECT_NE(err.find("no_such_image.png"), std::string::npos) << err;
  EXPECT_NE(err.find("warning"), std::string::npos) << err;
  EXPECT_GT(test::fraction_shaded_like(load(png), {0, 1, 0}), 0.1);
  // A file that is not an image: the same.
  std::ofstream(dir_ + "/not_an_image.png") << "hello";
  std::ofstream(scene) << "#VRML V1.0 ascii\nSeparator {\n"
                          " Texture2 { filename \"not_an_image.png\" }\n Cube {}\n}\n";
  ASSERT_EQ(lodforge_render(scene + " -o " + png + " --size 100x100", &err), 0);
  EXPECT_NE(err.find("not_an_image.png"), std::string::npos) << err;
  EXPECT_GT(test::pixel_stats(load(png)).covered_fraction, 0.1);
}

TEST_F(CmdRender, CastleShowsItsMaterialsAndItsTextures) {
  // castle.wrl (Blender export, Z up): white and grey (0.56) materials bound
  // PER_VERTEX_INDEXED under JPEG textures (grass, water, wood, stone).
  const std::string castle = kCastleDemo + "/castle/old/vrml_1/castle.wrl";
  if (!fs::exists(castle)) GTEST_SKIP() << "no shared corpus";
  const std::string textured = dir_ + "/castle.png", plain = dir_ + "/castle_materials.png";
  const std::string view = " --size 240x180 --view 10,-70";
  ASSERT_EQ(lodforge_render(castle + " -o " + textured + view), 0);
  ASSERT_EQ(lodforge_render(castle + " -o " + plain + view + " --no-textures"), 0);
  const Image with = load(textured), without = load(plain);
  // Materials only: neutral greys (the materials' white and 0.56 grey), not
  // the bluish grey of a scene without materials.
  EXPECT_GT(test::fraction_shaded_like(without, {1, 1, 1}, 0.01), 0.08);
  // Textured: the grass texture's colour covers the ground.
  const Texture grass = read_texture(kCastleDemo + "/castle/old/textures/grassfull.jpg");
  double sum[3] = {0, 0, 0};
  for (std::size_t i = 0; i < grass.image.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c) sum[c] += grass.image.pixels[i + c];
  const Vec3 mean{float(sum[0]), float(sum[1]), float(sum[2])};
  EXPECT_GT(test::fraction_shaded_like(with, mean, 0.04), 0.06);
  EXPECT_LT(test::fraction_shaded_like(without, mean, 0.04), 0.01);
}

TEST_F(CmdRender, TexturedCorpusSceneShowsItsTexture) {
  // texture_test.wrl: a Cone, Cylinder, Sphere and Cube under a PNG texture
  // (default texture coordinates of the primitives), then an untextured
  // Sphere beside them.
  const std::string scene = kCastleDemo + "/vrml_1/subdir1/subdir2/texture_test.wrl";
  if (!fs::exists(scene)) GTEST_SKIP() << "no shared corpus";
  const std::string png = dir_ + "/texture_test.png";
  ASSERT_EQ(lodforge_render(scene + " -o " + png + " --size 400x250 --view 0,0"), 0);
  const Texture tex = read_texture(kCastleDemo + "/textures/test_texture.png");
  // The most common texel colours of the image show on the shapes.
  std::map<std::uint32_t, int> count;
  for (std::size_t i = 0; i < tex.image.pixels.size(); i += 4)
    ++count[(tex.image.pixels[i] & 0xF0u) << 16 | (tex.image.pixels[i + 1] & 0xF0u) << 8 |
            (tex.image.pixels[i + 2] & 0xF0u)];
  const auto top = std::max_element(count.begin(), count.end(),
                                    [](auto& a, auto& b) { return a.second < b.second; });
  const Vec3 common{float((top->first >> 16) & 0xFF) + 8, float((top->first >> 8) & 0xFF) + 8,
                    float(top->first & 0xFF) + 8};
  const Image img = load(png);
  EXPECT_GT(test::fraction_shaded_like(img, common, 0.05), 0.002);
  std::string err;
  ASSERT_EQ(
      lodforge_render(scene + " -o " + png + " --size 400x250 --view 0,0 --no-textures", &err), 0);
  EXPECT_LT(test::fraction_shaded_like(load(png), common, 0.05),
            test::fraction_shaded_like(img, common, 0.05) / 4);
}

TEST_F(CmdRender, DeviationPicturesCarryTheirColourScale) {
  // compare --colored OUT.png: the coloured mesh with the bar; render
  // --color-bar: the same bar beside a coloured PLY.
  const std::string a = dir_ + "/sphere_a.ply", b = dir_ + "/sphere_b.ply";
  std::ofstream(dir_ + "/a.wrl") << "#VRML V1.0 ascii\nSphere { radius 1 }\n";
  std::ofstream(dir_ + "/b.wrl") << "#VRML V1.0 ascii\nCube { width 1.6 height 1.6 depth 1.6 }\n";
  const std::string png = dir_ + "/compare.png";
  ASSERT_EQ(std::system((exe_ + " compare " + dir_ + "/a.wrl " + dir_ + "/b.wrl --colored " + png +
                         " >/dev/null 2>&1")
                            .c_str()),
            0);
  const Image with_bar = load(png);
  EXPECT_EQ(with_bar.height, 480);
  EXPECT_GT(with_bar.width, 640 + 40);
  // The bar: red at its top, blue at its bottom, right of the 640 picture.
  int red = 0, blue = 0;
  for (int y = 0; y < with_bar.height; ++y)
    for (int x = 640; x < with_bar.width; ++x) {
      red += test::shaded_like(with_bar.at(x, y), {1, 0, 0}, 0.02);
      blue += test::shaded_like(with_bar.at(x, y), {0, 0, 1}, 0.02);
    }
  EXPECT_GT(red, 20);
  EXPECT_GT(blue, 20);
  const std::string plain = dir_ + "/plain.png", bar = dir_ + "/bar.png";
  ASSERT_EQ(lodforge_render(red_cube_ply() + " -o " + plain + " --size 200x150"), 0);
  ASSERT_EQ(lodforge_render(red_cube_ply() + " -o " + bar + " --size 200x150 --color-bar 0.5"), 0);
  EXPECT_EQ(load(plain).width, 200);
  EXPECT_GT(load(bar).width, 240);
  EXPECT_EQ(lodforge_render(red_cube_ply() + " -o " + bar + " --color-bar -1"), 2);
}

TEST_F(CmdRender, ContactSheetsOfManyLevelsWrapIntoRows) {
  // Six levels: rows of three (up to four stay in one row).
  const std::string scene = dir_ + "/six.wrl", png = dir_ + "/six.png";
  std::ofstream(scene)
      << "#VRML V1.0 ascii\nLOD { range [1, 2, 3, 4, 5]\n"
         " Sphere {} Cube {} Cone {} Cylinder {} Sphere { radius 0.5 } Cube {}\n}\n";
  ASSERT_EQ(lodforge_render(scene + " -o " + png + " --size 100x100 --levels"), 0);
  const Image img = load(png);
  EXPECT_EQ(img.width, 3 * 100 + 4 * 8);
  // Per row: the picture, half a gap, two label lines of 12 pixels, a gap.
  EXPECT_EQ(img.height, 8 + 2 * (100 + 4 + 2 * 12 + 8));
}

TEST_F(CmdRender, InventorWindmillIsDrawnInItsColours) {
  const std::string windmill = std::string(LODFORGE_SHARED_DATA) +
                               "/inventor/aumuell__open-inventor/apps/examples/Mentor/"
                               "01.1.Windmill.iv";
  if (!fs::exists(windmill)) GTEST_SKIP() << "no shared corpus";
  const std::string png = dir_ + "/windmill.png";
  ASSERT_EQ(lodforge_render(windmill + " -o " + png + " --size 200x200 --view 0,10"), 0);
  // Not the grey of a scene without materials: its materials' colours.
  EXPECT_LT(test::fraction_shaded_like(load(png), {0.72f, 0.74f, 0.80f}, 0.01), 0.05);
}

// ---- VRML97 / X3D classic scenes, flattened, in their own colours ----

TEST_F(CmdRender, Vrml97AndX3dScenesShowTheirTexturesAndColourNodes) {
  const std::string demo = std::string(LODFORGE_SHARED_DATA) + "/";
  const std::string oak =
      demo + "vrml2/castle-engine__demo-models/shadow_maps/castle_with_trees/oaktree.wrl";
  const std::string colors =
      demo + "x3d/castle-engine__demo-models/x3d/indexed_face_set_colors.x3dv";
  const std::string grid = demo + "x3d/castle-engine__demo-models/x3d/elevation_grid_texture.x3dv";
  for (const std::string& f : {oak, colors, grid})
    if (!fs::exists(f)) GTEST_SKIP() << "no shared corpus: " << f;
  const auto picture = [&](const std::string& in, const std::string& name,
                           const std::string& args) {
    const std::string png = dir_ + "/" + name + ".png";
    EXPECT_EQ(lodforge_render(in + " -o " + png + " --size 320x240 " + args), 0) << in;
    return load(png);
  };
  // The oak's leaves and bark are its ImageTextures (browns and greens);
  // without them, its Materials' 0.8 grey.
  const auto oak_textured = test::pixel_stats(picture(oak, "oak", ""));
  EXPECT_GT(oak_textured.covered_fraction, 0.1);
  EXPECT_LT(oak_textured.mean_b, 0.7 * oak_textured.mean_r);
  EXPECT_GT(oak_textured.distinct_colors, 2000u);
  const auto oak_plain = test::pixel_stats(picture(oak, "oak_plain", "--no-textures"));
  EXPECT_NEAR(oak_plain.mean_b, oak_plain.mean_r, 5);
  EXPECT_NEAR(oak_plain.covered_fraction, oak_textured.covered_fraction, 0.08);

  // Color nodes per vertex and per face: yellow faces among them, none
  // when drawn without colours.
  EXPECT_GT(test::fraction_shaded_like(picture(colors, "colors", ""), {1, 1, 0}), 0.005);
  EXPECT_LT(test::fraction_shaded_like(picture(colors, "colors_grey", "--no-colors"), {1, 1, 0}),
            0.001);

  // The ElevationGrid's Color node: green hills.
  const auto hills = test::pixel_stats(picture(grid, "grid", ""));
  EXPECT_GT(hills.covered_fraction, 0.05);
  EXPECT_GT(hills.mean_g, 1.3 * hills.mean_r);
  const auto grey_hills = test::pixel_stats(picture(grid, "grid_grey", "--no-colors"));
  EXPECT_LT(grey_hills.mean_g, 1.1 * grey_hills.mean_r);
}

}  // namespace
}  // namespace lodforge
