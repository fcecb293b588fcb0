#include "lodforge/mesh/triangle_stream.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/temp_dir.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/mesh/mesh_io.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;

/// Bytes of a binary file, each value in the byte order asked for.
struct Bytes {
  std::string data;
  bool big = false;
  template <class T>
  Bytes& put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    data.append(b, sizeof(T));
    return *this;
  }
  Bytes& text(std::string_view s) {
    data += s;
    return *this;
  }
};

/// Everything a stream visits, in order.
struct Visited {
  std::vector<StreamedTriangle> triangles;
  std::vector<std::uint64_t> firsts;  ///< `first` of each chunk
  std::uint64_t returned = 0;
};

Visited visit_all(const TriangleStream& s) {
  Visited v;
  v.returned =
      s.for_each_triangle([&](std::span<const StreamedTriangle> chunk, std::uint64_t first) {
        v.firsts.push_back(first);
        v.triangles.insert(v.triangles.end(), chunk.begin(), chunk.end());
      });
  return v;
}

std::array<std::uint64_t, 3> ids(const StreamedTriangle& t) {
  return t.vertex;
}

class TriangleStreamTest : public testing::TempDirTest {
 protected:
  std::string file(const std::string& name, const Bytes& b) {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << b.data;
    return p;
  }
  /// The message of the DataError that opening or reading `p` throws.
  static std::string error_of(const std::string& p) {
    try {
      TriangleStream s(p);
      visit_all(s);
      s.for_each_vertex([](std::span<const Vec3>, std::uint64_t) {});
    } catch (const DataError& e) {
      return e.what();
    }
    return "";
  }
};

// A unit square as float x y z with two more float properties (the bunny's
// confidence and intensity), faces as uchar-counted int lists.
Bytes square_ply() {
  Bytes b;
  b.text(
      "ply\nformat binary_little_endian 1.0\ncomment a square\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nproperty float confidence\n"
      "property float intensity\nelement face 2\nproperty list uchar int vertex_indices\n"
      "end_header\n");
  const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (auto& p : xy) b.put(p[0]).put(p[1]).put(0.5f).put(9.0f).put(-9.0f);
  b.put<std::uint8_t>(3).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(2);
  b.put<std::uint8_t>(3).put<std::int32_t>(0).put<std::int32_t>(2).put<std::int32_t>(3);
  return b;
}

TEST_F(TriangleStreamTest, SquareGivesItsTwoTrianglesWithPositions) {
  TriangleStream s(file("square.ply", square_ply()));
  EXPECT_EQ(s.format(), MeshFormat::kPly);
  EXPECT_EQ(s.vertex_count(), 4u);
  EXPECT_EQ(s.face_count(), 2u);
  const Visited v = visit_all(s);
  ASSERT_EQ(v.triangles.size(), 2u);
  EXPECT_EQ(v.returned, 2u);
  EXPECT_EQ(ids(v.triangles[0]), (std::array<std::uint64_t, 3>{0, 1, 2}));
  EXPECT_EQ(ids(v.triangles[1]), (std::array<std::uint64_t, 3>{0, 2, 3}));
  EXPECT_EQ(v.triangles[1].corner[2], (Vec3{0, 1, 0.5f}));  // extra properties skipped
  // A second pass reads the file again and gives the same.
  EXPECT_EQ(visit_all(s).triangles.size(), 2u);
}

