#include "lodforge/mesh/mesh_io.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/expect_near.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/mesh/adjacency.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

TriangleMesh parse(std::string_view text, MeshFormat f, Log* log = nullptr) {
  return read_mesh_data(text, f, "t", {.log = log});
}

/// The message of the DataError that parsing `text` throws ("" if none).
std::string error_of(std::string_view text, MeshFormat f) {
  try {
    parse(text, f);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

/// A mesh with every attribute: a 2x2 grid with colours and two materials,
/// plus two line segments.
TriangleMesh rich_mesh() {
  TriangleMesh m = test::make_grid(2);
  for (std::size_t i = 0; i < m.vertex_count(); ++i)
    m.colors.push_back({static_cast<float>(i * 20) / 255.0f, 1.0f, 0.0f});
  m.normals[4] = normalized(Vec3{0.3f, 0.1f, 1.0f});
  m.materials = {0, 0, 0, 0, 1, 1, 1, 1};
  m.lines = {{0, 8}, {2, 6}};
  return m;
}

using test::expect_near;

struct RoundTrip {
  const char* name;
  MeshWriteOptions options;
  bool materials, lines;
};

TEST(MeshIo, RoundTripEveryFormatAndAttribute) {
  const RoundTrip cases[] = {
      {"ply-binary", {.format = MeshFormat::kPly, .binary = true}, true, true},
      {"ply-ascii", {.format = MeshFormat::kPly, .binary = false}, true, true},
      {"obj", {.format = MeshFormat::kObj}, true, true},
      {"off", {.format = MeshFormat::kOff}, false, true},
  };
  TriangleMesh m = rich_mesh();
  for (const RoundTrip& c : cases) {
    SCOPED_TRACE(c.name);
    std::string bytes = write_mesh_data(m, c.options);
    TriangleMesh r = read_mesh_data(bytes, c.options.format, c.name);
    ASSERT_EQ(r.positions, m.positions);
    EXPECT_EQ(r.triangles, m.triangles);
    EXPECT_EQ(r.texcoords, m.texcoords);
    ASSERT_EQ(r.normals.size(), m.normals.size());
    for (std::size_t i = 0; i < m.normals.size(); ++i)
      expect_near(r.normals[i], m.normals[i], 1e-6f);
    ASSERT_EQ(r.colors.size(), m.colors.size());
    for (std::size_t i = 0; i < m.colors.size(); ++i) expect_near(r.colors[i], m.colors[i], 1e-6f);
    if (c.materials) EXPECT_EQ(r.materials, m.materials);
    if (c.lines) EXPECT_EQ(r.lines, m.lines);
  }
}

TEST(MeshIo, RoundTripBareMeshes) {
  for (MeshFormat f : {MeshFormat::kPly, MeshFormat::kObj, MeshFormat::kOff}) {
    TriangleMesh m = test::make_torus();
    TriangleMesh r = read_mesh_data(write_mesh_data(m, {.format = f}), f, "t");
    EXPECT_EQ(r.positions, m.positions);
    EXPECT_EQ(r.triangles, m.triangles);
    EXPECT_FALSE(r.has_normals() || r.has_colors() || r.has_texcoords() || r.has_materials());
  }
}

TEST(MeshIo, StlRoundTripWeldsBackToTheMesh) {
  TriangleMesh m = test::make_icosphere(2);
  for (bool binary : {true, false}) {
    std::string bytes = write_mesh_data(m, {.format = MeshFormat::kStl, .binary = binary});
    TriangleMesh r = read_mesh_data(bytes, MeshFormat::kStl, "t.stl");
    ASSERT_EQ(r.vertex_count(), m.vertex_count());
    ASSERT_EQ(r.triangle_count(), m.triangle_count());
    for (std::size_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(r.positions[r.triangles[f][k]], m.positions[m.triangles[f][k]]);
    EXPECT_TRUE(mesh_topology_report(r).closed());
  }
}

TEST(MeshIo, BinaryStlStartingWithSolidIsDetectedBySize) {
  std::string bytes = write_mesh_data(test::make_cube(), {.format = MeshFormat::kStl});
  std::memcpy(bytes.data(), "solid cube", 10);
  TriangleMesh r = read_mesh_data(bytes, MeshFormat::kAuto, "t.stl");
  EXPECT_EQ(r.vertex_count(), 8u);
  EXPECT_EQ(r.triangle_count(), 12u);
}

TEST(MeshIo, AsciiStlWithSeveralSolids) {
  std::string one =
      "solid a\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n "
      "endloop\nendfacet\nendsolid a\n";
  std::string text = one +
                     "SOLID b\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 1 0 0\nVERTEX 1 1 0\n"
                     "VERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID b\n";
  TriangleMesh r = parse(text, MeshFormat::kStl);
  EXPECT_EQ(r.vertex_count(), 4u);
  EXPECT_EQ(r.triangle_count(), 2u);
}

TEST(MeshIo, StlErrors) {
  EXPECT_EQ(
      error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\nendloop\n", MeshFormat::kStl),
      "t:5:1: expected a number for a vertex coordinate, got 'endloop'");
  EXPECT_EQ(error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop\n",
                     MeshFormat::kStl),
            "t:5:1: expected 'vertex', got 'endloop'");
  std::string bytes = write_mesh_data(test::make_cube(), {.format = MeshFormat::kStl});
  bytes.resize(bytes.size() - 10);
  EXPECT_EQ(error_of(bytes, MeshFormat::kStl),
            "t: byte 674: expected 684 bytes for 12 triangles, got end of file");
  std::string nan_stl = write_mesh_data(test::make_tetrahedron(), {.format = MeshFormat::kStl});
  float nan = std::nanf("");
  std::memcpy(nan_stl.data() + 84 + 50 + 16, &nan, 4);
  EXPECT_EQ(error_of(nan_stl, MeshFormat::kStl),
            "t: byte 146: triangle 1: expected finite vertex coordinates, got (1, nan, 1)");
  EXPECT_EQ(error_of("short", MeshFormat::kStl),
            "t: byte 5: expected a binary STL header of 84 bytes or an ASCII 'solid', got 5 bytes");
}

// ---- PLY -------------------------------------------------------------------

const char* kPlyHeader = "ply\nformat ascii 1.0\ncomment c\n";

TEST(MeshIo, PlyAsciiWithAttributesAndQuads) {
  std::string text =
      std::string(kPlyHeader) +
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
      "property float texture_u\nproperty float texture_v\n"
      "element face 1\nproperty list uchar uint vertex_index\nend_header\n"
      "0 0 0 255 0 0 255 0 0\n1 0 0 0 255 0 255 1 0\n1 1 0 0 0 255 255 1 1\n"
      "0 1 0 255 255 255 255 0 1\n4 0 1 2 3\n";
  TriangleMesh m = parse(text, MeshFormat::kPly);
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 2u);
  EXPECT_EQ(m.colors[1], (Vec3{0, 1, 0}));
  EXPECT_EQ(m.texcoords[2], (Vec2{1, 1}));
}

TEST(MeshIo, PlyFloatColoursAndNormalsAreNormalised) {
  std::string text = std::string(kPlyHeader) +
                     "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "property float nx\nproperty float ny\nproperty float nz\n"
                     "property float red\nproperty float green\nproperty float blue\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     "0 0 0 0 0 2 0.5 0.25 1\n1 0 0 0 0 1 0 0 0\n0 1 0 0 3 0 1 1 1\n3 0 1 2\n";
  TriangleMesh m = parse(text, MeshFormat::kPly);
  EXPECT_EQ(m.colors[0], (Vec3{0.5f, 0.25f, 1}));
  EXPECT_EQ(m.normals[0], (Vec3{0, 0, 1}));
  EXPECT_EQ(m.normals[2], (Vec3{0, 1, 0}));
}

TEST(MeshIo, PlyTristripsWithRestarts) {
  // Strip 0 1 2 3 gives (0,1,2) and (2,1,3); after -1, strip 1 3 4 gives (1,3,4).
  std::string text = std::string(kPlyHeader) +
                     "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                     "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                     "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 1 0\n8 0 1 2 3 -1 1 3 4\n";
  TriangleMesh m = parse(text, MeshFormat::kPly);
  EXPECT_EQ(m.triangles, (std::vector<Triangle>{{0, 1, 2}, {2, 1, 3}, {1, 3, 4}}));
}

TEST(MeshIo, PlySkipsUnknownElementsAndProperties) {
  std::string text =
      std::string(kPlyHeader) +
      "element material 2\nproperty list uchar float coeffs\nproperty int id\n"
      "element vertex 3\nproperty double x\nproperty list uchar int junk\nproperty double y\n"
      "property double z\nproperty float confidence\n"
      "element face 1\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
      "property list uchar float texcoord\nend_header\n"
      "3 1 2 3 7\n0 8\n0 2 5 5 0 0 0.5\n1 0 0 0 0.5\n0 0 1 0 0.5\n"
      "9 3 0 1 2 6 0 0 1 0 0 1\n";
  Log log;
  TriangleMesh m = parse(text, MeshFormat::kPly, &log);
  EXPECT_EQ(m.vertex_count(), 3u);
  EXPECT_EQ(m.positions[1], (Vec3{1, 0, 0}));
  EXPECT_EQ(m.triangles, (std::vector<Triangle>{{0, 1, 2}}));
  EXPECT_EQ(log.count(LogLevel::kWarning), 1u);  // element 'material' skipped
}

TEST(MeshIo, PlyBinaryBigEndian) {
  std::string text =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar short vertex_indices\nend_header\n";
  auto be32 = [&](float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 3; k >= 0; --k) text += static_cast<char>((u >> (8 * k)) & 0xff);
  };
  float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (float f : v) be32(f);
  text += '\x03';
  for (int i : {0, 1, 2}) text += '\0', text += static_cast<char>(i);
  TriangleMesh m = parse(text, MeshFormat::kPly);
  EXPECT_EQ(m.positions[1], (Vec3{1, 0, 0}));
  EXPECT_EQ(m.triangles, (std::vector<Triangle>{{0, 1, 2}}));
}

