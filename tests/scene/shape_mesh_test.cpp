#include "lodforge/scene/shape_mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::scene {
namespace {

/// Calls f(visit) for every shape of a VRML 1.0 text.
template <class F>
void for_each_shape(const std::string& body, F f) {
  const Scene s = vrml1::read_vrml1("#VRML V1.0 ascii\nSeparator {\n" + body + "\n}\n").scene;
  traverse(s, [&](const ShapeVisit& v) { f(v); });
}

TEST(ShapeMesh, TrianglesPassThroughAndPolygonsAreTriangulated) {
  for_each_shape(
      "Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 2 0 0] }\n"
      "IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 1, 2, 3, -1, 4, 1, 0] }",
      [](const ShapeVisit& v) {
        const TriangleMesh m = shape_mesh(v);
        ASSERT_EQ(m.triangles.size(), 1u + 2 + 1);
        EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
        EXPECT_EQ(m.triangles[3], (Triangle{4, 1, 0}));
      });
}

TEST(ShapeMesh, ADegenerateTriangleIsKeptAndReported) {
  for_each_shape(
      "Coordinate3 { point [0 0 0, 1 0 0, 2 0 0, 0 1 0] }\n"
      "IndexedFaceSet { coordIndex [0, 1, 2, -1, 0, 1, 3, -1] }",
      [](const ShapeVisit& v) {
        Log log;
        const TriangleMesh m = shape_mesh(v, {}, &log);
        EXPECT_EQ(m.triangles.size(), 2u);
        ASSERT_EQ(log.entries().size(), 1u);
        EXPECT_THAT(log.entries()[0].text, ::testing::HasSubstr("coordIndex[0] is degenerate"));
      });
}

TEST(ShapeMesh, AnIndexOutOfRangeIsADataErrorWithItsLine) {
  for_each_shape(
      "Coordinate3 { point [0 0 0, 1 0 0, 1 1 0] }\n"
      "IndexedFaceSet { coordIndex [0, 1, 5, -1] }",
      [](const ShapeVisit& v) {
        EXPECT_THAT([&] { shape_mesh(v); },
                    ::testing::ThrowsMessage<DataError>(
                        ::testing::HasSubstr("coordIndex[2] = 5 is out of range")));
        EXPECT_THAT([&] { shape_counts(v); },
                    ::testing::ThrowsMessage<DataError>(
                        ::testing::HasSubstr("coordIndex[2] = 5 is out of range")));
      });
}

/// shape_counts must say what shape_mesh builds, for every shape of the
/// real corpus (Inventor strips, primitives and point sets included).
TEST(ShapeCounts, AgreeWithTheBuiltMeshOnTheCorpus) {
  namespace fs = std::filesystem;
  std::size_t shapes = 0;
  for (const char* dir : {"vrml1", "inventor"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(LODFORGE_SHARED_DATA) / dir)) {
      if (!e.is_regular_file()) continue;
      vrml1::ReadResult r;
      try {
        r = vrml1::read_vrml1_file(e.path().string());
      } catch (const std::exception&) {
        continue;  // files the reader refuses are the reader tests' business
      }
      traverse(r.scene, [&](const ShapeVisit& v) {
        TriangleMesh m;
        try {
          m = shape_mesh(v);
        } catch (const DataError& err) {
          EXPECT_THROW(shape_counts(v), DataError) << e.path() << " " << err.what();
          return;
        }
        const ShapeCounts c = shape_counts(v);
        ++shapes;
        EXPECT_EQ(c.triangles, m.triangle_count()) << e.path() << " line " << v.shape.first_line;
        EXPECT_EQ(c.vertices, m.vertex_count()) << e.path() << " line " << v.shape.first_line;
        EXPECT_EQ(c.segments, m.lines.size()) << e.path() << " line " << v.shape.first_line;
        Box3 box;
        for (const Vec3& p : m.positions) box.add(p);
        EXPECT_EQ(c.bounds.lo, box.lo) << e.path();
        EXPECT_EQ(c.bounds.hi, box.hi) << e.path();
      });
    }
  EXPECT_GT(shapes, 1000u);
}

}  // namespace
}  // namespace lodforge::scene
