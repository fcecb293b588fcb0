// The VRML 1.0 writer: layout options, sharing, names, atomic files.
#include "lodforge/io/vrml1/write_vrml1.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge::vrml1 {
namespace {

using scene::Node;
using scene::NodePtr;
using ::testing::HasSubstr;
using ::testing::Not;

NodePtr make(std::string type) {
  auto n = std::make_shared<Node>();
  n->type = std::move(type);
  return n;
}

TEST(WriteVrml1, SharedNodeWithoutNameGetsDefAndUse) {
  scene::Scene s;
  auto root = make("Separator");
  auto cube = make("Cube");
  root->children = {cube, make("Translation"), cube};
  s.roots = {root};
  std::string text = write_vrml1(s);
  EXPECT_THAT(text, HasSubstr("DEF lf_1 Cube {"));
  EXPECT_THAT(text, HasSubstr("USE lf_1"));
  auto back = read_vrml1(text);
  const auto& kids = back.scene.roots[0]->children;
  EXPECT_EQ(kids[0].get(), kids[2].get());
}

TEST(WriteVrml1, NameReboundBeforeALaterUseIsMadeUnique) {
  // A is shared and named X; B (also X, also shared) is written between A's
  // DEF and A's USE. Without renaming, "USE X" would mean B.
  scene::Scene s;
  auto root = make("Separator");
  auto a = make("Cube");
  a->name = "X";
  auto b = make("Sphere");
  b->name = "X";
  root->children = {a, b, b, a};
  s.roots = {root};
  auto back = read_vrml1(write_vrml1(s));
  const auto& kids = back.scene.roots[0]->children;
  ASSERT_EQ(kids.size(), 4u);
  EXPECT_EQ(kids[3]->type, "Cube");
  EXPECT_EQ(kids[3].get(), kids[0].get());
  EXPECT_EQ(kids[2].get(), kids[1].get());
}

TEST(WriteVrml1, FloatsAndIntsPerLine) {
  auto r = read_vrml1(
      "#VRML V1.0 ascii\nSeparator { Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n"
      "IndexedFaceSet { coordIndex [0, 1, 2, 3, -1, 0, 2, 1, -1] } }");
  std::string text = write_vrml1(r.scene, {.floats_per_line = 6, .ints_per_line = 5});
  EXPECT_THAT(text, HasSubstr("\t\t\t0 0 0, 1 0 0,\n\t\t\t1 1 0, 0 1 0\n"));
  EXPECT_THAT(text, HasSubstr("\t\t\t0, 1, 2, 3, -1,\n\t\t\t0, 2, 1, -1\n"));
  std::string flat = write_vrml1(r.scene, {.no_tabs = true});
  EXPECT_THAT(flat, Not(HasSubstr("\t")));
}

TEST(WriteVrml1, MinimizeWritesOneLineAfterTheHeader) {
  auto r = read_vrml1(
      "#VRML V1.0 ascii\nSeparator {\n  Material { diffuseColor [1 0 0, 0 1 0] }\n"
      "  Info { string \"two\nlines\" }\n  Cube {}\n}\n");
  std::string text = write_vrml1(r.scene, {.minimize = true});
  EXPECT_EQ(text,
            "#VRML V1.0 ascii\n\nSeparator { Material { diffuseColor [1 0 0, 0 1 0] } Info { "
            "string \"two\nlines\" } Cube { } }\n");
  EXPECT_LT(text.size(), write_vrml1(r.scene).size());
}

TEST(WriteVrml1, StringsAreEscapedAndNumbersExact) {
  scene::Scene s;
  auto info = make("Info");
  info->set("string", scene::make_string("say \"hi\" \\o/"));
  auto cube = make("Cube");
  cube->set("width", scene::make_float(0.1f));
  cube->set("depth", scene::make_float(1e-30f));
  s.roots = {info, cube};
  std::string text = write_vrml1(s);
  EXPECT_THAT(text, HasSubstr("string \"say \\\"hi\\\" \\\\o/\""));
  auto back = read_vrml1(text);
  EXPECT_EQ(back.scene.roots[0]->value("string")->strings[0], "say \"hi\" \\o/");
  EXPECT_EQ(back.scene.roots[1]->value("width")->floats[0], 0.1f);
  EXPECT_EQ(back.scene.roots[1]->value("depth")->floats[0], 1e-30f);
}

TEST(WriteVrml1, FileIsReplacedAtomicallyAndNeverHalfWritten) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "lodforge_write_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  scene::Scene s;
  s.roots = {make("Cube")};
  std::string path = (dir / "out.wrl").string();
  {
    std::ofstream old(path);
    old << "old content";
  }
  write_vrml1_file(s, path);
  auto back = read_vrml1_file(path);
  EXPECT_EQ(back.scene.roots[0]->type, "Cube");
  // Nothing but the output is left in the folder (no temporary file).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  // A folder that does not exist: an error, and no file.
  std::string bad = (dir / "missing" / "out.wrl").string();
  EXPECT_THROW(write_vrml1_file(s, bad), DataError);
  EXPECT_FALSE(fs::exists(bad));
  fs::remove_all(dir);
}

TEST(WriteVrml1, GzNameIsWrittenCompressed) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("lodforge_write_gz_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  scene::Scene s;
  s.roots = {make("Separator")};
  s.roots[0]->children = {make("Cube")};
  std::string path = (dir / "out.wrl.gz").string();
  write_vrml1_file(s, path);
  std::ifstream f(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
  ASSERT_TRUE(is_gzip(bytes));
  EXPECT_EQ(gunzip(bytes, path), write_vrml1(s));
  auto back = read_vrml1_file(path);
  ASSERT_EQ(back.scene.roots.size(), 1u);
  EXPECT_EQ(back.scene.roots[0]->children.at(0)->type, "Cube");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lodforge::vrml1