TEST(MeshIo, PlyErrors) {
  std::string head = std::string(kPlyHeader) +
                     "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(error_of(head + "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", MeshFormat::kPly),
            "t:12:3: expected a number for 'y' of vertex 1, got 'abc'");
  EXPECT_EQ(error_of(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", MeshFormat::kPly),
            "t:14:7: face 0: vertex index 7 out of range (3 vertices)");
  EXPECT_EQ(error_of(head + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", MeshFormat::kPly),
            "t:14:5: face 0: vertex index -1 out of range (3 vertices)");
  EXPECT_EQ(error_of(head + "0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", MeshFormat::kPly),
            "t:12:5: expected a number for 'z' of vertex 1, got 'nan'");
  EXPECT_EQ(error_of(head + "0 0 0\n1 0 0\n", MeshFormat::kPly),
            "t:13:1: expected a number for 'x' of vertex 2, got end of file");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float64x x\nend_header\n",
                     MeshFormat::kPly),
            "t:4:10: expected a property type (char, uchar, short, ushort, int, uint, float, "
            "double), got 'float64x'");
  EXPECT_EQ(error_of("ply\nelement vertex 0\nend_header\n", MeshFormat::kPly),
            "t:2:1: expected a 'format' line in the PLY header");
  EXPECT_EQ(error_of("plx\n", MeshFormat::kPly),
            "t:1:1: expected 'ply' at the start of a PLY file");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
                     MeshFormat::kPly),
            "t:3:1: element 'vertex' needs properties 'x', 'y' and 'z'");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 1\n", MeshFormat::kPly),
            "t:4:1: expected 'end_header', got end of file");

  std::string bin = write_mesh_data(test::make_tetrahedron(), {.format = MeshFormat::kPly});
  std::size_t body = bin.find("end_header\n") + 11;
  EXPECT_EQ(
      error_of(bin.substr(0, body + 20), MeshFormat::kPly),
      fmt::format("t: byte {}: expected 4 bytes for 'z' of vertex 1, got end of file", body + 20));
  std::string bad_index = bin;
  bad_index[body + 48 + 1] = 9;  // first index of face 0
  EXPECT_EQ(error_of(bad_index, MeshFormat::kPly),
            fmt::format("t: byte {}: face 0: vertex index 9 out of range (4 vertices)", body + 53));
  std::string huge =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  EXPECT_EQ(error_of(huge, MeshFormat::kPly),
            fmt::format("t: byte {}: expected 4 bytes for 'x' of vertex 0, got end of file",
                        huge.size()));
}

