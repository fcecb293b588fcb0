// `lodforge lod` with the X3D XML encoding (.x3d) in and out, judged by Castle
// Model Viewer (view3dscene) as a child process: every .x3d of the corpus to
// .x3d and .x3dv, VRML97 and X3D classic scenes to .x3d; the .x3d output holds
// the scene the .x3dv output holds (so its level 0 is the input's shapes).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/castle_viewer.h"
#include "apps/run_command.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/x3dxml/read_x3d_xml.h"

namespace lodforge::testing {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> corpus(const std::vector<std::string>& extensions) {
  std::vector<std::string> out;
  for (const char* dir : {"/vrml2", "/x3d"}) {
    const std::string root = std::string(LODFORGE_SHARED_DATA) + dir;
    std::error_code ec;
    if (!fs::is_directory(root, ec)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.is_regular_file() &&
          std::count(extensions.begin(), extensions.end(), e.path().extension().string()))
        out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

class LodX3dXml : public TempDirTest {
 protected:
  // The output goes beside links to the input's neighbours, so that its
  // relative URLs (textures, inlines) reach the same files.
  fs::path beside(const std::string& in) {
    const fs::path dir = dir_ / "beside";
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(fs::path(in).parent_path()))
      fs::create_symlink(e.path(), dir / e.path().filename());
    return dir;
  }

  // Runs lod; on exit 1 checks the message and that nothing was written.
  bool lod(const std::string& in, const std::string& out) {
    fs::remove(out);
    const auto r = run_lodforge("lod -q '" + in + "' -o '" + out + "'");
    if (r.exit_code == 0) return true;
    EXPECT_EQ(r.exit_code, 1) << in << "\n" << r.err;
    EXPECT_NE(r.err.find("error:"), std::string::npos) << in;
    EXPECT_FALSE(fs::exists(out)) << in;
    return false;
  }

  // Castle complains of nothing in `out` it does not complain of in `in`.
  void castle_adds_nothing(const std::set<std::string>& on_input, const std::string& in,
                           const std::string& out) {
    std::set<std::string> added;
    for (const auto& e : castle_errors(out, dir_ / "home"))
      if (!on_input.count(e)) added.insert(e);
    EXPECT_TRUE(added.empty()) << in << " -> " << out << ":\n" << *added.begin();
  }
};

TEST_F(LodX3dXml, EveryX3dFileToX3dAndX3dvLoadsInCastle) {
  const auto files = corpus({".x3d"});
  ASSERT_GE(files.size(), 15u) << "expected the corpus at " << LODFORGE_SHARED_DATA;
  const bool castle = have_view3dscene();
  std::size_t runs = 0, succeeded = 0;
  for (const auto& in : files) {
    const fs::path dir = beside(in);
    const std::set<std::string> on_input =
        castle ? castle_errors(in, dir_ / "home") : std::set<std::string>{};
    const std::string xml = (dir / "lodforge-out.x3d").string();
    const std::string classic = (dir / "lodforge-out.x3dv").string();
    runs += 2;
    const bool xml_ok = lod(in, xml);
    const bool classic_ok = lod(in, classic);
    succeeded += xml_ok + classic_ok;
    EXPECT_TRUE(classic_ok) << in;
    if (xml_ok && classic_ok) {
      // One scene in either encoding: the .x3d output's LOD levels are the
      // .x3dv output's, whose level 0 draws the input's shapes.
      const auto a = x3dxml::read_x3d_xml_file(xml);
      const auto b = vrml97::read_vrml97_file(classic);
      EXPECT_TRUE(scene::equal(a.scene, b.scene)) << in;
    }
    if (!castle) continue;
    if (xml_ok) castle_adds_nothing(on_input, in, xml);
    if (classic_ok) castle_adds_nothing(on_input, in, classic);
  }
  EXPECT_GE(succeeded * 10, runs * 9) << succeeded << " of " << runs << " runs exit 0";
}

TEST_F(LodX3dXml, Vrml97AndX3dClassicScenesToX3dLoadInCastle) {
  const auto files = corpus({".wrl", ".x3dv"});
  ASSERT_GE(files.size(), 40u) << "expected the corpus at " << LODFORGE_SHARED_DATA;
  const bool castle = have_view3dscene();
  std::size_t succeeded = 0;
  for (const auto& in : files) {
    const fs::path dir = beside(in);
    const std::string out = (dir / "lodforge-out.x3d").string();
    if (!lod(in, out)) continue;
    ++succeeded;
    EXPECT_NO_THROW(x3dxml::read_x3d_xml_file(out)) << in;
    if (castle) castle_adds_nothing(castle_errors(in, dir_ / "home"), in, out);
  }
  // The refusals are scenes with a PROTO or EXTERNPROTO.
  EXPECT_GE(succeeded * 10, files.size() * 7) << succeeded << " of " << files.size();
}

TEST_F(LodX3dXml, BadXmlExitsOneWithLineAndColumnAndNoOutput) {
  const std::string out = (dir_ / "out.x3d").string();
  auto check = [&](const std::string& text, const std::string& message) {
    const std::string in = (dir_ / "bad.x3d").string();
    std::ofstream(in) << text;
    const auto r = run_lodforge("lod '" + in + "' -o " + out);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("bad.x3d:" + message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  };
  check("<X3D><Scene>\n<Transform>\n  <Shape><Box/></Shape>\n</Scene></X3D>\n",
        "4:1: malformed XML: Start-end tags mismatch");
  check(
      "<X3D><Scene>\n<Transform>\n  <Shape><Box size='1 2'/></Shape>\n</Transform></Scene></X3D>\n",
      "3:10: expected a number for SFVec3f field 'size'");
  check("<X3D><Scene>\n<Transform translation='1 2 3\n</Scene></X3D>\n", "");
}

}  // namespace
}  // namespace lodforge::testing
