// `lodforge lod` as a user runs it: one scene or several, statistics,
// messages, bad input (exit 1, no output file), bad usage (exit 2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/run_command.h"
#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::read_text;
using testing::run_lodforge;

class LodCli : public testing::TempDirTest {};

const std::string kPrimitives = std::string(LODFORGE_EXAMPLES) + "/primitives.wrl";

TEST_F(LodCli, OneSceneWithStatistics) {
  auto r = run_lodforge("lod " + kPrimitives + " -o " + path("out.wrl") + " --stats " +
                        path("stats.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("triangles drawn"));
  auto out = vrml1::read_vrml1_file(path("out.wrl"));
  EXPECT_THAT(read_text(path("out.wrl")), HasSubstr("LOD {"));
  auto j = nlohmann::json::parse(read_text(path("stats.json")));
  ASSERT_TRUE(j.contains("shapes"));
  for (const auto& s : j["shapes"]) {
    EXPECT_TRUE(s.contains("levels"));
    EXPECT_TRUE(s.contains("ranges"));
  }
  // Fewer triangles the farther away, ending at none.
  const auto& table = j["triangles_by_distance"];
  ASSERT_GE(table.size(), 2u);
  for (std::size_t i = 1; i < table.size(); ++i)
    EXPECT_LE(table[i]["triangles"].get<long>(), table[i - 1]["triangles"].get<long>());
  EXPECT_EQ(table.back()["triangles"].get<long>(), 0);
}

TEST_F(LodCli, GzOutputsAreGzip) {
  // The folder t/ does not exist yet: lod creates it.
  const std::string out = path("t/out.wrl.gz");
  const std::string stats = path("t/stats.json.gz");
  auto r = run_lodforge("lod " + std::string(LODFORGE_EXAMPLES) + "/scene.wrl -o " + out +
                        " --stats " + stats + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& p : {out, stats}) {
    const std::string bytes = read_text(p);
    ASSERT_GE(bytes.size(), 2u) << p;
    EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f) << p;
    EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b) << p;
  }
  // gzip itself reads them: VRML and JSON.
  ASSERT_EQ(std::system(("gzip -dc " + out + " > " + path("out.wrl")).c_str()), 0);
  EXPECT_TRUE(read_text(path("out.wrl")).starts_with("#VRML V1.0 ascii"));
  EXPECT_THAT(read_text(path("out.wrl")), HasSubstr("LOD {"));
  ASSERT_EQ(std::system(("gzip -dc " + stats + " > " + path("stats.json")).c_str()), 0);
  EXPECT_TRUE(nlohmann::json::parse(read_text(path("stats.json"))).contains("shapes"));
  // And the product reads the compressed scene back as the same scene.
  auto gz = vrml1::read_vrml1_file(out);
  auto plain = vrml1::read_vrml1_file(path("out.wrl"));
  EXPECT_TRUE(scene::equal(gz.scene, plain.scene));
  // --out-dir keeps a compressed input's name, so its output is compressed too.
  auto d = run_lodforge("lod " + out + " --out-dir " + path("d") + " -q");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const std::string again = read_text(path("d/out.wrl.gz"));
  ASSERT_GE(again.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(again[0]), 0x1f);
  EXPECT_FALSE(std::filesystem::exists(path("d/out.wrl")));
}