TEST(MeshIo, PlyFacesBeforeVerticesAreCheckedAtTheEnd) {
  std::string text =
      std::string(kPlyHeader) +
      "element face 1\nproperty list uchar int vertex_indices\n"
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
      "3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(parse(text, MeshFormat::kPly).triangle_count(), 1u);
  text[text.find("3 0 1 2") + 6] = '5';
  EXPECT_EQ(error_of(text, MeshFormat::kPly), "t: vertex index 5 out of range (3 vertices)");
}

// ---- OBJ -------------------------------------------------------------------

TEST(MeshIo, ObjCornersAreUnifiedAndSplit) {
  // Two triangles sharing the edge 1-3 but with different normals there.
  std::string text =
      "# comment\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\nvn 0 0 -1\n"
      "f 1/1/1 2/2/1 3/1/1\nf 2/2/2 4/2/2 3/1/2\n";
  TriangleMesh m = parse(text, MeshFormat::kObj);
  EXPECT_EQ(m.vertex_count(), 6u);  // 2 and 3 split
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (Triangle{4, 3, 5}));
  EXPECT_EQ(m.positions[4], m.positions[1]);
  EXPECT_EQ(m.normals[4], (Vec3{0, 0, -1}));
  EXPECT_EQ(m.normals[3], (Vec3{0, 0, -1}));
  EXPECT_EQ(m.normals[0], (Vec3{0, 0, 1}));
}

