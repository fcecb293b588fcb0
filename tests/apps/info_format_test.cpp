// `lodforge info` and `lodforge format` as a user runs them: exit codes,
// messages, JSON, standard input/output, gzip, inlines, no partial output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/run_command.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/scene/relocate_references.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::read_text;
using testing::run_lodforge;

class Cli : public testing::TempDirTest {};

const std::string kExample = std::string(LODFORGE_EXAMPLES) + "/scene.wrl";

TEST_F(Cli, InfoJsonOnTheExample) {
  auto r = run_lodforge("info --json " + kExample);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["shapes"]["IndexedFaceSet"].get<int>(), 1);
  EXPECT_GE(j["ifs_triangles"].get<int>(), 39200);
  EXPECT_GT(j["triangles"].get<int>(), j["ifs_triangles"].get<int>());  // + primitives
  EXPECT_GT(j["bounds"]["diagonal"].get<double>(), 100);
  EXPECT_EQ(j["node_counts"]["WWWAnchor"].get<int>(), 1);
}

TEST_F(Cli, InfoTextNamesTheOriginalCounts) {
  auto r = run_lodforge("info " + kExample);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("IndexedFaceSets "));
  EXPECT_THAT(r.out, HasSubstr("Cylinders "));
  EXPECT_THAT(r.out, HasSubstr("bounds ["));
}

// A mesh file: its counts, bounds and topology (two tetrahedra: two
// components, closed, four faces each).
TEST_F(Cli, InfoDescribesAMeshFile) {
  const std::string mesh = path("two.off");
  std::ofstream(mesh) << "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                         "5 0 0\n6 0 0\n5 1 0\n5 0 1\n"
                         "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
                         "3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n";
  auto r = run_lodforge("info --json " + mesh);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["triangles"].get<int>(), 8);
  EXPECT_EQ(j["vertices"].get<int>(), 8);
  EXPECT_EQ(j["components"].get<int>(), 2);
  EXPECT_EQ(j["boundary_edges"].get<int>(), 0);
  EXPECT_DOUBLE_EQ(j["bounds"]["max"][0].get<double>(), 6.0);
  auto text = run_lodforge("info " + mesh);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("triangles 8, vertices 8"));
  EXPECT_THAT(text.out, HasSubstr("components 2, boundary edges 0"));
  // A mesh file that is not one: the reader's message, exit 1.
  const std::string bad = path("bad.off");
  std::ofstream(bad) << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  auto b = run_lodforge("info " + bad);
  EXPECT_EQ(b.exit_code, 1);
  EXPECT_THAT(b.err, HasSubstr("bad.off"));
}

TEST_F(Cli, FormatRoundTripsThroughStdinAndStdout) {
  auto r = run_lodforge("format - -o - --minimize", kExample);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto a = vrml1::read_vrml1_file(kExample);
  auto b = vrml1::read_vrml1(r.out);
  EXPECT_TRUE(scene::equal(a.scene, b.scene));
  EXPECT_LT(r.out.size(), read_text(kExample).size());
}

TEST_F(Cli, GzipInputIsReadTransparently) {
  std::string plain = write("a.wrl", "#VRML V1.0 ascii\nSeparator { Cube {} }\n");
  ASSERT_EQ(std::system(("gzip -k -f " + plain).c_str()), 0);
  auto r = run_lodforge("info --json " + plain + ".gz");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["shapes"]["Cube"].get<int>(), 1);
}