TEST_F(LodCli, SeveralScenesOneBrokenGoOnAndExitOne) {
  std::string good = write("good.wrl", "#VRML V1.0 ascii\nSeparator { Sphere {} }\n");
  std::string bad = write("bad.wrl",
                          "#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [0 0 0, 1 0 0] }\n"
                          "IndexedFaceSet { coordIndex [0, 1, 5, -1] }\n}\n");
  auto r = run_lodforge("lod " + bad + " " + good + " --out-dir " + path("out"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err,
              HasSubstr("bad.wrl: line 4: IndexedFaceSet coordIndex[2] = 5 is out of range"));
  EXPECT_TRUE(fs::exists(path("out/good.wrl")));
  EXPECT_FALSE(fs::exists(path("out/bad.wrl")));
}

TEST_F(LodCli, BrokenInputsAreErrorsWithoutOutput) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"#VRML V1.0 ascii\nSeparator { Cube { width } }\n",
       "case0.wrl:2:26: expected a number for SFFloat field 'width', got '}'"},
      {"#VRML V1.0 ascii\nSeparator { Coordinate3 { point [0 0 0, 1 0 nan, 0 1 0] }\n"
       "IndexedFaceSet { coordIndex [0, 1, 2] } }\n",
       "line 2: Coordinate3 point 1 used by the IndexedFaceSet at line 3 is not finite"},
      {"#VRML V1.0 ascii\nDEF A Separator { USE A }\n", "USE of undefined node name 'A'"},
  };
  int n = 0;
  for (const auto& [text, message] : cases) {
    std::string in = write("case" + std::to_string(n) + ".wrl", text);
    std::string out = path("case" + std::to_string(n++) + ".out.wrl");
    std::string stats = path("case" + std::to_string(n) + ".json");
    auto r = run_lodforge("lod " + in + " -o " + out + " --stats " + stats);
    EXPECT_EQ(r.exit_code, 1) << text;
    EXPECT_THAT(r.err, HasSubstr(message));
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(stats)) << "statistics of a scene that failed";
  }
}

// NaN passes every comparison, so range checks alone let it through into the
// written ranges; every numeric option refuses numbers that are not finite.
TEST_F(LodCli, NumbersThatAreNotFiniteAreRefused) {
  for (const std::string option :
       {"--error-range nan", "--camera-angle inf", "--level-spacing NaN", "--min-diff -inf"}) {
    const std::string out = path("nan.wrl");
    auto r = run_lodforge("lod " + kPrimitives + " -o " + out + " " + option);
    EXPECT_NE(r.exit_code, 0) << option;
    EXPECT_THAT(r.err, HasSubstr("is not a finite number")) << option;
    EXPECT_FALSE(fs::exists(out)) << option;
  }
}

TEST_F(LodCli, EmptyFaceSetIsAWarningNamingItsLine) {
  std::string in = write("empty.wrl",
                         "#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [0 0 0] }\n"
                         "IndexedFaceSet { coordIndex [] }\n}\n");
  auto r = run_lodforge("lod " + in + " -o " + path("empty.out.wrl"));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("warning: line 4: IndexedFaceSet has no faces; kept as it is"));
}

TEST_F(LodCli, TexturesAreFoundFromAnotherOutputFolder) {
  fs::create_directories(path("in/tex"));
  write("in/tex/wood.png", "not read by lod");
  std::string in = write("in/scene.wrl",
                         "#VRML V1.0 ascii\nSeparator {\nTexture2 { filename \"tex/wood.png\" }\n"
                         "Cube {}\n}\n");
  auto r = run_lodforge("lod " + in + " -o " + path("other/dir/out.wrl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 file reference made relative to"));
  auto out = vrml1::read_vrml1_file(path("other/dir/out.wrl"));
  EXPECT_THAT(read_text(path("other/dir/out.wrl")), HasSubstr("\"../../in/tex/wood.png\""));
  EXPECT_TRUE(fs::exists(path("other/dir/../../in/tex/wood.png")));
  // format moves them too.
  r = run_lodforge("format " + in + " -o " + path("formatted/out.wrl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(read_text(path("formatted/out.wrl")), HasSubstr("\"../in/tex/wood.png\""));
}