TEST_F(TriangleStreamTest, PolygonsAreFannedAndSmallFacesSkipped) {
  // A pentagon (3 triangles), a 2-gon (nothing), a quad (2): short indices,
  // int counts, a material after the list.
  Bytes b;
  b.text(
      "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nelement face 3\n"
      "property list int ushort vertex_indices\nproperty int material_index\nend_header\n");
  for (int i = 0; i < 5; ++i) b.put(float(i)).put(0.0f).put(0.0f);
  b.put<std::int32_t>(5);
  for (std::uint16_t i : {0, 1, 2, 3, 4}) b.put(i);
  b.put<std::int32_t>(7);
  b.put<std::int32_t>(2).put<std::uint16_t>(0).put<std::uint16_t>(1).put<std::int32_t>(7);
  b.put<std::int32_t>(4);
  for (std::uint16_t i : {4, 3, 2, 1}) b.put(i);
  b.put<std::int32_t>(7);
  const Visited v = visit_all(TriangleStream(file("fan.ply", b)));
  ASSERT_EQ(v.triangles.size(), 5u);
  EXPECT_EQ(ids(v.triangles[0]), (std::array<std::uint64_t, 3>{0, 1, 2}));
  EXPECT_EQ(ids(v.triangles[2]), (std::array<std::uint64_t, 3>{0, 3, 4}));
  EXPECT_EQ(ids(v.triangles[3]), (std::array<std::uint64_t, 3>{4, 3, 2}));
  EXPECT_EQ(ids(v.triangles[4]), (std::array<std::uint64_t, 3>{4, 2, 1}));
}

TEST_F(TriangleStreamTest, BigEndianDoublesAfterAnElementWithLists) {
  // An element with a list before the vertices: their offset is found by
  // reading through it. Double coordinates, uint indices, big-endian.
  Bytes b;
  b.big = true;
  b.text(
      "ply\nformat binary_big_endian 1.0\nelement note 2\nproperty list uchar uchar text\n"
      "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n");
  b.put<std::uint8_t>(2).put<std::uint8_t>('h').put<std::uint8_t>('i');
  b.put<std::uint8_t>(0);
  b.put(1.5).put(2.5).put(3.5).put(-1.0).put(0.0).put(0.0).put(0.0).put(0.0).put(1e3);
  b.put<std::uint8_t>(3).put<std::uint32_t>(2).put<std::uint32_t>(0).put<std::uint32_t>(1);
  const Visited v = visit_all(TriangleStream(file("big.ply", b)));
  ASSERT_EQ(v.triangles.size(), 1u);
  EXPECT_EQ(v.triangles[0].corner[0], (Vec3{0, 0, 1000}));
  EXPECT_EQ(v.triangles[0].corner[1], (Vec3{1.5f, 2.5f, 3.5f}));
}

TEST_F(TriangleStreamTest, ChunksNumberTheirFirstTriangle) {
  TriangleStream s(file("square.ply", square_ply()), {.chunk_triangles = 1});
  const Visited v = visit_all(s);
  EXPECT_EQ(v.firsts, (std::vector<std::uint64_t>{0, 1}));
  std::vector<std::uint64_t> vertex_firsts;
  std::vector<Vec3> vertices;
  s.for_each_vertex([&](std::span<const Vec3> chunk, std::uint64_t first) {
    vertex_firsts.push_back(first);
    vertices.insert(vertices.end(), chunk.begin(), chunk.end());
  });
  EXPECT_EQ(vertex_firsts, (std::vector<std::uint64_t>{0, 1, 2, 3}));
  EXPECT_EQ(vertices[2], (Vec3{1, 1, 0.5f}));
}

// The bunny written as binary PLY and binary STL streams as read_mesh reads it.
TEST_F(TriangleStreamTest, BunnyStreamsAsReadMeshReadsIt) {
  const std::filesystem::path bunny_path =
      std::filesystem::path(LODFORGE_SHARED_DATA) / "meshes" / "bun_zipper.ply";
  if (!std::filesystem::exists(bunny_path)) GTEST_SKIP() << bunny_path << " missing";
  const TriangleMesh bunny = read_mesh(bunny_path.string());
  const std::string ply = path("bunny.ply"), stl = path("bunny.stl");
  write_mesh(bunny, ply);
  write_mesh(bunny, stl);
  for (const std::string& p : {ply, stl}) {
    SCOPED_TRACE(p);
    TriangleStream s(p, {.chunk_triangles = 1000});
    const Visited v = visit_all(s);
    ASSERT_EQ(v.triangles.size(), bunny.triangle_count());
    for (std::size_t f = 0; f < bunny.triangle_count(); f += 97)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(v.triangles[f].corner[c], bunny.positions[bunny.triangles[f][c]]) << f;
    if (p == ply) EXPECT_EQ(ids(v.triangles[5])[1], bunny.triangles[5][1]);
    if (p == stl) EXPECT_EQ(ids(v.triangles[5])[1], 3u * 5 + 1);
  }
}

