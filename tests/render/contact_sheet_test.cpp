#include "lodforge/render/contact_sheet.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "lodforge/mesh/mesh_io.h"
#include "lodforge/render/write_png.h"
#include "mesh/test_meshes.h"
#include "render/pixel_checks.h"

namespace lodforge {
namespace {

using test::make_centered_cube;
using test::make_seamed_sphere;
using test::pixel_stats;

TEST(ContactSheet, ThreePanelsSideBySideEachWithContentAndLabels) {
  const TriangleMesh levels[3] = {make_seamed_sphere(1, 24, 48), make_seamed_sphere(1, 8, 16),
                                  make_seamed_sphere(1, 3, 6)};
  std::vector<ContactSheetPanel> panels;
  for (std::size_t k = 0; k < 3; ++k)
    panels.push_back({.mesh = &levels[k], .labels = lod_labels(levels[k].triangle_count(), k)});
  const ContactSheetResult r =
      render_contact_sheet(panels, {.panel = {.width = 200, .height = 180}, .gap = 8});
  write_png(r.image, test::output_dir() + "/contact_sheet.png");

  ASSERT_EQ(r.panel_x.size(), 3u);
  EXPECT_EQ(r.image.width, 3 * 200 + 4 * 8);
  EXPECT_NEAR(static_cast<double>(r.image.width) / 200, 3, 0.2);
  EXPECT_GT(r.image.height, 180);  // room for the labels
  for (int k = 0; k < 3; ++k) {
    const auto picture = pixel_stats(r.image, r.panel_x[k], r.panel_y[k], 200, 180);
    EXPECT_GT(picture.covered_fraction, 0.3) << "panel " << k;
    const int label_top = r.panel_y[k] + 180;
    const auto labels =
        pixel_stats(r.image, r.panel_x[k], label_top, 200, r.image.height - label_top);
    EXPECT_GT(labels.covered_fraction, 0.005) << "labels of panel " << k;
    EXPECT_LT(labels.mean_r, 100) << "labels are dark text";
  }
  // The levels differ, so the panels do.
  Image p0(200, 180), p2(200, 180);
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 200; ++x) {
      std::copy_n(r.image.at(r.panel_x[0] + x, r.panel_y[0] + y), 4, p0.at(x, y));
      std::copy_n(r.image.at(r.panel_x[2] + x, r.panel_y[2] + y), 4, p2.at(x, y));
    }
  EXPECT_GT(test::difference_fraction(p0, p2), 0.05);
}

TEST(ContactSheet, PanelsShareOneCameraSoSizesCompare) {
  const TriangleMesh big = make_centered_cube(1), small = make_centered_cube(0.5f);
  const ContactSheetPanel panels[2] = {{.mesh = &big}, {.mesh = &small}};
  const ContactSheetResult r =
      render_contact_sheet(panels, {.panel = {.width = 120, .height = 120}});
  EXPECT_NEAR(r.frame.radius, std::sqrt(3.f), 1e-4);
  const double a = pixel_stats(r.image, r.panel_x[0], r.panel_y[0], 120, 120).covered_fraction;
  const double b = pixel_stats(r.image, r.panel_x[1], r.panel_y[1], 120, 120).covered_fraction;
  EXPECT_NEAR(b / a, 0.25, 0.05);
}

TEST(ContactSheet, EmptyPanelsKeepTheirPlace) {
  const TriangleMesh m = make_centered_cube();
  const TriangleMesh empty;
  const ContactSheetPanel panels[3] = {
      {.mesh = &m, .labels = {"level 0"}}, {.mesh = &empty, .labels = {"empty"}}, {}};
  const ContactSheetResult r = render_contact_sheet(panels, {.panel = {.width = 64, .height = 64}});
  EXPECT_EQ(r.image.width, 3 * 64 + 4 * 8);
  EXPECT_GT(pixel_stats(r.image, r.panel_x[0], r.panel_y[0], 64, 64).covered_fraction, 0.1);
  EXPECT_EQ(pixel_stats(r.image, r.panel_x[1], r.panel_y[1], 64, 64).covered_fraction, 0);
  EXPECT_EQ(pixel_stats(r.image, r.panel_x[2], 0, 64, r.image.height).covered_fraction, 0);
  EXPECT_TRUE(render_contact_sheet({}).image.empty());
}

// The real corpus: the Stanford bunny at its four scanned resolutions, like the
// original's Figure 5.5 (skipped when ../shared/data is absent).
TEST(ContactSheet, BunnyResolutions) {
  const std::string dir = std::string(LODFORGE_SHARED_DATA) + "/meshes/";
  const char* names[] = {"bun_zipper.ply", "bun_zipper_res2.ply", "bun_zipper_res3.ply",
                         "bun_zipper_res4.ply"};
  if (!std::filesystem::exists(dir + names[0])) GTEST_SKIP() << "no " << dir;
  std::vector<TriangleMesh> levels;
  for (const char* name : names) levels.push_back(read_mesh(dir + name));
  std::vector<ContactSheetPanel> panels;
  for (std::size_t k = 0; k < levels.size(); ++k)
    panels.push_back({.mesh = &levels[k], .labels = lod_labels(levels[k].triangle_count(), k)});
  const ContactSheetResult r = render_contact_sheet(
      panels, {.panel = {.width = 240, .height = 240, .azimuth = 0, .elevation = 10}});
  write_png(r.image, test::output_dir() + "/bunny_levels.png");
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const auto s = pixel_stats(r.image, r.panel_x[k], r.panel_y[k], 240, 240);
    EXPECT_GT(s.covered_fraction, 0.25) << names[k];
    EXPECT_LT(s.covered_fraction, 0.75) << names[k];
    EXPECT_NEAR(s.center_x - r.panel_x[k], 120, 20) << names[k];
  }
}