// The same for VRML97 and X3D: every value of a url field (ImageTexture,
// Inline, Background's ...Url), the part after '#' kept, URLs and program
// code left alone; in both encodings of X3D, from lod and from format.
TEST_F(LodCli, Vrml97UrlsAreFoundFromAnotherOutputFolder) {
  fs::create_directories(path("in97/tex"));
  const std::string in = write("in97/scene.x3dv", R"(#X3D V3.0 utf8
PROFILE Immersive
Background { backUrl [ "sky/back.png" ] }
Shape { appearance Appearance { texture ImageTexture { url [ "tex/wood.png" "http://x.org/w.png" ] } }
        geometry Box { } }
Inline { url "parts/wheel.x3dv#Top" }
Script { url "ecmascript:
function initialize() {}" }
)");
  for (const std::string out : {"other/dir/out.x3dv", "other/dir/out.x3d"}) {
    auto r = run_lodforge("lod " + in + " -o " + path(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("3 file references made relative to")) << out;
    const std::string text = read_text(path(out));
    for (const char* moved :
         {"../../in97/tex/wood.png", "../../in97/sky/back.png", "../../in97/parts/wheel.x3dv#Top",
          "http://x.org/w.png", "function initialize"})
      EXPECT_THAT(text, HasSubstr(moved)) << out;
  }
  auto r = run_lodforge("format " + in + " -o " + path("in97/same.x3dv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, Not(HasSubstr("made relative")));
  EXPECT_THAT(read_text(path("in97/same.x3dv")), HasSubstr("\"tex/wood.png\""));
  r = run_lodforge("format " + in + " -o " + path("f/out.x3dv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(read_text(path("f/out.x3dv")), HasSubstr("\"../in97/tex/wood.png\""));
}

TEST_F(LodCli, BadUsageIsExitTwo) {
  EXPECT_EQ(run_lodforge("lod " + kPrimitives).exit_code, 2);  // no -o
  EXPECT_EQ(run_lodforge("lod " + kPrimitives + " " + kPrimitives + " -o x.wrl").exit_code, 2);
  EXPECT_EQ(
      run_lodforge("lod " + kPrimitives + " -o " + path("x.wrl") + " --quality teapot=3").exit_code,
      2);
  EXPECT_EQ(
      run_lodforge("lod " + kPrimitives + " -o " + path("x.wrl") + " --method magic").exit_code, 2);
  EXPECT_EQ(run_lodforge("lod " + kPrimitives + " -o " + path("x.wrl") + " --ranges 5,2").exit_code,
            2);
  EXPECT_FALSE(fs::exists(path("x.wrl")));
}

TEST_F(LodCli, OptionsOfTheOriginalAreAccepted) {
  for (const std::string opts :
       {"--method cluster --min-diff 50", "--method decimate --levels 3",
        "--export reducer --no-quads", "--export performer --no-lines --quad-split-angle 0.3",
        "--extract 1", "--extract -1",
        "--quality sphere=0 --quality cone=1 --quality cylinder=3 --ranges cube=5", "--join",
        "--error-range 0.1 --camera-angle 0.5 --minimize"}) {
    auto r = run_lodforge("lod " + kPrimitives + " -o " + path("o.wrl") + " " + opts);
    EXPECT_EQ(r.exit_code, 0) << opts << ": " << r.err;
    EXPECT_NO_THROW(vrml1::read_vrml1_file(path("o.wrl"))) << opts;
  }
}

// The same warning at many places is printed once, with its count and first
// place; -q keeps the one-line summary, --quiet=all prints nothing.
TEST_F(LodCli, RepeatedWarningsAreGroupedAndQuietKeepsTheSummary) {
  std::string scene = "#VRML V1.0 ascii\nSeparator {\n";
  for (int i = 0; i < 5; ++i) scene += "Material { shininess 0.5 reflSpecular 0.1 }\nCube {}\n";
  scene += "}\n";
  const std::string in = path("warn.wrl");
  std::ofstream(in) << scene;
  auto r = run_lodforge("lod " + in + " -o " + path("out.wrl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("reflSpecular"));
  EXPECT_THAT(r.err, HasSubstr("(5 times, first at " + in + ":3:"));
  std::size_t mentions = 0;
  for (std::size_t at = r.err.find("reflSpecular"); at != std::string::npos;
       at = r.err.find("reflSpecular", at + 1))
    ++mentions;
  EXPECT_EQ(mentions, 1u) << r.err;

  auto quiet = run_lodforge("lod " + in + " -o " + path("out.wrl") + " -q");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_THAT(quiet.err, ::testing::Not(HasSubstr("warning")));
  EXPECT_THAT(quiet.err, HasSubstr("5 shapes"));
  EXPECT_THAT(quiet.err, ::testing::Not(HasSubstr("triangles drawn")));

  auto silent = run_lodforge("lod " + in + " -o " + path("out.wrl") + " --quiet=all");
  ASSERT_EQ(silent.exit_code, 0) << silent.err;
  EXPECT_EQ(silent.err, "");
  EXPECT_EQ(run_lodforge("lod " + in + " -o " + path("out.wrl") + " --quiet=loud").exit_code, 2);
}

}  // namespace
}  // namespace lodforge
