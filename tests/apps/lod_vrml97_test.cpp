// `lodforge lod` on the VRML97 and X3D classic corpus, judged by the real
// readers as child processes: Castle Model Viewer (view3dscene) loads every
// X3D output without an error, Coin3D reads every VRML97 output with the
// input's level-0 triangle count, and our own reader reads every output.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "apps/castle_viewer.h"
#include "apps/run_command.h"
#include "gltf/gltf_corpus.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "tools/coin_probe_runner.h"
#include "vrml97/vrml97_corpus.h"

namespace lodforge::testing {
namespace {

namespace fs = std::filesystem;

class LodVrml97Corpus : public TempDirTest {};

// What Castle reports of an X3D output of `in` that it does not report of
// `in` itself; for an XML output, nor of its own XML conversion of `in`.
// Where Castle cannot read its own XML conversion of a scene (X3D 4 nodes its
// XML reader does not know, such as Skin), only its exit status is judged.
std::set<std::string> castle_added(const std::string& in, const std::string& out,
                                   const std::set<std::string>& on_input, const fs::path& dir) {
  std::set<std::string> allowed = on_input;
  bool judge_messages = true;
  const std::string own = (fs::path(out).parent_path() / "castle-own.x3d").string();
  if (out.ends_with(".x3d") && castle_to_xml(in, own, dir / "home"))
    for (const auto& e : castle_errors(own, dir / "home")) {
      if (!on_input.count(e)) judge_messages = false;
      allowed.insert(e);
    }
  std::set<std::string> added;
  for (const auto& e : castle_errors(out, dir / "home"))
    if (!allowed.count(e) && (judge_messages || e.starts_with("view3dscene exit status")))
      added.insert(e);
  return added;
}

TEST_F(LodVrml97Corpus, EveryFileGetsLodsThatItsReadersRead) {
  const auto files = vrml97_corpus_files(true);
  ASSERT_GE(files.size(), 50u) << "expected the corpus at " << LODFORGE_SHARED_DATA;
  const bool castle = kOutsideReaders && have_view3dscene();
  std::size_t succeeded = 0, runs = 0, with_lod = 0;
  for (const auto& in : files) {
    const bool wrl = in.ends_with(".wrl");
    // The output goes beside links to the input's neighbours, so that its
    // relative URLs (textures, inlines, EXTERNPROTOs) reach the same files.
    const fs::path beside = dir_ / "beside";
    fs::remove_all(beside);
    fs::create_directories(beside);
    for (const auto& e : fs::directory_iterator(fs::path(in).parent_path()))
      fs::create_symlink(e.path(), beside / e.path().filename());
    std::set<std::string> castle_on_input;
    if (castle) castle_on_input = castle_errors(in, dir_ / "home");
    // `info` reads every file, also those `lod` refuses.
    const CommandResult info = run_lodforge("info --json -q '" + in + "'");
    ASSERT_EQ(info.exit_code, 0) << in << ": " << info.err;
    const auto triangles = nlohmann::json::parse(info.out).at("triangles").get<std::size_t>();
    for (const std::string ext : wrl ? std::vector<std::string>{"wrl", "x3dv", "x3d"}
                                     : std::vector<std::string>{"x3dv", "x3d"}) {
      ++runs;
      const std::string out = (beside / ("lodforge-out." + ext)).string();
      const std::string stats = (dir_ / "stats.json").string();
      fs::remove(out);
      auto r = run_lodforge("lod -q '" + in + "' -o " + out + " --stats " + stats);
      if (r.exit_code != 0) {
        expect_refused(r, in, out);  // an unsupported construct
        continue;
      }
      ++succeeded;
      const auto j = nlohmann::json::parse(read_text(stats));
      std::size_t lods = 0;
      for (const auto& s : j.value("shapes", nlohmann::json::array()))
        lods += s.at("ranges").empty() ? 0 : 1;
      with_lod += lods ? 1 : 0;
      // Our reader reads it back, in the encoding asked for.
      const auto back =
          ext == "x3d" ? vrml97::read_x3d_xml_file(out) : vrml97::read_vrml97_file(out);
      EXPECT_EQ(vrml97::is_x3d_header(back.scene.header), ext != "wrl") << in;
      // Level 0 of what lod wrote draws the triangles info counts in the
      // input (every USE in its place, each LOD at its finest level).
      const CommandResult written = run_lodforge("info --json -q " + out);
      ASSERT_EQ(written.exit_code, 0) << out << ": " << written.err;
      EXPECT_EQ(nlohmann::json::parse(written.out).at("triangles").get<std::size_t>(), triangles)
          << in << " -> " << out;
      // Castle complains of nothing it does not complain of in the input
      // (its own limits: glTF skins, Castle extensions it dropped).
      if (ext != "wrl" && castle) {
        const auto added = castle_added(in, out, castle_on_input, dir_);
        EXPECT_TRUE(added.empty()) << in << " -> " << out << ":\n" << *added.begin();
      }
      if (ext == "wrl" && kOutsideReaders) {
        // Coin reads VRML97 (not X3D): level 0 draws what the input draws.
        const CoinResult before = run_coin_probe(in);
        const CoinResult after = run_coin_probe(out, std::chrono::seconds(120), 0);
        if (!before.accepted()) continue;  // Coin's own limits (PROTOs, extensions)
        EXPECT_TRUE(after.accepted()) << in << ": " << after.why_rejected();
        EXPECT_EQ(after.triangles(), before.triangles()) << in;
      }
    }
  }
  EXPECT_GE(succeeded * 10, runs * 9) << succeeded << " of " << runs << " runs exit 0";
  EXPECT_GE(with_lod * 10, succeeded * 6) << "files given LODs: " << with_lod;
}

// glTF scenes written as VRML97 (`format`) and given LODs as X3D XML (`lod`):
// exit 0, level 0 draws the input's triangles (`info`; Coin for the VRML97
// file), and Castle (and our `render`) draws both without an error
// (textures found, embedded images as data: URIs).
TEST_F(LodVrml97Corpus, GltfScenesAreWrittenAsVrml97AndX3d) {
  const auto files = gltf_corpus_files();
  if (files.empty()) GTEST_SKIP() << "no glTF corpus";
  const bool castle = kOutsideReaders && have_view3dscene();
  for (const auto& in : files) {
    const CommandResult info = run_lodforge("info --json -q '" + in + "'");
    ASSERT_EQ(info.exit_code, 0) << in << ": " << info.err;
    const auto triangles = nlohmann::json::parse(info.out).at("triangles").get<std::size_t>();
    for (const std::string ext : {"wrl", "x3d"}) {
      const std::string out = path("gltf-out." + ext);
      const std::string command = ext == "wrl" ? "format" : "lod";
      const CommandResult r = run_lodforge(command + " -q '" + in + "' -o " + out);
      ASSERT_EQ(r.exit_code, 0) << command << " " << in << ": " << r.err;
      const CommandResult written = run_lodforge("info --json -q " + out);
      ASSERT_EQ(written.exit_code, 0) << out << ": " << written.err;
      EXPECT_EQ(nlohmann::json::parse(written.out).at("triangles").get<std::size_t>(), triangles)
          << in << " -> " << out;
      if (castle)
        for (const auto& e : castle_errors(out, dir_ / "home", ext == "wrl"))
          ADD_FAILURE() << in << " -> " << out << ": " << e;
      // `render` finds every texture, files and data: URIs alike.
      if (ext == "wrl") {
        const CommandResult picture = run_lodforge("render " + out + " -o " + path("p.png"));
        EXPECT_EQ(picture.exit_code, 0) << picture.err;
        EXPECT_EQ(picture.err.find("Texture"), std::string::npos) << in << ": " << picture.err;
      }
      if (ext == "wrl" && kOutsideReaders) {
        const CoinResult coin = run_coin_probe(out, std::chrono::seconds(120), 0);
        EXPECT_TRUE(coin.accepted()) << in << ": " << coin.why_rejected();
        EXPECT_EQ(coin.triangles(), triangles) << in;
      }
    }
  }
}

TEST_F(LodVrml97Corpus, TheX3dOutputDrawsLikeTheInputAtItsViewpoint) {
  if (!have_view3dscene() || std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "view3dscene or xvfb-run missing (scripts/install-deps.sh)";
  const std::string in =
      std::string(LODFORGE_SHARED_DATA) + "/vrml2/castle-engine__demo-models/vrml_2/teapot.wrl";
  const std::string out = (dir_ / "teapot.x3dv").string();
  ASSERT_EQ(run_lodforge("lod -q '" + in + "' -o " + out).exit_code, 0);
  auto shot = [&](const std::string& file, const std::string& png) {
    const std::string cmd = "HOME=" + dir_.string() + " timeout 120 xvfb-run -a view3dscene '" +
                            file + "' --screenshot 0 " + png + " >/dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return read_text(png);
  };
  const std::string a = shot(in, (dir_ / "in.png").string());
  const std::string b = shot(out, (dir_ / "out.png").string());
  ASSERT_GT(a.size(), 1000u);
  // Seen from the file's viewpoint the teapot is near: level 0, pixel for pixel.
  EXPECT_EQ(a, b);
}

// `info` flattens a VRML97 scene as Coin3D does: on every corpus file whose
// shapes Coin reads and draws as indexed face sets (Coin tessellates the
// primitives its own way), the same triangles in all.
TEST_F(LodVrml97Corpus, InfoCountsTheTrianglesCoinDraws) {
  if (!kOutsideReaders) GTEST_SKIP() << "Coin3D is not run under the sanitizers";
  std::size_t compared = 0;
  for (const auto& in : vrml97_corpus_files()) {
    const CommandResult r = run_lodforge("info --json -q '" + in + "'");
    ASSERT_EQ(r.exit_code, 0) << in << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    if (!in.ends_with(".wrl")) continue;  // Coin reads VRML97, not X3D
    const CoinResult coin = run_coin_probe(in);
    if (!coin.accepted()) continue;
    bool faces_only = true;
    for (const auto& [type, n] : coin.shape_triangles)
      faces_only = faces_only && type == "VRMLIndexedFaceSet";
    if (!faces_only) continue;
    EXPECT_EQ(j["triangles"].get<std::size_t>(), coin.triangles()) << in;
    ++compared;
  }
  EXPECT_GE(compared, 15u);
}

// render, simplify and compare take a VRML97 / X3D scene as one surface: the
// LOD output's level 0 is the input, its level 1 within the error written for
// it, and the picture draws the triangles info counts.
TEST_F(LodVrml97Corpus, RenderSimplifyAndCompareReadTheScene) {
  const std::string in =
      std::string(LODFORGE_SHARED_DATA) + "/vrml2/castle-engine__demo-models/vrml_2/teapot.wrl";
  const std::string out = (dir_ / "teapot.x3dv").string();
  const std::string stats = (dir_ / "stats.json").string();
  ASSERT_EQ(run_lodforge("lod -q '" + in + "' -o " + out + " --stats " + stats).exit_code, 0);
  const auto st = nlohmann::json::parse(read_text(stats));
  const auto info = nlohmann::json::parse(run_lodforge("info --json '" + in + "'").out);
  const std::size_t triangles = info["triangles"].get<std::size_t>();
  EXPECT_EQ(triangles, st["shapes"][0]["levels"][0]["triangles"].get<std::size_t>());

  const CommandResult same = run_lodforge("compare --json -q '" + in + "' " + out);
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_EQ(nlohmann::json::parse(same.out)["hausdorff"], 0.0);
  const CommandResult level1 = run_lodforge("compare --json -q '" + in + "' " + out + " --level 1");
  ASSERT_EQ(level1.exit_code, 0) << level1.err;
  const double h = nlohmann::json::parse(level1.out)["hausdorff"].get<double>();
  EXPECT_GT(h, 0);
  // (The error is the shape's own units; the teapot is scaled by its Transform.)
  EXPECT_LE(h, st["shapes"][0]["levels"][1]["error"].get<double>() *
                   st["shapes"][0]["scale"].get<double>() * (1 + 1e-5));

  const CommandResult pic = run_lodforge("render '" + in + "' -o " + (dir_ / "t.png").string());
  ASSERT_EQ(pic.exit_code, 0) << pic.err;
  EXPECT_NE(pic.err.find(std::to_string(triangles) + " triangles"), std::string::npos) << pic.err;
  EXPECT_GT(fs::file_size(dir_ / "t.png"), 2000u);
  // The output's levels side by side, and as a browser switches them.
  const CommandResult sheet =
      run_lodforge("render " + out + " -o " + (dir_ / "levels.png").string() + " --levels");
  ASSERT_EQ(sheet.exit_code, 0) << sheet.err;
  EXPECT_NE(sheet.err.find(std::to_string(st["shapes"][0]["ranges"].size() + 1) + " levels"),
            std::string::npos)
      << sheet.err;
  const CommandResult far =
      run_lodforge("render " + out + " -o " + (dir_ / "far.png").string() + " --distances 5,200");
  ASSERT_EQ(far.exit_code, 0) << far.err;
  EXPECT_NE(far.err.find("2 distances"), std::string::npos) << far.err;

  const CommandResult half =
      run_lodforge("simplify '" + in + "' -o " + (dir_ / "half.ply").string() + " --ratio 0.5 -q");
  ASSERT_EQ(half.exit_code, 0) << half.err;
  const auto small =
      nlohmann::json::parse(run_lodforge("info --json " + (dir_ / "half.ply").string()).out);
  EXPECT_NEAR(small["triangles"].get<double>(), triangles / 2.0, triangles * 0.02);
}

// An X3D scene written as VRML97: the header, no PROFILE (named in a
// warning), triangle sets as IndexedFaceSets; Coin3D reads it and draws what
// the input draws.
TEST_F(LodVrml97Corpus, X3dWrittenAsVrml97IsReadByCoin) {
  const std::string in =
      std::string(LODFORGE_SHARED_DATA) + "/x3d/castle-engine__demo-models/x3d/reuse_coords.x3dv";
  const std::string out = (dir_ / "out.wrl").string();
  const CommandResult r = run_lodforge("lod '" + in + "' -o " + out + " --format vrml97");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("left out: PROFILE (1)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("IndexedFaceSets: IndexedTriangleSet"), std::string::npos) << r.err;
  const auto back = vrml97::read_vrml97_file(out);
  EXPECT_EQ(back.scene.header, "#VRML V2.0 utf8");
  EXPECT_FALSE(vrml97::is_x3d_header(back.scene.header));
  const auto info = nlohmann::json::parse(run_lodforge("info --json -q '" + in + "'").out);
  if (!kOutsideReaders) return;
  const CoinResult coin = run_coin_probe(out, std::chrono::seconds(120), 0);
  ASSERT_TRUE(coin.accepted()) << coin.why_rejected();
  EXPECT_EQ(coin.triangles(), info["triangles"].get<std::size_t>());
}

TEST_F(LodVrml97Corpus, BadInputExitsOneWithTheLineAndNoOutput) {
  const std::string in = (dir_ / "bad.wrl").string();
  {
    std::ofstream f(in);
    f << "#VRML V2.0 utf8\nTransform { translation 1 2 }\n";
  }
  const std::string out = (dir_ / "out.wrl").string();
  auto r = run_lodforge("lod '" + in + "' -o " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.wrl:2:29: expected a number for SFVec3f field 'translation'"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
  // The one-surface commands give the reader's message too.
  for (const std::string cmd : {"info '" + in + "'", "render '" + in + "' -o " + out + ".png",
                                "simplify '" + in + "' -o " + out + ".ply --ratio 0.5",
                                "compare '" + in + "' '" + in + "'"}) {
    const CommandResult c = run_lodforge(cmd);
    EXPECT_EQ(c.exit_code, 1) << cmd;
    EXPECT_NE(c.err.find("bad.wrl:2:29: expected a number"), std::string::npos) << cmd << c.err;
  }
  EXPECT_FALSE(fs::exists(out + ".png"));
  EXPECT_FALSE(fs::exists(out + ".ply"));
}

// Options only the VRML 1.0 / Inventor pipeline uses are named when given
// for a VRML97 or glTF scene (they were ignored silently); manual mode and
// --extract apply to VRML97.
TEST_F(LodVrml97Corpus, OptionsThatDoNotApplyAreNamed) {
  const std::string in = (dir_ / "grid.wrl").string();
  {
    std::ofstream f(in);
    f << "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [";
    for (int y = 0; y <= 20; ++y)
      for (int x = 0; x <= 20; ++x) f << x << " " << y << " " << (x * y % 7) * 0.1 << ", ";
    f << "] } coordIndex [";
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x)
        f << y * 21 + x << " " << y * 21 + x + 1 << " " << y * 21 + x + 22 << " " << y * 21 + x + 21
          << " -1 ";
    f << "] } }\n";
  }
  const std::string out = (dir_ / "out.wrl").string();
  auto r = run_lodforge("lod '" + in + "' -o " + out + " --join --export reducer");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --join, --export are not used for a VRML97 / X3D scene"),
            std::string::npos)
      << r.err;
  r = run_lodforge("lod '" + in + "' -o " + out + " --quality polygon=3 --ranges polygon=7");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  std::ifstream written(out);
  const std::string text{std::istreambuf_iterator<char>(written), {}};
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(range \[\s*7,)"))) << text.substr(0, 400);
  const std::string glb = (dir_ / "out.glb").string();
  r = run_lodforge("lod '" + in + "' -o " + out + ".glb --format glb");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_lodforge("lod '" + out + ".glb' -o " + glb + " --ranges 1,2 --no-lines");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --no-lines is not used for a glTF scene"), std::string::npos)
      << r.err;
}

// The encoding is told by the content where it tells: an X3D XML document
// named .wrl, classic X3D named .x3d, and a bad XML file's line and column.
TEST_F(LodVrml97Corpus, TheContentTellsTheEncoding) {
  const std::string shape =
      "Shape { geometry IndexedFaceSet { coordIndex [0 1 2 -1] coord Coordinate { point [0 0 0, "
      "1 0 0, 0 1 0] } } }";
  std::ofstream(dir_ / "classic.x3d") << "#X3D V3.2 utf8\n" << shape << "\n";
  std::ofstream(dir_ / "xml.wrl")
      << "\xEF\xBB\xBF<?xml version='1.0'?>\n<X3D version='3.2'><Scene><Shape><IndexedFaceSet "
         "coordIndex='0 1 2 -1'><Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet></Shape>"
         "</Scene></X3D>\n";
  for (const char* name : {"classic.x3d", "xml.wrl"}) {
    const CommandResult info = run_lodforge("info --json -q " + (dir_ / name).string());
    ASSERT_EQ(info.exit_code, 0) << name << ": " << info.err;
    EXPECT_EQ(nlohmann::json::parse(info.out)["triangles"], 1) << name;
  }
  std::ofstream(dir_ / "broken.x3d") << "<X3D><Scene>\n  <Group></Scene></X3D>\n";
  const CommandResult bad =
      run_lodforge("lod " + (dir_ / "broken.x3d").string() + " -o " + (dir_ / "o.x3d").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("broken.x3d:2:"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "o.x3d"));
}

}  // namespace
}  // namespace lodforge::testing
