// `lodforge render` end to end: runs the built executable (skipped when it has
// not been built, since test_render does not depend on it).
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "render/test_meshes.h"

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
  // Exit code of `lodforge render <args>`, output discarded.
  int lodforge_render(const std::string& args) {
    const int status = std::system((exe_ + " render " + args + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  // An ASCII PLY of a cube with every vertex red.
  std::string red_cube_ply() {
    const TriangleMesh m = test::cube();
    const std::string path = dir_ + "/red_cube.ply";
    std::ofstream out(path);
    out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
           "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
           "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : m.positions) out << p.x << ' ' << p.y << ' ' << p.z << " 255 0 0\n";
    for (const auto& t : m.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return path;
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

}  // namespace
}  // namespace lodforge
