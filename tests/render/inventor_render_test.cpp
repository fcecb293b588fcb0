// Open Inventor scenes in pictures: the Mentor's windmill (RotationXYZ with an
// engine connected, Array, Complexity 0, DEF/USE of the blades) draws its
// four blades, and the `render` and `compare` commands take .iv files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/render/render_mesh.h"
#include "lodforge/scene/flatten_scene.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

const std::string kWindmill = std::string(LODFORGE_SHARED_DATA) +
                              "/inventor/aumuell__open-inventor/apps/examples/Mentor/"
                              "01.1.Windmill.iv";

// Pixels that differ from the background.
std::size_t covered(const Image& img) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < img.pixels.size(); i += 4)
    if (img.pixels[i] < 250 || img.pixels[i + 1] < 250 || img.pixels[i + 2] < 250) ++n;
  return n;
}

std::size_t differing(const Image& a, const Image& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < a.pixels.size(); i += 4)
    if (a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] ||
        a.pixels[i + 2] != b.pixels[i + 2])
      ++n;
  return n;
}

TEST(InventorRender, WindmillBladesAppear) {
  if (!fs::exists(kWindmill)) GTEST_SKIP() << "no shared corpus";
  const scene::Scene full = vrml1::read_vrml1_file(kWindmill).scene;
  // The file: Separator { Separator { blades } Separator { tower } }.
  ASSERT_EQ(full.roots.size(), 1u);
  ASSERT_EQ(full.roots[0]->children.size(), 2u);
  scene::Scene tower = full;
  tower.roots[0] = std::make_shared<scene::Node>(*full.roots[0]);
  tower.roots[0]->children.erase(tower.roots[0]->children.begin());

  const TriangleMesh with = scene::flatten_scene(full);
  const TriangleMesh without = scene::flatten_scene(tower);
  // The blades: 4 x (a Cube and 13 frame rods), and the hub's Cylinder.
  ASSERT_GT(with.triangle_count(), without.triangle_count());
  Box3 blades, rest;
  for (const auto& p : with.positions) blades.add(p);
  for (const auto& p : without.positions) rest.add(p);
  // The blades reach above the tower (they turn about the hub, 3 or more up).
  EXPECT_GT(blades.hi.y, rest.hi.y + 2);

  // Seen from the front, both framed the same: the blades cover pixels the
  // tower alone leaves empty, above and beside it.
  RenderOptions o;
  o.width = 200;
  o.height = 200;
  o.azimuth = 0;
  o.elevation = 0;
  o.frame = bounding_sphere(with);
  const RenderResult a = render_mesh(with, o);
  const RenderResult b = render_mesh(without, o);
  // (degenerate triangles aside: the blades' flat cubes are 0.02 thick)
  EXPECT_GE(a.triangles_drawn + 8, with.triangle_count());
  EXPECT_GT(a.triangles_drawn, b.triangles_drawn + 4 * 12);
  const std::size_t diff = differing(a.image, b.image);
  EXPECT_GT(diff, 200u * 200u / 20);
  EXPECT_GT(covered(a.image), covered(b.image) + 200u * 200u / 20);
  // The top quarter of the picture: blades only.
  Image top_a(200, 50), top_b(200, 50);
  top_a.pixels.assign(a.image.pixels.begin(), a.image.pixels.begin() + 200 * 50 * 4);
  top_b.pixels.assign(b.image.pixels.begin(), b.image.pixels.begin() + 200 * 50 * 4);
  EXPECT_GT(covered(top_a), 200u);
  EXPECT_EQ(covered(top_b), 0u);
}

int run(const std::string& args) {
  const int status = std::system(
      (std::string(LODFORGE_BINARY_DIR) + "/lodforge " + args + " >/dev/null 2>/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(InventorRender, RenderAndCompareTakeInventorFiles) {
  if (!fs::exists(kWindmill)) GTEST_SKIP() << "no shared corpus";
  if (!fs::exists(std::string(LODFORGE_BINARY_DIR) + "/lodforge")) GTEST_SKIP() << "not built";
  const fs::path dir =
      fs::temp_directory_path() / ("lodforge_iv_render_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string png = (dir / "w.png").string();
  EXPECT_EQ(run("render " + kWindmill + " -o " + png + " --size 64x64"), 0);
  EXPECT_TRUE(fs::exists(png));
  EXPECT_EQ(
      run("render " + kWindmill + " -o " + (dir / "l.png").string() + " --levels --size 64x64"), 0);
  EXPECT_EQ(run("compare " + kWindmill + " " + kWindmill + " --samples 2000"), 0);
  // The content decides when the name does not: an Inventor file named .txt.
  const std::string txt = (dir / "windmill.txt").string();
  fs::copy_file(kWindmill, txt);
  EXPECT_EQ(run("compare " + kWindmill + " " + txt + " --samples 2000"), 0);
  EXPECT_EQ(run("render " + txt + " -o " + png + " --size 64x64"), 0);
  // And lod on it writes Inventor that render reads back.
  const std::string lod = (dir / "w_lod.iv").string();
  ASSERT_EQ(run("lod " + kWindmill + " -o " + lod), 0);
  std::ifstream in(lod);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "#Inventor V2.1 ascii");
  EXPECT_EQ(run("render " + lod + " -o " + png + " --distances 10,40 --size 64x64"), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lodforge
