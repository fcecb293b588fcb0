// VRML 1.0 / Inventor scenes written as VRML97 and X3D classic by `lod` and
// `format`, judged by their readers as child processes: Castle Model Viewer
// (view3dscene, drawing under xvfb) adds no complaint to what it says of the
// input, and Coin3D draws at level 0 of the VRML97 output the triangles
// `lodforge info` counts in the input.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "apps/castle_viewer.h"
#include "apps/run_command.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "lodforge/io/vrml97/write_x3d_xml.h"
#include "tools/coin_probe_runner.h"

namespace lodforge::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kRepository = fs::path(LODFORGE_EXAMPLES).parent_path();

std::vector<std::string> vrml1_corpus() {
  std::vector<std::string> out;
  const fs::path root = fs::path(LODFORGE_SHARED_DATA) / "vrml1";
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return out;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && (name.ends_with(".wrl") || name.ends_with(".iv") ||
                                name.ends_with(".wrl.gz") || name.ends_with(".iv.gz")))
      out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t info_triangles(const std::string& file) {
  const CommandResult r = run_lodforge("info --json '" + file + "'");
  if (r.exit_code != 0) return SIZE_MAX;
  return nlohmann::json::parse(r.out)["triangles"].get<std::size_t>();
}

using WriteSceneVrml97 = TempDirTest;

TEST_F(WriteSceneVrml97, FormatAndNameChooseTheEncoding) {
  const std::string in = (kRepository / "examples/scene.wrl").string();
  ASSERT_EQ(run_lodforge("lod -q " + in + " --format vrml97 -o " + path("a.wrl")).exit_code, 0);
  EXPECT_TRUE(read_text(path("a.wrl")).starts_with("#VRML V2.0 utf8"));
  ASSERT_EQ(run_lodforge("lod -q " + in + " -o " + path("b.x3dv")).exit_code, 0);
  EXPECT_TRUE(read_text(path("b.x3dv")).starts_with("#X3D V3.0 utf8"));
  ASSERT_EQ(run_lodforge("format -q " + in + " --format x3dv -o " + path("c.out")).exit_code, 0);
  const scene::Scene c = vrml97::read_vrml97_file(path("c.out")).scene;
  EXPECT_TRUE(vrml97::is_x3d_header(c.header));
  // A plain VRML 1.0 output stays VRML 1.0.
  ASSERT_EQ(run_lodforge("lod -q " + in + " -o " + path("d.wrl")).exit_code, 0);
  EXPECT_TRUE(read_text(path("d.wrl")).starts_with("#VRML V1.0 ascii"));
  // X3D's XML encoding, by name or by --format: the scene the X3D classic
  // output holds, and Castle loads it with no complaint it has not of that one.
  ASSERT_EQ(run_lodforge("lod -q " + in + " -o " + path("e.x3d")).exit_code, 0);
  ASSERT_EQ(run_lodforge("lod -q " + in + " --format x3d -o " + path("f.out")).exit_code, 0);
  EXPECT_TRUE(read_text(path("e.x3d")).starts_with("<?xml"));
  EXPECT_EQ(read_text(path("e.x3d")), read_text(path("f.out")));
  const scene::Scene e = vrml97::read_x3d_xml_file(path("e.x3d")).scene;
  const scene::Scene b = vrml97::read_vrml97_file(path("b.x3dv")).scene;
  // (Field order aside: the XML lists a node's fields before its nodes.)
  EXPECT_TRUE(vrml97::write_x3d_xml(e) == vrml97::write_x3d_xml(b));
  EXPECT_EQ(info_triangles(path("e.x3d")), info_triangles(path("b.x3dv")));
  if (kOutsideReaders && have_view3dscene())
    EXPECT_EQ(castle_errors(path("e.x3d"), path("home")),
              castle_errors(path("b.x3dv"), path("home")));
}

TEST_F(WriteSceneVrml97, EveryVrml1CorpusFileIsReadByCastleAndCoin) {
  const auto files = vrml1_corpus();
  if (files.empty()) GTEST_SKIP() << "no corpus at " << LODFORGE_SHARED_DATA << "/vrml1";
  const bool castle = kOutsideReaders && have_view3dscene() &&
                      std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
  std::size_t written = 0;
  for (const std::string& in : files) {
    const std::string x3dv = path("out/o.x3dv"), wrl = path("out/o.wrl");
    fs::remove_all(path("out"));
    const CommandResult r = run_lodforge("lod -q '" + in + "' -o " + x3dv);
    if (r.exit_code != 0) {
      expect_refused(r, in, x3dv);  // an unsupported construct
      continue;
    }
    ++written;
    EXPECT_TRUE(vrml97::is_x3d_header(vrml97::read_vrml97_file(x3dv).scene.header)) << in;
    if (castle) {
      // A texture URL that does not resolve from the input's own folder
      // either (Castle does not always say so of a VRML 1.0 input) is the
      // input's problem; nothing else may be reported.
      for (const std::string& e : castle_errors(x3dv, dir_ / "home", true)) {
        const auto url = e.find("texture from URL \"");
        bool absent = false;
        if (url != std::string::npos) {
          const std::string name = e.substr(url + 18, e.find('"', url + 18) - url - 18);
          std::error_code ec;
          absent = !fs::exists(fs::path(in).parent_path() / name, ec);
        }
        EXPECT_TRUE(absent) << in << " -> .x3dv: " << e;
      }
    }
    ASSERT_EQ(run_lodforge("lod -q '" + in + "' --format vrml97 -o " + wrl).exit_code, 0) << in;
    if (!kOutsideReaders) continue;
    const CoinResult out = run_coin_probe(wrl, std::chrono::seconds(300), 0);
    if (!run_coin_probe(in).accepted() && !out.accepted()) continue;  // Coin's own limits
#ifdef LODFORGE_COIN_PROBE
    ASSERT_TRUE(out.accepted()) << in << ": " << out.why_rejected();
    // Level 0 draws the input's triangles; Coin's VRML97 IndexedFaceSet
    // leaves out zero-area triangles (two corners at one index), as Coin
    // counts them in the input.
    const std::size_t expected = info_triangles(in);
    if (out.triangles() != expected) {
      const CoinResult coin_in = run_coin_probe(in);
      EXPECT_EQ(coin_in.triangles(), expected) << in;
      std::size_t distinct = 0;
      for (const auto& [type, n] : coin_in.distinct_triangles) distinct += n;
      EXPECT_EQ(out.triangles(), distinct) << in;
    }
#endif
  }
  EXPECT_GE(written * 10, files.size() * 9) << written << " of " << files.size();
}

}  // namespace
}  // namespace lodforge::testing