TEST_F(Cli, BadInputIsExitCodeOneWithPositionAndNoOutputFile) {
  std::string bad = write("bad.wrl", "#VRML V1.0 ascii\nSeparator {\n  Cube { width x }\n}\n");
  std::string out = path("out.wrl");
  auto r = run_lodforge("format " + bad + " -o " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "error: " + bad + ":3:16: expected a number for SFFloat field 'width', got 'x'\n");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(Cli, MissingFileAndBadUsage) {
  auto missing = run_lodforge("info " + path("nope.wrl"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.err, HasSubstr("nope.wrl: cannot open: No such file or directory"));
  EXPECT_EQ(run_lodforge("format").exit_code, 2);
  EXPECT_EQ(run_lodforge("frobnicate x").exit_code, 2);
  EXPECT_EQ(run_lodforge("format a.wrl -o b.wrl --floats-per-line 0").exit_code, 2);
}

TEST_F(Cli, UnknownNodesWarnAndSurviveFormatting) {
  std::string in = write("ext.wrl",
                         "#VRML V1.0 ascii\nSeparator {\n  Fog { color 1 0 0 visibilityRange 50 }\n"
                         "  Material { diffuseColor 1 0 0 mirror 0.3 }\n}\n");
  std::string out = path("ext.out.wrl");
  auto r = run_lodforge("format " + in + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("3-3: unknown node type >Fog< kept as it is"));
  EXPECT_THAT(r.err, HasSubstr("unknown field >mirror< of Material kept as it is"));
  std::string text = read_text(out);
  EXPECT_THAT(text, HasSubstr("Fog { color 1 0 0 visibilityRange 50 }"));
  EXPECT_THAT(text, HasSubstr("mirror 0.3"));
}

TEST_F(Cli, InlinesAreReadOnlyWhenAskedAndNeverOutsideTheFolder) {
  write("scene/part.wrl", "#VRML V1.0 ascii\nSeparator { Cube {} Sphere {} }\n");
  std::string main =
      write("scene/main.wrl", "#VRML V1.0 ascii\nSeparator { WWWInline { name \"part.wrl\" } }\n");
  auto without = nlohmann::json::parse(run_lodforge("info --json " + main).out);
  EXPECT_EQ(without["shapes"]["Cube"].get<int>(), 0);
  auto r = run_lodforge("info --json --inline " + main);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["shapes"]["Cube"].get<int>(), 1);

  write("secret.wrl", "#VRML V1.0 ascii\nCube {}\n");
  std::string escape = write(
      "scene/escape.wrl", "#VRML V1.0 ascii\nSeparator { WWWInline { name \"../secret.wrl\" } }\n");
  auto refused = run_lodforge("info --inline " + escape);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, HasSubstr("WWWInline '../secret.wrl' leaves the scene's folder"));

  std::string net =
      write("scene/net.wrl", "#VRML V1.0 ascii\nWWWInline { name \"http://example.com/x.wrl\" }\n");
  auto remote = run_lodforge("info --inline " + net);
  EXPECT_EQ(remote.exit_code, 0);
  EXPECT_THAT(remote.err, HasSubstr("lodforge never reads over a network"));
}

