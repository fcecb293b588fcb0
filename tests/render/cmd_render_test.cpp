// `lodforge render` end to end: runs the built executable (skipped when it has
// not been built, since test_render does not depend on it).
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
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

}  // namespace
}  // namespace lodforge