TEST(ContactSheet, RowsOfPanelsWithTheirOwnCameras) {
  // Two rows of two, the second row's camera twice as far: its sphere covers
  // a quarter of the first row's, and both cells of a row agree.
  const TriangleMesh m = make_seamed_sphere();
  const LookAt near{.eye = {0, 0, 8}}, far{.eye = {0, 0, 16}};
  const ContactSheetPanel panels[4] = {{.mesh = &m, .labels = {"a"}, .camera = near},
                                       {.mesh = &m, .labels = {"b"}, .camera = near},
                                       {.mesh = &m, .labels = {"c"}, .camera = far},
                                       {.mesh = &m, .labels = {"d"}, .camera = far}};
  const ContactSheetResult r =
      render_contact_sheet(panels, {.panel = {.width = 100, .height = 100}, .columns = 2});
  EXPECT_EQ(r.image.width, 2 * 100 + 3 * 8);
  ASSERT_EQ(r.panel_y.size(), 4u);
  EXPECT_EQ(r.panel_x[2], r.panel_x[0]);
  EXPECT_EQ(r.panel_y[1], r.panel_y[0]);
  EXPECT_GT(r.panel_y[2], r.panel_y[0] + 100);  // below the first row's labels
  EXPECT_EQ(r.image.height, r.panel_y[2] + (r.panel_y[2] - r.panel_y[0]));
  double cover[4];
  for (int k = 0; k < 4; ++k)
    cover[k] = pixel_stats(r.image, r.panel_x[k], r.panel_y[k], 100, 100).covered_fraction;
  EXPECT_EQ(cover[0], cover[1]);
  EXPECT_EQ(cover[2], cover[3]);
  EXPECT_NEAR(cover[2] / cover[0], 0.25, 0.04);
}

TEST(ContactSheet, LodLabels) {
  EXPECT_EQ(lod_labels(69451, 0), (std::vector<std::string>{"every LOD at child 0", "69451 tris"}));
  EXPECT_EQ(lod_labels(9318, std::nullopt, 1.25),
            (std::vector<std::string>{"d 1.25: 9318 tris", "each LOD by its distance"}));
  EXPECT_EQ(lod_labels(69451, 0, 40),
            (std::vector<std::string>{"d 40: 69451 tris", "every LOD at child 0"}));
}

}  // namespace
}  // namespace lodforge
