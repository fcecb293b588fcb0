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
    // Stored in need order: the same nodes, renumbered.
    ASSERT_EQ(r.lod.size(), t.lod.size());
    for (std::size_t k = 0; k < t.lod.size(); ++k) {
      EXPECT_EQ(r.nodes[r.lod[k]].coords, t.nodes[t.lod[k]].coords);
      EXPECT_EQ(r.nodes[r.lod[k]].level, t.nodes[t.lod[k]].level);
    }
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

// Progressive order: the first bytes of a file extract every level up to the
// priority they were cut after, exactly as the whole model does.
TEST(McoFile, PrefixExtractsTheSameLevels) {
  for (bool colored : {false, true}) {
    McOctree t = small_model(colored);
    std::string data = write_mco_data(t);
    const auto L = static_cast<std::uint32_t>(t.lod.size());
    std::uint64_t previous = 0;
    for (std::uint32_t n : {0u, 1u, 2u, 5u, L / 10, L / 3, L / 2, L - 1, L}) {
      std::uint64_t size = mco_prefix_size(data, n, "m.mco");
      EXPECT_GE(size, previous);
      previous = size;
      std::string_view prefix = std::string_view(data).substr(0, size);
      McOctree r = read_mco_data(prefix, "m.mco", {.max_priority = n});
      EXPECT_EQ(r.lod.size(), n);
      for (std::uint32_t k : {0u, n / 2, n}) {
        auto a = extract_mc_mesh(t, {.priority = k}).mesh;
        auto b = extract_mc_mesh(r, {.priority = k}).mesh;
        EXPECT_EQ(a.triangles, b.triangles) << "cut after " << n << ", priority " << k;
        EXPECT_EQ(a.positions, b.positions);
        EXPECT_EQ(a.colors, b.colors);
      }
      // One byte short of the cut is not enough for priority n.
      if (n > 0) {
        try {
          read_mco_data(prefix.substr(0, size - 1), "m.mco", {.max_priority = n});
          ADD_FAILURE() << "no error";
        } catch (const DataError& e) {
          EXPECT_THAT(e.what(), testing::HasSubstr("truncated .mco file: priority"));
        }
      }
    }
    EXPECT_EQ(mco_prefix_size(data, L, "m.mco"), data.size());
    // The first half of the file holds a good share of the levels.
    std::uint32_t half = 0;
    while (half < L && mco_prefix_size(data, half + 1, "m.mco") <= data.size() / 2) ++half;
    std::printf("progressive: half of the file (%zu bytes) extracts priorities 0..%u of %u\n",
                data.size() / 2, half, L);
    EXPECT_GT(half, 0u);
  }
}

}  // namespace
}  // namespace lodforge
