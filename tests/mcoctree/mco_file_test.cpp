#include "lodforge/mcoctree/mco_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

McOctree small_tree(bool colored) {
  auto torus = test::make_torus(1.0f, 0.3f, 32, 16);
  if (colored) torus.colors.assign(torus.positions.size(), Vec3{0.2f, 0.4f, 0.6f});
  return build_mc_octree(torus, {.resolution = 16}).tree;
}
McLodModel small_model(bool colored) {
  return compile_mc_lod(small_tree(colored));
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
    McOctree tree = small_tree(colored);
    McLodModel t = compile_mc_lod(tree);
    std::string data = write_mco_data(t);
    McLodModel r = read_mco_data(data, "m.mco");
    // The model is stored as it is: every array comes back.
    EXPECT_EQ(r.depth, t.depth);
    EXPECT_EQ(r.cell_size, t.cell_size);
    EXPECT_EQ(r.accumulated, t.accumulated);
    EXPECT_EQ(r.group, t.group);
    EXPECT_EQ(r.cells, t.cells);
    EXPECT_EQ(r.intervals, t.intervals);
    EXPECT_EQ(r.triangles, t.triangles);
    EXPECT_EQ(r.positions, t.positions);
    EXPECT_EQ(r.normals, t.normals);
    EXPECT_EQ(r.colors, t.colors);
    EXPECT_EQ(r.centroids, t.centroids);
    EXPECT_EQ(r.colors.size(), colored ? r.positions.size() : 0);
    for (double pct : {100.0, 50.0, 10.0}) {
      auto a = extract_mc_mesh(tree, {.percent = pct}).mesh;
      auto b = extract_mc_mesh(r, {.percent = pct}).mesh;
      EXPECT_EQ(a.triangles, b.triangles);
      EXPECT_EQ(a.positions, b.positions);
      EXPECT_EQ(a.colors, b.colors);
    }
  }
  // An empty model round-trips too.
  McLodModel empty = read_mco_data(write_mco_data(McLodModel{}), "m.mco");
  EXPECT_EQ(extract_mc_mesh(empty).mesh.triangle_count(), 0u);
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

std::uint64_t fnv1a(std::string_view d) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : d) h = (h ^ c) * 1099511628211ULL;
  return h;
}

// The chunks of an uncoloured file (see the layout in mco_file.h): where each
// starts, its size before the checksum, and where its triangles start.
struct ChunkPlace {
  std::size_t at, size, triangles_at;
  std::uint32_t triangles;
};
std::vector<ChunkPlace> chunk_places(const std::string& data) {
  auto pad8 = [](std::size_t n) { return (n + 7) / 8 * 8; };
  std::vector<ChunkPlace> out;
  for (std::size_t at = 88; at < data.size();) {
    std::uint32_t n[5];
    std::memcpy(n, data.data() + at, sizeof n);
    const auto [cells, intervals, triangles, vertices, centroids] = n;
    std::size_t tri_at = at + 32 + pad8(16 * std::size_t{vertices}) + 8 * std::size_t{cells} +
                         8 * std::size_t{intervals};
    std::size_t size = tri_at - at + pad8(12 * std::size_t{triangles} + 4 * std::size_t{centroids});
    out.push_back({at, size, tri_at, triangles});
    at += size + 8;
  }
  return out;
}
void reseal(std::string& data, const ChunkPlace& c) {
  std::uint64_t h = fnv1a(std::string_view(data).substr(c.at, c.size));
  std::memcpy(data.data() + c.at + c.size, &h, 8);
}

// The first index of the first triangle set to v, the chunk re-sealed.
std::string with_first_triangle_index(std::string data, std::uint32_t v) {
  for (const auto& c : chunk_places(data))
    if (c.triangles > 0) {
      std::memcpy(data.data() + c.triangles_at, &v, 4);
      reseal(data, c);
      break;
    }
  return data;
}

// Data that pass the checksums but not the structure: extraction trusts the
// accumulation table (it sizes its output) and the indices, so reading checks
// them. The chunk is re-sealed after the change so only the check can catch it.
TEST(McoFile, InconsistentDataAreRejected) {
  McLodModel t = small_model(false);
  auto reseal_and_expect = [&](McLodModel bad, const std::string& text) {
    expect_message(write_mco_data(bad), text);
  };
  McLodModel acc = t;
  acc.accumulated[acc.accumulated.size() / 2] += 1;
  reseal_and_expect(acc, "accumulation table disagrees with the cells");
  expect_message(with_first_triangle_index(write_mco_data(t), 1u << 30),
                 "vertex index out of range");
  // A vertex of a later chunk is out of range too: a prefix must stand alone.
  expect_message(with_first_triangle_index(write_mco_data(t),
                                           static_cast<std::uint32_t>(t.positions.size() - 1)),
                 "vertex index out of range");
  // A forged header (counts near 2^32, checksum recomputed) is a truncated
  // file, not an allocation of its counts.
  std::string forged = write_mco_data(t);
  for (std::size_t at : {40u, 48u, 56u, 64u}) {
    std::uint64_t n = 4'000'000'000u;
    std::memcpy(forged.data() + at, &n, 8);
  }
  std::uint64_t priorities = 3'999'999'999u;
  std::memcpy(forged.data() + 72, &priorities, 8);
  std::uint64_t h = fnv1a(std::string_view(forged).substr(0, 80));
  std::memcpy(forged.data() + 80, &h, 8);
  expect_message(forged, "truncated .mco file: priority");
  McLodModel until = t;
  until.cells[until.cell_count() - 1].until = 0;
  reseal_and_expect(until, "cell out of range");
  // Numbers that are not numbers never reach an extracted mesh.
  for (float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    McLodModel vertex = t;
    vertex.positions[vertex.positions.size() / 2].y = bad;
    reseal_and_expect(vertex, "vertex position not finite");
    McLodModel origin = t;
    origin.origin.x = bad;
    reseal_and_expect(origin, "the lattice origin or cell size is not a finite number");
  }
}

