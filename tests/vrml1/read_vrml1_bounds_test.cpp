// The reader's bounds on work a file can ask for: expanded instances and
// triangles (DEF/USE doubling, inlines), nesting across inlines, the number
// of inlined files, and inlines that are not regular files.
#include <sys/stat.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/temp_dir.h"
#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::vrml1 {
namespace {

using ::testing::HasSubstr;

// A scene that doubles its instances at each of `levels` levels below a Cube.
std::string doubling_scene(int levels) {
  std::string s = "#VRML V1.0 ascii\nSeparator {\n DEF L0 Cube {}\n";
  for (int i = 1; i <= levels; ++i)
    s += " DEF L" + std::to_string(i) + " Separator { USE L" + std::to_string(i - 1) + " USE L" +
         std::to_string(i - 1) + " }\n";
  return s + "}\n";
}

std::string error_of(const std::string& text, const ReadOptions& options) {
  try {
    read_vrml1(text, options);
  } catch (const DataError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadVrml1Bounds, DoublingSharingWithinTheLimitIsRead) {
  // Level i expands to 2^(i+1) - 1 instances; the root holds L0..L10: 4084.
  auto r = read_vrml1(doubling_scene(10), {.source_name = "t.wrl"});
  EXPECT_EQ(r.scene.roots.size(), 1u);
  EXPECT_EQ(error_of(doubling_scene(10), {.source_name = "t.wrl", .max_instances = 4084}),
            "no error");
  EXPECT_THAT(error_of(doubling_scene(10), {.source_name = "t.wrl", .max_instances = 4083}),
              HasSubstr("t.wrl:2:1: the scene expands to more than 4083 node instances"));
}

TEST(ReadVrml1Bounds, InstancesPastTheLimitAreRefusedAtTheNode) {
  // Level 10 (line 13) alone expands to 2047.
  EXPECT_THAT(error_of(doubling_scene(10), {.source_name = "t.wrl", .max_instances = 2046}),
              HasSubstr("t.wrl:13:10: the scene expands to more than 2046 node instances"));
}

TEST(ReadVrml1Bounds, FortyDoublingsAreRefusedQuickly) {
  // The triangles (12 per cube) pass their limit first, at level 20 (line 23).
  EXPECT_THAT(error_of(doubling_scene(40), {.source_name = "t.wrl"}),
              HasSubstr("t.wrl:23:10: the scene's shapes, expanded, draw more than 10000000 "));
  EXPECT_THAT(error_of(doubling_scene(40), {.source_name = "t.wrl", .max_triangles = 0}),
              HasSubstr("t.wrl:26:10: the scene expands to more than 10000000 node instances"));
}

TEST(ReadVrml1Bounds, TrianglesPastTheLimitAreRefused) {
  // 2047 cubes of 12 triangles in all; level 10 alone draws 12288.
  EXPECT_EQ(error_of(doubling_scene(10), {.source_name = "t.wrl", .max_triangles = 24564}),
            "no error");
  EXPECT_THAT(error_of(doubling_scene(10), {.source_name = "t.wrl", .max_triangles = 12287}),
              HasSubstr("t.wrl:13:10: the scene's shapes, expanded, draw more than 12287"));
  const std::string faces =
      "#VRML V1.0 ascii\nSeparator { Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n"
      "IndexedFaceSet { coordIndex [0, 1, 2, 3, -1, 0, 1, 2, -1] } }\n";
  EXPECT_EQ(error_of(faces, {.source_name = "t.wrl", .max_triangles = 3}), "no error");
  EXPECT_THAT(error_of(faces, {.source_name = "t.wrl", .max_triangles = 2}),
              HasSubstr("t.wrl:3:1: the scene's shapes, expanded, draw more than 2 triangles"));
}

TEST(ReadVrml1Bounds, ZeroMeansNoLimit) {
  EXPECT_EQ(error_of(doubling_scene(30),
                     {.source_name = "t.wrl", .max_instances = 0, .max_triangles = 0}),
            "no error");
}

class ReadVrml1Inlines : public testing::TempDirTest {
 protected:
  std::string error_of_file(const std::string& path, ReadOptions options = {}) {
    options.read_inlines = true;
    try {
      read_vrml1_file(path, options);
    } catch (const DataError& e) {
      return e.what();
    }
    return "no error";
  }
};

TEST_F(ReadVrml1Inlines, NestingCountsAcrossInlines) {
  // A chain of 40 files, each inlining the next: 80 levels deep in all.
  for (int i = 0; i < 40; ++i)
    write("c" + std::to_string(i) + ".wrl",
          "#VRML V1.0 ascii\nSeparator { " +
              (i + 1 < 40 ? "WWWInline { name \"c" + std::to_string(i + 1) + ".wrl\" }"
                          : std::string("Cube {}")) +
              " }\n");
  EXPECT_EQ(error_of_file(path("c0.wrl")), "no error");
  EXPECT_THAT(error_of_file(path("c0.wrl"), {.max_depth = 50}),
              HasSubstr("c25.wrl:2:1: nodes nested deeper than 50 levels"));
}

TEST_F(ReadVrml1Inlines, InlinedFilesAreCounted) {
  // Each file inlines the next twice: 2^20 inlines for 20 files.
  for (int i = 0; i < 20; ++i) {
    const std::string next = "WWWInline { name \"d" + std::to_string(i + 1) + ".wrl\" }";
    write("d" + std::to_string(i) + ".wrl",
          "#VRML V1.0 ascii\nSeparator { " + (i + 1 < 20 ? next + " " + next : "Cube {}") + " }\n");
  }
  EXPECT_THAT(error_of_file(path("d0.wrl"), {.max_inline_files = 100}),
              HasSubstr("d18.wrl:2: WWWInline 'd19.wrl' goes past the limit of 100 inlined "
                        "files; refused"));
}

TEST_F(ReadVrml1Inlines, AFifoIsRefused) {
  ASSERT_EQ(mkfifo(path("pipe.wrl").c_str(), 0600), 0);
  const std::string scene =
      write("s.wrl", "#VRML V1.0 ascii\nSeparator {\nWWWInline { name \"pipe.wrl\" } }\n");
  EXPECT_EQ(error_of_file(scene),
            scene + ":3: WWWInline 'pipe.wrl' is not a regular file; refused");
}

TEST_F(ReadVrml1Inlines, ASymbolicLinkLoopIsRefusedWithTheInlinesLine) {
  std::filesystem::create_symlink("b.wrl", dir_ / "a.wrl");
  std::filesystem::create_symlink("a.wrl", dir_ / "b.wrl");
  const std::string scene =
      write("s.wrl", "#VRML V1.0 ascii\nSeparator { WWWInline { name \"a.wrl\" } }\n");
  EXPECT_THAT(error_of_file(scene),
              HasSubstr(scene + ":2: WWWInline 'a.wrl' cannot be resolved: "));
}

}  // namespace
}  // namespace lodforge::vrml1