TEST_F(TriangleStreamTest, TruncatedAndBadFilesNameTheFileAndWhatWasExpected) {
  const std::string good = square_ply().data;
  // Truncated in the faces: the last index is missing.
  EXPECT_THAT(error_of(file("cut.ply", Bytes{good.substr(0, good.size() - 2)})),
              HasSubstr("cut.ply: byte " + std::to_string(good.size() - 4) +
                        ": expected 4 bytes for a vertex index, got end of file"));
  // Truncated in the vertices.
  const std::size_t header = good.find("end_header\n") + 11;
  EXPECT_THAT(error_of(file("v.ply", Bytes{good.substr(0, header + 30)})),
              HasSubstr("v.ply: byte " + std::to_string(header) +
                        ": expected 4 vertices of 20 bytes, got end of file"));
  // An index out of range.
  std::string bad = good;
  bad[bad.size() - 4] = 9;
  EXPECT_THAT(error_of(file("idx.ply", Bytes{bad})),
              HasSubstr("idx.ply: byte " + std::to_string(bad.size() - 4) +
                        ": face 1: vertex index 9 out of range (4 vertices)"));
  // A vertex coordinate that is not finite.
  std::string nan = good;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + header + 20, &q, 4);
  EXPECT_THAT(error_of(file("nan.ply", Bytes{nan})),
              HasSubstr("vertex 1 has a coordinate that is not a finite number"));
  // A malformed header is a ParseError with its line.
  EXPECT_THROW(TriangleStream(file("h.ply", Bytes{"ply\nformat binary_little_endian 1.0\n"
                                                  "element vertex 1\nproperty flot x\n"})),
               ParseError);
}

TEST_F(TriangleStreamTest, KindsItCannotStreamAreRefusedWithAReason) {
  auto refused = [&](const std::string& name, const std::string& bytes, const std::string& why) {
    const std::string message = error_of(file(name, Bytes{bytes}));
    EXPECT_THAT(message, HasSubstr(name + ": " + why)) << name;
    EXPECT_THAT(message, HasSubstr("takes a binary PLY or a binary STL")) << name;
    EXPECT_FALSE(TriangleStream::accepts(path(name)));
  };
  refused("a.ply",
          "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
          "property float y\nproperty float z\nend_header\n",
          "an ASCII PLY file");
  refused("a.stl", "solid x\nfacet normal 0 0 1\nendsolid x\n", "an ASCII STL file");
  refused("z.ply", gzip(square_ply().data), "gzip-compressed");
  refused("l.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
          "property float y\nproperty float z\nproperty list uchar int n\nend_header\n",
          "element 'vertex' has a list property");
  refused("t.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
          "property float y\nproperty float z\nelement tristrips 1\n"
          "property list int int vertex_indices\nend_header\n",
          "element 'tristrips'");
  EXPECT_TRUE(TriangleStream::accepts(file("square.ply", square_ply())));
}

TEST_F(TriangleStreamTest, StlCountMustFitTheFile) {
  Bytes b;
  b.text(std::string(80, ' ')).put<std::uint32_t>(2);
  b.text(std::string(50, '\0'));  // one record of the two
  EXPECT_THAT(error_of(file("short.stl", b)),
              HasSubstr("short.stl: byte 134: expected 184 bytes for 2 triangles"));
  EXPECT_THAT(error_of(file("tiny.stl", Bytes{"abc"})),
              HasSubstr("tiny.stl: byte 3: expected a binary STL header of 84 bytes"));
}

}  // namespace
}  // namespace lodforge