// Random damage to the data of a chunk, re-sealed so that the checksum does
// not catch it: reading either throws DataError or returns a model whose
// every level extracts with indices in range and the counts of its table.
TEST(McoFile, ResealedDamageIsRejectedOrHarmless) {
  const std::string data = write_mco_data(small_model(false));
  const auto places = chunk_places(data);
  std::mt19937 rng(11);
  int rejected = 0, accepted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bad = data;
    const auto& c = places[rng() % places.size()];
    if (c.size <= 32) continue;
    std::size_t at = c.at + 32 + rng() % (c.size - 32);
    bad[at] = static_cast<char>(bad[at] ^ (1 + rng() % 255));
    reseal(bad, c);
    McLodModel m;
    try {
      m = read_mco_data(bad, "m.mco");
    } catch (const DataError&) {
      ++rejected;
      continue;
    }
    ++accepted;
    std::vector<Triangle> tris;
    for (std::uint32_t n = 0; n <= m.priorities(); ++n) {
      ASSERT_EQ(extract_mc_indices(m, n, tris), m.accumulated[n]);
      for (const auto& t : tris)
        for (auto v : t) ASSERT_LT(v, m.positions.size());
    }
  }
  std::printf("damaged files: %d rejected, %d accepted (damage to positions, normals, ...)\n",
              rejected, accepted);
  EXPECT_GT(rejected, 0);
}

// Progressive order: the first bytes of a file extract every level up to the
// priority they were cut after, exactly as the whole model does.
TEST(McoFile, PrefixExtractsTheSameLevels) {
  for (bool colored : {false, true}) {
    McLodModel t = small_model(colored);
    std::string data = write_mco_data(t);
    const auto L = t.priorities();
    std::uint64_t previous = 0;
    for (std::uint32_t n : {0u, 1u, 2u, 5u, L / 10, L / 3, L / 2, L - 1, L}) {
      std::uint64_t size = mco_prefix_size(data, n, "m.mco");
      EXPECT_GE(size, previous);
      previous = size;
      std::string_view prefix = std::string_view(data).substr(0, size);
      McLodModel r = read_mco_data(prefix, "m.mco", {.max_priority = n});
      EXPECT_EQ(r.priorities(), n);
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

// A cut file read as a prefix: up to the last priority it holds in full,
// the same levels as the whole model; the summary says how much is there.
TEST(McoFile, CutFilesReadAsAPrefix) {
  McLodModel t = small_model(false);
  const std::string data = write_mco_data(t);
  const McoFileSummary whole = summarize_mco_data(data, "m.mco");
  EXPECT_FALSE(whole.truncated());
  EXPECT_EQ(whole.version, kMcoVersion);
  EXPECT_EQ(whole.priorities, t.priorities());
  EXPECT_EQ(whole.full_triangles, t.full_triangles());
  EXPECT_EQ(whole.complete_priorities, t.priorities() + 1u);
  const std::uint32_t n = t.priorities() / 3;
  const std::uint64_t size = mco_prefix_size(data, n, "m.mco");
  // One byte short of priority n + 1: n is the last one held.
  const std::string_view cut =
      std::string_view(data).substr(0, mco_prefix_size(data, n + 1, "m.mco") - 1);
  ASSERT_GT(cut.size(), size);
  const McoFileSummary s = summarize_mco_data(cut, "m.mco");
  EXPECT_TRUE(s.truncated());
  EXPECT_EQ(s.complete_priorities, n + 1u);
  EXPECT_EQ(s.full_triangles, t.full_triangles());
  McLodModel r = read_mco_data(cut, "m.mco", {.prefix = true});
  EXPECT_EQ(r.priorities(), n);
  EXPECT_EQ(extract_mc_mesh(r, {.priority = n}).mesh.triangles,
            extract_mc_mesh(t, {.priority = n}).mesh.triangles);
  // Without the prefix option a cut file is an error; so is a cut before
  // priority 0 even with it.
  EXPECT_THROW(read_mco_data(cut, "m.mco"), DataError);
  EXPECT_THROW(read_mco_data(data.substr(0, 100), "m.mco", {.prefix = true}), DataError);
}

// Version 3 files (no full triangle count in the header) are still read.
TEST(McoFile, VersionThreeIsRead) {
  McLodModel t = small_model(false);
  std::string data = write_mco_data(t);
  const std::uint32_t three = 3, zero = 0;
  std::memcpy(data.data() + 8, &three, 4);
  std::memcpy(data.data() + 36, &zero, 4);
  std::uint64_t h = 1469598103934665603ULL;  // the header's FNV-1a 64, made again
  for (std::size_t i = 0; i < 80; ++i)
    h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ULL;
  std::memcpy(data.data() + 80, &h, 8);
  const McoFileSummary s = summarize_mco_data(data, "m.mco");
  EXPECT_EQ(s.version, 3u);
  EXPECT_EQ(s.full_triangles, 0u);
  EXPECT_EQ(read_mco_data(data, "m.mco").accumulated, t.accumulated);
}

}  // namespace
}  // namespace lodforge