TEST(MeshIo, ObjNegativeIndicesPolygonsLinesColoursMaterials) {
  std::string text =
      "mtllib x.mtl\no thing\nv 0 0 0 1 0 0\nv 2 0 0 0 1 0\nv 2 1 0 0 0 1\nv 1 0.5 0 1 1 1\n"
      "v 0 1 0 0.5 0.5 0.5\ng g1\nusemtl red\nf -5 -4 -3 -2 -1\nusemtl blue\nf 1 2 3\n"
      "usemtl red\nf 1 3 5\nl 1 2 3\ns off\ncurv 0 1 1 2\n";
  Log log;
  TriangleMesh m = parse(text, MeshFormat::kObj, &log);
  EXPECT_EQ(m.vertex_count(), 5u);
  EXPECT_EQ(m.triangle_count(), 5u);
  EXPECT_EQ(m.materials, (std::vector<std::uint32_t>{0, 0, 0, 1, 0}));
  EXPECT_EQ(m.lines, (std::vector<Segment>{{0, 1}, {1, 2}}));
  EXPECT_EQ(m.colors[1], (Vec3{0, 1, 0}));
  EXPECT_EQ(log.count(LogLevel::kWarning), 0u);
}

TEST(MeshIo, ObjWarnsAboutUnknownStatements) {
  Log log;
  parse("v 0 0 0\nfrobnicate 1\nfrobnicate 2\n", MeshFormat::kObj, &log);
  ASSERT_EQ(log.count(LogLevel::kWarning), 1u);
  EXPECT_EQ(log.entries()[0].text, "t: OBJ statement 'frobnicate' ignored");
}

TEST(MeshIo, ObjErrors) {
  std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(error_of(v + "f 1 2 5\n", MeshFormat::kObj),
            "t:4:7: face 1: vertex index 5 out of range (3 defined)");
  EXPECT_EQ(error_of(v + "f 1 2 0\n", MeshFormat::kObj),
            "t:4:7: face 1: vertex index 0 out of range (3 defined)");
  EXPECT_EQ(error_of(v + "f 1 2 -4\n", MeshFormat::kObj),
            "t:4:7: face 1: vertex index -4 out of range (3 defined)");
  EXPECT_EQ(error_of(v + "f 1/1 2 3\n", MeshFormat::kObj),
            "t:4:5: face 1: texture coordinate index 1 out of range (0 defined)");
  EXPECT_EQ(error_of(v + "f 1 2 3x\n", MeshFormat::kObj),
            "t:4:8: expected a face corner v, v/vt, v//vn or v/vt/vn, got '3x'");
  EXPECT_EQ(error_of(v + "f 1 2\n", MeshFormat::kObj),
            "t:4:6: f: expected at least 3 corners, got 2");
  EXPECT_EQ(error_of("v 0 0 nan\n", MeshFormat::kObj),
            "t:1:7: expected a number for z of a vertex, got 'nan'");
  EXPECT_EQ(error_of("v 0 0 1e999\n", MeshFormat::kObj),
            "t:1:7: expected a number for z of a vertex, got '1e999'");
  EXPECT_EQ(error_of("v 0 0\n", MeshFormat::kObj),
            "t:1:6: expected a number for z of a vertex, got end of line");
  EXPECT_EQ(error_of("vn 0 0 1 1\n", MeshFormat::kObj), "t:1:10: expected end of line, got '1'");
}

