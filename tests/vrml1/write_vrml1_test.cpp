// The VRML 1.0 writer: layout options, sharing, names, atomic files.
#include "lodforge/io/vrml1/write_vrml1.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

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

// Lists long enough to be formatted in pieces on several threads: the same
// layout as a short one (two points per line, commas between values, none
// after the last) and the same values, in order.
TEST(WriteVrml1, LongListsKeepTheirLayoutAndOrder) {
  constexpr int kPoints = 50001, kFaces = 40001;
  std::vector<float> points;
  for (int i = 0; i < 3 * kPoints; ++i) points.push_back(float(i) * 0.001f + 0.5f);
  std::vector<std::int32_t> index;
  for (int f = 0; f < kFaces; ++f) index.insert(index.end(), {f, f + 1, f + 2, -1});
  scene::Scene s;
  auto root = make("Separator");
  auto coords = make("Coordinate3");
  coords->set("point", scene::make_floats(scene::FieldKind::kVec3f, true, points));
  auto faces = make("IndexedFaceSet");
  faces->set("coordIndex", scene::make_longs(index));
  root->children = {coords, faces};
  s.roots = {root};
  for (bool minimize : {false, true}) {
    const std::string text =
        write_vrml1(s, {.floats_per_line = 6, .ints_per_line = 8, .minimize = minimize});
    auto back = read_vrml1(text);
    const auto& kids = back.scene.roots.at(0)->children;
    ASSERT_EQ(kids.size(), 2u);
    EXPECT_EQ(kids[0]->value("point")->floats, points);
    EXPECT_EQ(kids[1]->value("coordIndex")->ints, index);
    if (minimize) {
      EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);  // the header's and the last
      continue;
    }
    // Each list line holds two points (a point has a '.') or eight indices,
    // each value followed by a comma but the list's last.
    std::istringstream lines(text);
    std::vector<std::string> point_lines, index_lines;
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("\t\t\t", 0) == 0 && line.size() > 3 && line[3] != '\t')
        (line.find('.') != std::string::npos ? point_lines : index_lines).push_back(line);
    ASSERT_EQ(point_lines.size(), std::size_t(kPoints + 1) / 2);
    ASSERT_EQ(index_lines.size(), std::size_t(4 * kFaces + 7) / 8);
    auto count = [](const std::string& l, char c) { return std::count(l.begin(), l.end(), c); };
    for (std::size_t i = 0; i + 1 < point_lines.size(); ++i) {
      EXPECT_EQ(count(point_lines[i], ','), 2) << point_lines[i];
      EXPECT_EQ(count(point_lines[i], ' '), 5) << point_lines[i];
    }
    EXPECT_EQ(count(point_lines.back(), ','), 0) << point_lines.back();
    for (std::size_t i = 0; i + 1 < index_lines.size(); ++i) {
      EXPECT_EQ(count(index_lines[i], ','), 8) << index_lines[i];
      EXPECT_EQ(count(index_lines[i], ' '), 7) << index_lines[i];
    }
    EXPECT_EQ(count(index_lines.back(), ','), 3) << index_lines.back();
  }
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