// `format` on VRML97 and X3D classic scenes: written back in their own
// encoding, the same scene read again; VRML97 to X3D classic by the output
// name; an X3D scene as VRML97 on request.
// The writer options lay out VRML97 as they do VRML 1.0 (its writer is the
// same); for an X3D XML or glTF output they are named in a warning.
TEST_F(Cli, WriterOptionsLayOutVrml97AndAreNamedWhereUnused) {
  const std::string& in = kExample;
  ASSERT_EQ(run_lodforge("format -q " + in + " --format vrml97 -o " + path("a.wrl")).exit_code, 0);
  auto r = run_lodforge("format " + in + " --format vrml97 --minimize -o " + path("b.wrl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("--minimize"), std::string::npos) << r.err;
  EXPECT_LT(read_text(path("b.wrl")).size(), read_text(path("a.wrl")).size());
  // The same scene (SFImage values are kept as read, so compared by what
  // they draw).
  auto info = [&](const std::string& f) {
    auto j = nlohmann::json::parse(run_lodforge("info --json " + f).out);
    return std::make_pair(j["shapes"], j["triangles"]);
  };
  EXPECT_EQ(info(path("a.wrl")), info(path("b.wrl")));
  EXPECT_GT(info(path("b.wrl")).second.get<std::size_t>(), 0u);
  r = run_lodforge("format " + in + " --minimize -o " + path("c.x3d"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --minimize is not used for an X3D XML output"), std::string::npos)
      << r.err;
  r = run_lodforge("format " + path("a.wrl") + " --floats-per-line 2 --no-tabs -o " +
                   path("d.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --floats-per-line, --no-tabs are not used for a glTF output"),
            std::string::npos)
      << r.err;
}

TEST_F(Cli, FormatWritesVrml97AndX3dClassicScenesBackAsTheSameScene) {
  std::vector<std::string> files;
  for (const char* dir : {"/vrml2", "/x3d"}) {
    const fs::path root = fs::path(LODFORGE_SHARED_DATA + std::string(dir));
    std::error_code ec;
    if (!fs::is_directory(root, ec)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".wrl" || ext == ".x3dv")) files.push_back(e.path());
    }
  }
  if (files.empty()) GTEST_SKIP() << "no VRML97 / X3D corpus at " << LODFORGE_SHARED_DATA;
  std::sort(files.begin(), files.end());
  std::size_t vrml97_files = 0;
  for (const std::string& in : files) {
    vrml97::ReadResult original = vrml97::read_vrml97_file(in);
    const bool x3d = vrml97::is_x3d_header(original.scene.header);
    const std::string same = path(x3d ? "same.x3dv" : "same.wrl");
    auto r = run_lodforge("format -q '" + in + "' -o " + same);
    ASSERT_EQ(r.exit_code, 0) << in << "\n" << r.err;
    // The same scene, its relative file references seen from the output's folder.
    scene::relocate_references(original.scene, fs::path(in).parent_path(),
                               fs::path(same).parent_path());
    EXPECT_TRUE(scene::equal(original.scene, vrml97::read_vrml97_file(same).scene)) << in;
    if (x3d) {
      // As VRML97: a VRML97 file our reader reads back.
      r = run_lodforge("format -q '" + in + "' --format vrml97 -o " + path("as.wrl"));
      ASSERT_EQ(r.exit_code, 0) << in << "\n" << r.err;
      EXPECT_EQ(vrml97::read_vrml97_file(path("as.wrl")).scene.header, "#VRML V2.0 utf8") << in;
      continue;
    }
    ++vrml97_files;
    r = run_lodforge("format -q '" + in + "' -o " + path("as.x3dv"));
    ASSERT_EQ(r.exit_code, 0) << in << "\n" << r.err;
    EXPECT_TRUE(vrml97::is_x3d_header(vrml97::read_vrml97_file(path("as.x3dv")).scene.header))
        << in;
  }
  EXPECT_GT(vrml97_files, 0u);
  // A gzipped VRML97 file (.wrl.gz) is one too, for format and lod.
  const auto plain = std::find_if(files.begin(), files.end(), [](const std::string& f) {
    return !vrml97::is_x3d_header(vrml97::read_vrml97_file(f).scene.header);
  });
  ASSERT_NE(plain, files.end());
  std::ofstream(path("in.wrl.gz"), std::ios::binary) << gzip(read_text(*plain));
  auto gz = run_lodforge("format -q " + path("in.wrl.gz") + " -o " + path("gz.wrl"));
  ASSERT_EQ(gz.exit_code, 0) << gz.err;
  EXPECT_TRUE(scene::equal(vrml97::read_vrml97_file(*plain).scene,
                           vrml97::read_vrml97_file(path("gz.wrl")).scene));
  gz = run_lodforge("lod -q " + path("in.wrl.gz") + " -o " + path("gz_lod.wrl"));
  EXPECT_EQ(gz.exit_code, 0) << gz.err;
  EXPECT_FALSE(vrml97::is_x3d_header(vrml97::read_vrml97_file(path("gz_lod.wrl")).scene.header));
  // As glTF: the shapes it draws, in world space (LodVrml97ToGltf judges the files).
  const auto glb = run_lodforge("format -q '" + files.front() + "' -o " + path("out.glb"));
  EXPECT_EQ(glb.exit_code, 0) << glb.err;
  EXPECT_TRUE(read_text(path("out.glb")).starts_with("glTF"));
  const auto triangles = [&](const std::string& f) {
    return nlohmann::json::parse(run_lodforge("info --json -q '" + f + "'").out)["triangles"];
  };
  EXPECT_EQ(triangles(path("out.glb")), triangles(files.front()));
}

}  // namespace
}  // namespace lodforge
