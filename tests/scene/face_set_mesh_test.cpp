#include "lodforge/scene/face_set_mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "lodforge/core/error.h"

namespace lodforge::scene {
namespace {

using Runs = std::vector<FaceRun>;

TEST(FaceRuns, RunsBetweenSeparatorsWithOrWithoutAFinalOne) {
  const std::vector<std::int32_t> ci{0, 1, 2, -1, -1, 3, 4, 5, 6, -1, 7, 8};
  EXPECT_EQ(face_runs(ci, 9, {}), (Runs{{0, 3}, {5, 9}, {10, 12}}));
  Runs visited;
  for_each_index_run(ci, [&](std::size_t b, std::size_t e) { visited.emplace_back(b, e); });
  EXPECT_EQ(visited, face_runs(ci, 9, {}));
  EXPECT_TRUE(face_runs(std::vector<std::int32_t>{-1, -1}, 0, {}).empty());
  // Any negative index ends a face, as -1 does.
  EXPECT_EQ(face_runs(std::vector<std::int32_t>{0, 1, 2, -7, 2, 1, 0}, 3, {}),
            (Runs{{0, 3}, {4, 7}}));
}

TEST(FaceRuns, AnIndexOutOfRangeIsADataErrorNamingTheFieldAndPosition) {
  const std::vector<std::int32_t> ci{0, 1, 2, -1, 2, 1, 5, -1, 9};
  EXPECT_THAT(
      [&] {
        face_runs(ci, 3, {"line 4: IndexedFaceSet", "Coordinate3"});
      },
      ::testing::ThrowsMessage<DataError>(
          "line 4: IndexedFaceSet coordIndex[6] = 5 is out of range (the current "
          "Coordinate3 has 3 points)"));
  EXPECT_EQ(face_runs(ci, 10, {}).size(), 3u);
}

TEST(FaceTriangles, ATrianglePassesAsItIsAndTooFewCornersAddNothing) {
  const std::vector<Vec3> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> poly{2, 0, 1};
  FaceTriangles r = face_triangles(pts, poly, {}, tris);
  EXPECT_EQ(r.triangles, 1u);
  EXPECT_FALSE(r.degenerate);
  EXPECT_EQ(tris, (std::vector<Triangle>{{2, 0, 1}}));
  poly = {0, 1};
  r = face_triangles(pts, poly, {}, tris);
  EXPECT_EQ(r.corners, 2u);
  EXPECT_EQ(r.triangles, 0u);
  EXPECT_EQ(tris.size(), 1u);
}

TEST(FaceTriangles, AConcavePolygonGetsTrianglesInsideIt) {
  // An L of six corners: the reflex corner 3 (1,1) must not be fanned over.
  const std::vector<Vec3> pts{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<std::uint32_t> poly{0, 1, 2, 3, 4, 5};
  std::vector<Triangle> tris;
  const FaceTriangles r = face_triangles(pts, poly, {}, tris);
  ASSERT_EQ(r.triangles, 4u);
  EXPECT_FALSE(r.degenerate || r.not_simple);
  double area = 0;
  for (const Triangle& t : tris) {
    const Vec3 a = pts[t[1]] - pts[t[0]], b = pts[t[2]] - pts[t[0]];
    const double z = double(a.x) * b.y - double(a.y) * b.x;
    EXPECT_GT(z, 0) << "wound like the face";
    area += z / 2;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);  // the L's area: no triangle outside it
}

TEST(FaceTriangles, RepeatedCornersMergedOrTheirTrianglesDropped) {
  const std::vector<Vec3> pts{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  std::vector<Triangle> tris;
  // 0 0 1 2 0: merged, one triangle of three distinct corners.
  std::vector<std::uint32_t> poly{0, 0, 1, 2, 0};
  FaceTriangles r = face_triangles(pts, poly, {.merge_repeated_corners = true}, tris);
  EXPECT_EQ(r.corners, 3u);
  EXPECT_EQ(tris, (std::vector<Triangle>{{0, 1, 2}}));
  // Unmerged, the triangles that use a vertex twice can be left out.
  tris.clear();
  poly = {0, 0, 1, 2};
  r = face_triangles(pts, poly, {.drop_repeated_vertex_triangles = true}, tris);
  EXPECT_EQ(r.corners, 4u);
  ASSERT_EQ(tris.size(), r.triangles);
  for (const Triangle& t : tris) EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
  // Two distinct corners after merging: nothing.
  tris.clear();
  poly = {1, 1, 2, 2, 1};
  EXPECT_EQ(face_triangles(pts, poly, {.merge_repeated_corners = true}, tris).triangles, 0u);
  EXPECT_TRUE(tris.empty());
}

TEST(FaceTriangles, AFlatQuadStaysAQuadUnlessQuadsAreOff) {
  const std::vector<Vec3> pts{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> poly{0, 1, 2, 3};
  EXPECT_TRUE(face_triangles(pts, poly, {}, tris).keep_as_quad);
  EXPECT_EQ(tris.size(), 2u);
  FaceTriangulation no_quads;
  no_quads.triangulation.keep_quads = false;
  EXPECT_FALSE(face_triangles(pts, poly, no_quads, tris).keep_as_quad);
}

TEST(FaceTriangles, ACollinearFaceIsReportedDegenerate) {
  const std::vector<Vec3> pts{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> tri{0, 1, 2}, quad{0, 1, 2, 3};
  EXPECT_TRUE(face_triangles(pts, tri, {}, tris).degenerate);
  EXPECT_FALSE(face_triangles(pts, tri, {.diagnose_triangles = false}, tris).degenerate);
  EXPECT_TRUE(face_triangles(pts, quad, {}, tris).degenerate);
}

// Two faces, a triangle and a quad: positions 0..2 and 4..7 of coordIndex.
const std::vector<std::int32_t> kTwoFaces{0, 1, 2, -1, 2, 1, 3, 4, -1};

// The value index of every corner (face, corner number, coordIndex position).
std::vector<std::int64_t> corner_values(const FaceSetAttribute& a) {
  std::vector<std::int64_t> out;
  std::size_t corner = 0;
  const std::vector<FaceRun> runs = face_runs(kTwoFaces, 5, {});
  for (std::size_t f = 0; f < runs.size(); ++f)
    for (std::size_t p = runs[f].first; p < runs[f].second; ++p, ++corner)
      out.push_back(corner_attribute(a, f, corner, p, "line 3: IndexedFaceSet"));
  return out;
}

using Values = std::vector<std::int64_t>;

TEST(CornerAttribute, EachBindingPicksItsValue) {
  const std::vector<std::int32_t> face_index{1, 0};
  const std::vector<std::int32_t> vertex_index{6, 5, 4, -1, 3, 2, 1, 0, -1};
  const std::vector<std::int32_t> default_index{-1};
  auto with = [&](Binding b, const std::vector<std::int32_t>* index) {
    return corner_values({{b, index, &kTwoFaces}, 7, "materialIndex"});
  };
  EXPECT_EQ(with(Binding::kOverall, nullptr), Values(7, -1));
  EXPECT_EQ(with(Binding::kPerFace, nullptr), (Values{0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(with(Binding::kPerFaceIndexed, &face_index), (Values{1, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(with(Binding::kPerVertex, nullptr), (Values{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(with(Binding::kPerVertexIndexed, &vertex_index), (Values{6, 5, 4, 3, 2, 1, 0}));
  // PER_VERTEX_INDEXED with the index field left at [] or [-1]: coordIndex.
  EXPECT_EQ(with(Binding::kPerVertexIndexed, &default_index), (Values{0, 1, 2, 2, 1, 3, 4}));
  EXPECT_EQ(with(Binding::kPerVertexIndexed, nullptr), (Values{0, 1, 2, 2, 1, 3, 4}));
}

TEST(CornerAttribute, Vrml97BindingsByPerVertexAndIndexField) {
  EXPECT_EQ(vrml97_binding(true, true), Binding::kPerVertexIndexed);
  EXPECT_EQ(vrml97_binding(true, false), Binding::kPerVertexIndexed);
  EXPECT_EQ(vrml97_binding(false, true), Binding::kPerFaceIndexed);
  EXPECT_EQ(vrml97_binding(false, false), Binding::kPerFace);
}

TEST(CornerAttribute, ABadIndexIsADataErrorNamingTheFieldAndIndex) {
  using ::testing::ThrowsMessage;
  const std::vector<std::int32_t> past{0, 1, 2, -1, 0, 9, 1, 2, -1};
  const std::vector<std::int32_t> minus{0, 1, -1, -1, 0, 1, 2, 3, -1};
  const std::vector<std::int32_t> short_faces{0};
  const std::vector<std::int32_t> short_corners{0, 1, 2, -1, 0};
  auto values = [&](Binding b, const std::vector<std::int32_t>* index, std::size_t count) {
    return [=] { corner_values({{b, index, &kTwoFaces}, count, "colorIndex"}); };
  };
  EXPECT_THAT(values(Binding::kPerVertexIndexed, &past, 4),
              ThrowsMessage<DataError>(
                  "line 3: IndexedFaceSet colorIndex[5] = 9 is out of range (4 values)"));
  // A -1 at a corner (not at the end of a face) is no value either.
  EXPECT_THAT(values(Binding::kPerVertexIndexed, &minus, 4),
              ThrowsMessage<DataError>(
                  "line 3: IndexedFaceSet colorIndex[2] = -1 is out of range (4 values)"));
  EXPECT_THAT(values(Binding::kPerVertexIndexed, &short_corners, 4),
              ThrowsMessage<DataError>("line 3: IndexedFaceSet colorIndex has no entry 5 (5 "
                                       "entries)"));
  // coordIndex read for a default index field is named as such.
  EXPECT_THAT(values(Binding::kPerVertexIndexed, nullptr, 4),
              ThrowsMessage<DataError>(
                  "line 3: IndexedFaceSet coordIndex[7] = 4 is out of range (4 values)"));
  EXPECT_THAT(values(Binding::kPerFaceIndexed, &short_faces, 4),
              ThrowsMessage<DataError>("line 3: IndexedFaceSet colorIndex has no entry 1 (1 "
                                       "entries)"));
  EXPECT_THAT(values(Binding::kPerFace, nullptr, 1),
              ThrowsMessage<DataError>("line 3: IndexedFaceSet PER_FACE binding: face 1 takes "
                                       "value 1, out of range (1 values)"));
  EXPECT_THAT(values(Binding::kPerVertex, nullptr, 6),
              ThrowsMessage<DataError>("line 3: IndexedFaceSet PER_VERTEX binding: corner 6 takes "
                                       "value 6, out of range (6 values)"));
  EXPECT_NO_THROW(values(Binding::kOverall, nullptr, 0)());
}

}  // namespace
}  // namespace lodforge::scene