// ---- OFF -------------------------------------------------------------------

TEST(MeshIo, OffVariants) {
  TriangleMesh a = parse(
      "OFF\n# cube corner\n4 2 0\n0 0 0\n1 0 0\n1 1 0 # c\n0 1 0\n4 0 1 2 3\n"
      "2 0 2\n",
      MeshFormat::kOff);
  EXPECT_EQ(a.triangle_count(), 2u);
  EXPECT_EQ(a.lines, (std::vector<Segment>{{0, 2}}));
  TriangleMesh c = parse(
      "COFF 3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n0 1 0 0 0 255 255\n"
      "3 0 1 2 1 0 0\n",
      MeshFormat::kOff);
  EXPECT_EQ(c.colors, (std::vector<Vec3>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  EXPECT_EQ(c.triangle_count(), 1u);
  TriangleMesh n =
      parse("NOFF\n3 1 3\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", MeshFormat::kOff);
  EXPECT_EQ(n.normals[0], (Vec3{0, 0, 1}));
  TriangleMesh bare = parse("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::kOff);
  EXPECT_EQ(bare.triangle_count(), 1u);
}

TEST(MeshIo, OffErrors) {
  EXPECT_EQ(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", MeshFormat::kOff),
            "t:6:8: face 0: vertex index 3 out of range (3 vertices)");
  EXPECT_EQ(error_of("4OFF\n", MeshFormat::kOff),
            "t:1:1: expected OFF, COFF, NOFF, STOFF or a combination, got '4OFF' (only 3D OFF is "
            "supported)");
  EXPECT_EQ(error_of("OFF\n3 1 0\n0 0 0\n1 0 x\n", MeshFormat::kOff),
            "t:4:5: expected a number for a coordinate of a vertex, got 'x'");
  EXPECT_EQ(error_of("OFF\n900000000 1 0\n0 0 0\n", MeshFormat::kOff),
            "t:2:14: 900000000 vertices and 1 faces cannot fit in the 7 bytes that follow");
}

// ---- Dispatch and files ------------------------------------------------------

TEST(MeshIo, FormatFromPathAndContent) {
  EXPECT_EQ(format_from_path("a/b.PLY"), MeshFormat::kPly);
  EXPECT_EQ(format_from_path("b.obj.gz"), MeshFormat::kObj);
  EXPECT_EQ(format_from_path("b.off"), MeshFormat::kOff);
  EXPECT_EQ(format_from_path("b.stl"), MeshFormat::kStl);
  EXPECT_EQ(format_from_path("b.wrl"), MeshFormat::kAuto);
  EXPECT_EQ(parse("OFF 3 1 0 0 0 0 1 0 0 0 1 0 3 0 1 2", MeshFormat::kAuto).triangle_count(), 1u);
  EXPECT_EQ(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::kAuto).triangle_count(), 1u);
  EXPECT_EQ(error_of("hello", MeshFormat::kAuto),
            "t: cannot tell the mesh format (expected PLY, OBJ, OFF or STL)");
  EXPECT_THROW(write_mesh_data(test::make_cube(), {}), DataError);
  TriangleMesh bad = test::make_cube();
  bad.normals.resize(3);
  EXPECT_EQ(error_of("", MeshFormat::kAuto),
            "t: cannot tell the mesh format (expected PLY, OBJ, OFF or STL)");
  try {
    write_mesh_data(bad, {.format = MeshFormat::kPly});
    FAIL();
  } catch (const DataError& e) {
    EXPECT_STREQ(e.what(), "cannot write mesh: 3 normals for 8 vertices");
  }
}

TEST(MeshIo, WriteAndReadFiles) {
  auto dir = std::filesystem::path(LODFORGE_BINARY_DIR) / "mesh_io_test";
  std::filesystem::create_directories(dir);
  TriangleMesh m = test::make_uv_sphere();
  for (const char* name : {"s.ply", "s.obj", "s.off", "s.stl"}) {
    std::string path = (dir / name).string();
    write_mesh(m, path);
    TriangleMesh r = read_mesh(path);
    EXPECT_EQ(r.triangle_count(), m.triangle_count()) << name;
    EXPECT_EQ(r.vertex_count(), m.vertex_count()) << name;
  }
  EXPECT_THROW(write_mesh(m, (dir / "s.xyz").string()), DataError);
  EXPECT_THROW(read_mesh((dir / "missing.ply").string()), DataError);
}

TEST(MeshIo, GzNamesAreWrittenCompressedInTheFormatOfTheRest) {
  auto dir = std::filesystem::path(LODFORGE_BINARY_DIR) / "mesh_io_gz_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  TriangleMesh m = test::make_uv_sphere();
  for (const char* name : {"s.ply.gz", "s.obj.gz", "s.off.gz", "s.stl.gz"}) {
    std::string path = (dir / name).string();
    write_mesh(m, path);
    std::ifstream f(path, std::ios::binary);
    std::string bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    ASSERT_TRUE(is_gzip(bytes)) << name;
    EXPECT_EQ(gunzip(bytes, path), write_mesh_data(m, {.format = format_from_path(path)})) << name;
    TriangleMesh r = read_mesh(path);
    EXPECT_EQ(r.triangle_count(), m.triangle_count()) << name;
    EXPECT_EQ(r.vertex_count(), m.vertex_count()) << name;
  }
  std::filesystem::remove_all(dir);
}

// ---- The real corpus ----------------------------------------------------------

TEST(MeshIo, SharedCorpus) {
  std::filesystem::path dir = std::filesystem::path(LODFORGE_SHARED_DATA) / "meshes";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " missing";
  // Counts from shared/data/SOURCES.md.
  const std::map<std::string, std::pair<std::size_t, std::size_t>> expected = {
      {"bun_zipper.ply", {35947, 69451}},
      {"bun_zipper_res2.ply", {8171, 16301}},
      {"bun_zipper_res3.ply", {1889, 3851}},
      {"bun_zipper_res4.ply", {453, 948}},
      {"stanford-bunny.obj", {35947, 69451}},
      {"horse.ply", {48485, 96966}},
      {"nefertiti.obj", {49971, 99938}},
      {"igea.ply", {134345, 268686}},
      {"fandisk.obj", {6475, 12946}},
      {"rocker-arm.obj", {10044, 20088}},
      {"cow.obj", {2903, 5804}},
      {"suzanne.obj", {507, 968}},
      {"teapot.obj", {3644, 6320}},
  };
  std::size_t read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    if (format_from_path(name) == MeshFormat::kAuto) continue;
    SCOPED_TRACE(name);
    auto t0 = std::chrono::steady_clock::now();
    TriangleMesh m = read_mesh(entry.path().string());
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("  %-22s %7zu vertices %7zu triangles %6.3f s\n", name.c_str(), m.vertex_count(),
                m.triangle_count(), seconds);
    auto it = expected.find(name);
    if (it != expected.end()) {
      EXPECT_EQ(m.vertex_count(), it->second.first);
      EXPECT_EQ(m.triangle_count(), it->second.second);
    }
    for (const Triangle& t : m.triangles)
      for (std::uint32_t v : t) ASSERT_LT(v, m.vertex_count());
    if (name == "horse.ply") EXPECT_TRUE(m.has_normals());
    if (name == "suzanne.obj") EXPECT_TRUE(m.has_normals());
    ++read;
  }
  EXPECT_GE(read, expected.size());
}

}  // namespace
}  // namespace lodforge
