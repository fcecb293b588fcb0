#include "lodforge/mcoctree/mco_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

McOctree small_model(bool colored) {
  auto torus = test::make_torus(1.0f, 0.3f, 32, 16);
  if (colored) torus.colors.assign(torus.positions.size(), Vec3{0.2f, 0.4f, 0.6f});
  return build_mc_octree(torus, {.resolution = 16}).tree;
}

void expect_message(std::string_view data, const std::string& text) {
  try {
    read_mco_data(data, "m.mco");
    FAIL() << "no error for " << text;
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("m.mco: " + text));
  }
}

TEST(McoFile, RoundTripExtractsTheSameMeshes) {
  for (bool colored : {false, true}) {
    McOctree t = small_model(colored);
    std::string data = write_mco_data(t);
    McOctree r = read_mco_data(data, "m.mco");
    EXPECT_EQ(r.accumulated, t.accumulated);
    EXPECT_EQ(r.lod, t.lod);
    EXPECT_EQ(r.colors.size(), t.colors.size());
    for (double pct : {100.0, 50.0, 10.0}) {
      auto a = extract_mc_mesh(t, {.percent = pct}).mesh;
      auto b = extract_mc_mesh(r, {.percent = pct}).mesh;
      EXPECT_EQ(a.triangles, b.triangles);
      EXPECT_EQ(a.positions, b.positions);
      EXPECT_EQ(a.colors, b.colors);
    }
  }
}

TEST(McoFile, BadFiles) {
  std::string data = write_mco_data(small_model(false));
  expect_message(data.substr(0, 40), "truncated .mco file (40 bytes)");
  expect_message(data.substr(0, data.size() - 9), "truncated .mco file");
  std::string corrupt = data;
  corrupt[corrupt.size() / 2] ^= 0x10;
  expect_message(corrupt, "checksum mismatch");
  std::string magic = data;
  magic[0] = 'X';
  expect_message(magic, "not a .mco model");
  std::string version = data;
  version[8] = 9;
  expect_message(version, "unsupported .mco version 9");
  expect_message("", "truncated .mco file (0 bytes)");
}

}  // namespace
}  // namespace lodforge
