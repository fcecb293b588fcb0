// The studio's API, served in-process on a free port and called through
// cpp-httplib's client: files, tree, a LOD run on a corpus scene, save, and
// the refusal of paths outside the folders it was given.
#include "lodforge/studio/studio_server.h"

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::studio {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kRocket =
    std::string(LODFORGE_SHARED_DATA) + "/vrml1/castle-engine__malfunction/data/vrmls/rocket.wrl";

// A server on a free port of 127.0.0.1 over the rocket and two scenes of a
// fresh folder (a copy of the example scene and a scene that does not parse).
class StudioServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kRocket)) GTEST_SKIP() << "no shared corpus at " << LODFORGE_SHARED_DATA;
    dir_ = fs::temp_directory_path() /
           ("studio_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::copy_file(std::string(LODFORGE_EXAMPLES) + "/scene.wrl", dir_ / "scene.wrl");
    std::ofstream(dir_ / "broken.wrl") << "#VRML V1.0 ascii\nSeparator {\n  Cube { width }\n}\n";
    StudioOptions options{
        .scenes = {kRocket, (dir_ / "scene.wrl").string(), (dir_ / "broken.wrl").string()},
        .port = 0,
        .web_root = LODFORGE_STUDIO_WEB};
    server_ = std::make_unique<StudioServer>(options);
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->serve(); });
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(120, 0);
  }
  void TearDown() override {
    if (server_) server_->stop();
    if (thread_.joinable()) thread_.join();
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  json get(const std::string& url, int expect = 200) {
    auto res = client_->Get(url.c_str());
    EXPECT_TRUE(res) << url;
    if (!res) return {};
    EXPECT_EQ(res->status, expect) << url << ": " << res->body;
    return json::parse(res->body);
  }
  json post(const std::string& url, const json& body, int expect = 200) {
    auto res = client_->Post(url.c_str(), body.dump(), "application/json");
    EXPECT_TRUE(res) << url;
    if (!res) return {};
    EXPECT_EQ(res->status, expect) << url << ": " << res->body;
    return json::parse(res->body);
  }
  static std::string query(const std::string& path) {
    return httplib::detail::encode_query_param(fs::canonical(path).string());
  }
  // Starts a run and waits for its end.
  json run_lod(const std::string& path, const json& options) {
    json started = post("/api/lod", {{"path", path}, {"options", options}});
    EXPECT_EQ(started["state"], "running");
    for (int i = 0; i < 1200; ++i) {
      json status = get("/api/lod?path=" + query(path));
      if (status["state"] != "running") return status;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ADD_FAILURE() << "the run did not end";
    return {};
  }

  fs::path dir_;
  std::unique_ptr<StudioServer> server_;
  int port_ = 0;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(StudioServerTest, FilesListSizesShapeCountsAndParseErrors) {
  json files = get("/api/files")["files"];
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0]["path"], fs::canonical(kRocket).string());
  EXPECT_EQ(files[0]["size"], fs::file_size(kRocket));
  EXPECT_EQ(files[0]["shapes"]["IndexedFaceSet"], 2);
  EXPECT_GT(files[0]["triangles"].get<int>(), 0);
  EXPECT_FALSE(files[1].contains("error"));
  EXPECT_GT(files[1]["shapes"]["IndexedFaceSet"].get<int>(), 0);
  // The broken scene is listed with the reader's file:line:column.
  ASSERT_TRUE(files[2].contains("error"));
  EXPECT_NE(files[2]["error"].get<std::string>().find("broken.wrl:3:"), std::string::npos)
      << files[2]["error"];
}

TEST_F(StudioServerTest, TreeHasTheExampleDefNamesAndFields) {
  json tree = get("/api/tree?path=" + query((dir_ / "scene.wrl").string()));
  std::vector<std::string> names;
  std::function<void(const json&)> walk = [&](const json& n) {
    if (n.contains("name")) names.push_back(n["name"]);
    for (const auto& c : n.value("children", json::array())) walk(c);
  };
  for (const auto& r : tree) walk(r);
  for (const char* name : {"Terrain", "House", "Tree", "Link"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST_F(StudioServerTest, LodRunEqualsThePipelineAndSaves) {
  json status = run_lod(kRocket, {{"error-range", 10}, {"method", "qem"}});
  ASSERT_EQ(status["state"], "done") << status.dump();
  EXPECT_NE(status["command_line"].get<std::string>().find("--error-range 10 --method qem"),
            std::string::npos)
      << status["command_line"];
  const json& result = status["result"];
  // The same run through the library, as `lodforge lod --error-range 10` does it.
  LodOptions options;
  options.range.error_range = 0.1f;
  const LodResult direct = generate_lod(vrml1::read_vrml1_file(kRocket).scene, options);
  ASSERT_EQ(result["shapes"].size(), direct.shapes.size());
  for (std::size_t i = 0; i < direct.shapes.size(); ++i) {
    ASSERT_EQ(result["shapes"][i]["levels"].size(), direct.shapes[i].levels.size());
    for (std::size_t l = 0; l < direct.shapes[i].levels.size(); ++l)
      EXPECT_EQ(result["shapes"][i]["levels"][l]["triangles"],
                direct.shapes[i].levels[l].triangles);
    EXPECT_EQ(result["shapes"][i]["ranges"].get<std::vector<float>>(), direct.shapes[i].ranges);
  }
  ASSERT_EQ(result["triangles_by_distance"].size(), direct.triangles_by_distance.size());
  std::size_t levels = 0;
  for (const auto& shape : direct.shapes) levels += shape.levels.size();
  ASSERT_GT(levels, direct.shapes.size()) << "the rocket should get simplified levels";
  // The geometry of the result: one LOD instance per LOD node drawn, each
  // level's triangles as the statistics count them.
  auto geo = client_->Get(("/api/geometry?which=output&path=" + query(kRocket)).c_str());
  ASSERT_TRUE(geo);
  ASSERT_EQ(geo->status, 200) << geo->body;
  const json g = json::parse(geo->body);
  ASSERT_EQ(g["lods"].size(), direct.shapes.size());
  std::size_t level0 = 0;
  for (const auto& lod : g["lods"])
    for (const auto& m : lod["levels"][0]) level0 += m["indices"].size() / 3;
  EXPECT_EQ(level0, result["triangles"].get<std::size_t>());

  // Save into the allowed scratch folder; the written file is the LOD scene.
  const fs::path out = dir_ / "rocket_lod.wrl";
  json saved = post("/api/save", {{"path", kRocket}, {"output", out.string()}});
  EXPECT_EQ(saved["written"], out.string());
  ASSERT_TRUE(fs::exists(out));
  std::size_t lods = 0;
  scene::traverse(vrml1::read_vrml1_file(out.string()).scene, [&](const scene::ShapeVisit& v) {
    lods += std::count_if(v.path.begin(), v.path.end(), [](auto* n) { return n->type == "LOD"; });
  });
  EXPECT_EQ(lods, direct.shapes.size());
}

TEST_F(StudioServerTest, WriterOptionsAndFormatTakeEffectOnSave) {
  const auto save = [&](const json& options, const std::string& name) {
    json status = run_lod(kRocket, options);
    EXPECT_EQ(status["state"], "done") << status.dump();
    const fs::path out = dir_ / name;
    json saved = post("/api/save", {{"path", kRocket}, {"output", out.string()}});
    EXPECT_EQ(saved["written"], out.string());
    return std::make_pair(saved, read_file(out.string()));
  };
  const auto [plain_answer, plain] = save(json::object(), "plain.wrl");
  EXPECT_EQ(plain_answer["format"], "vrml1");
  const auto [minimized_answer, minimized] = save({{"minimize", true}}, "minimized.wrl");
  EXPECT_LT(minimized.size(), plain.size() * 9 / 10);
  EXPECT_EQ(std::count(minimized.begin(), minimized.end(), '\n'), 3)
      << "the header, a blank line and the scene on one line";
  const auto [untabbed_answer, untabbed] = save({{"no-tabs", true}}, "untabbed.wrl");
  EXPECT_LT(untabbed.size(), plain.size());
  EXPECT_EQ(untabbed.find("\n "), std::string::npos);
  EXPECT_EQ(untabbed.find("\n\t"), std::string::npos);
  // One float per line: more lines than the default six.
  const auto [narrow_answer, narrow] = save({{"floats-per-line", 1}}, "narrow.wrl");
  EXPECT_GT(std::count(narrow.begin(), narrow.end(), '\n'),
            std::count(plain.begin(), plain.end(), '\n'));
  // The same LOD scene in each (the writer options change only the layout).
  const auto lod_count = [](const std::string& path) {
    std::size_t lods = 0;
    scene::traverse(vrml1::read_vrml1_file(path).scene, [&](const scene::ShapeVisit& v) {
      lods += std::count_if(v.path.begin(), v.path.end(), [](auto* n) { return n->type == "LOD"; });
    });
    return lods;
  };
  EXPECT_EQ(lod_count((dir_ / "minimized.wrl").string()), lod_count((dir_ / "plain.wrl").string()));
  EXPECT_GT(lod_count((dir_ / "plain.wrl").string()), 0u);

  // --format x3dv writes X3D classic whatever the name; an .x3dv name alone
  // does too, and --format vrml97 / glb as the CLI.
  const auto [x3d_answer, x3d] = save({{"format", "x3dv"}}, "rocket_x3d.wrl");
  EXPECT_EQ(x3d_answer["format"], "x3dv");
  EXPECT_TRUE(x3d.starts_with("#X3D V3.0 utf8")) << x3d.substr(0, 40);
  const auto [named_answer, named] = save(json::object(), "rocket.x3dv");
  EXPECT_TRUE(named.starts_with("#X3D V3.0 utf8")) << named.substr(0, 40);
  const auto [vrml97_answer, vrml97] = save({{"format", "vrml97"}}, "rocket97.wrl");
  EXPECT_TRUE(vrml97.starts_with("#VRML V2.0 utf8")) << vrml97.substr(0, 40);
  const auto [glb_answer, glb] = save({{"format", "glb"}}, "rocket.glb");
  EXPECT_EQ(glb_answer["format"], "glb");
  EXPECT_TRUE(glb.starts_with("glTF")) << "binary glTF magic";

  // Byte for byte what `lodforge lod` writes with the same options.
  const auto cli = [&](const std::string& args, const std::string& name) {
    const std::string out = (dir_ / name).string();
    const std::string command =
        fmt::format("{} lod '{}' -o '{}' -q {}", LODFORGE_EXE, kRocket, out, args);
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return read_file(out);
  };
  EXPECT_EQ(minimized, cli("--minimize", "cli_minimized.wrl"));
  EXPECT_EQ(narrow, cli("--floats-per-line 1", "cli_narrow.wrl"));
  EXPECT_EQ(x3d, cli("--format x3dv", "cli_x3d.wrl"));
  // The XML encoding, by name or by --format, as the CLI writes it.
  const auto [xml_answer, xml] = save(json::object(), "rocket.x3d");
  EXPECT_EQ(xml_answer["format"], "x3d");
  EXPECT_TRUE(xml.starts_with("<?xml")) << xml.substr(0, 40);
  EXPECT_EQ(xml, cli("--format x3d", "cli_xml.out"));
}

TEST_F(StudioServerTest, ReadingOptionsRereadTheScene) {
  // A scene whose only shape is in a WWWInline: without --inline the run
  // sees no shape, with it the inlined cube set.
  std::ofstream(dir_ / "part.wrl")
      << "#VRML V1.0 ascii\nSeparator { Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n"
         "IndexedFaceSet { coordIndex [0, 1, 2, 3, -1] } }\n";
  std::ofstream(dir_ / "main.wrl")
      << "#VRML V1.0 ascii\nSeparator { WWWInline { name \"part.wrl\" } }\n";
  const std::string main_scene = (dir_ / "main.wrl").string();
  post("/api/open", {{"path", main_scene}});
  json plain = run_lod(main_scene, json::object());
  ASSERT_EQ(plain["state"], "done") << plain.dump();
  EXPECT_EQ(plain["result"]["shapes"].size(), 0u);
  json inlined = run_lod(main_scene, {{"inline", true}});
  ASSERT_EQ(inlined["state"], "done") << inlined.dump();
  EXPECT_EQ(inlined["result"]["shapes"].size(), 1u);
  EXPECT_NE(inlined["command_line"].get<std::string>().find("--inline"), std::string::npos);
  // --max-triangles below the scene's count refuses it, as the CLI does.
  json limited = run_lod(kRocket, {{"max-triangles", 1}});
  ASSERT_EQ(limited["state"], "failed") << limited.dump();
  EXPECT_NE(limited["error"].get<std::string>().find("triangles"), std::string::npos) << limited;
  json instances = run_lod(kRocket, {{"max-instances", 2}});
  ASSERT_EQ(instances["state"], "failed") << instances.dump();
  EXPECT_NE(instances["error"].get<std::string>().find("instances"), std::string::npos)
      << instances;
}

TEST_F(StudioServerTest, VerboseKeepsOnlyTheMessagesOfItsCategories) {
  json status = run_lod(kRocket, {{"verbose", {"join"}}});
  ASSERT_EQ(status["state"], "done") << status.dump();
  for (const auto& m : status["result"]["messages"])
    if (m["level"] == "message") EXPECT_EQ(m["category"], "join") << m;
  json bad = post("/api/lod", {{"path", kRocket}, {"options", {{"verbose", {"colour"}}}}}, 400);
  EXPECT_NE(bad["error"].get<std::string>().find("unknown category 'colour'"), std::string::npos);
}

TEST_F(StudioServerTest, BadOptionsAreRefusedWithTheOptionNamed) {
  json e = post("/api/lod", {{"path", kRocket}, {"options", {{"error-range", "ten"}}}}, 400);
  EXPECT_NE(e["error"].get<std::string>().find("error-range"), std::string::npos) << e;
  e = post("/api/lod", {{"path", kRocket}, {"options", {{"no-such-option", 1}}}}, 400);
  EXPECT_NE(e["error"].get<std::string>().find("no-such-option"), std::string::npos) << e;
}

TEST_F(StudioServerTest, PathsOutsideTheGivenFoldersAreRefused) {
  json e = post("/api/open", {{"path", "/etc/passwd"}}, 403);
  EXPECT_NE(e["error"].get<std::string>().find("refused"), std::string::npos) << e;
  // Leaving an allowed folder with .. is the same path outside it.
  post("/api/open", {{"path", (dir_ / "../../etc/passwd").string()}}, 403);
  get("/api/tree?path=%2Fetc%2Fpasswd", 403);
  ASSERT_EQ(run_lod((dir_ / "scene.wrl").string(), {{"levels", 3}})["state"], "done");
  const fs::path outside = fs::temp_directory_path() / "studio_test_outside.wrl";
  post("/api/save", {{"path", (dir_ / "scene.wrl").string()}, {"output", outside.string()}}, 403);
  EXPECT_FALSE(fs::exists(outside));
  // The page's files: no request leaves the page's folder.
  for (const char* url : {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
                          "/..%2f..%2f..%2f..%2fetc%2fpasswd", "/three/../../../etc/passwd"}) {
    auto res = client_->Get(url);
    if (!res) continue;  // a refused connection serves nothing either
    EXPECT_NE(res->status, 200) << url;
    EXPECT_EQ(res->body.find("root:"), std::string::npos) << url;
  }
  auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("lodforge studio"), std::string::npos);
}

// The geometry of a LOD result carries each level's per-vertex deviation
// from level 0 and its colours on one scale: level 0 at 0 (blue), a coarser
// level with some vertex off the surface.
TEST_F(StudioServerTest, GeometryCarriesTheDeviationFromLevelZero) {
  const std::string scene = (dir_ / "scene.wrl").string();
  ASSERT_EQ(run_lod(scene, {{"levels", 3}})["state"], "done");
  auto res = client_->Get(("/api/geometry?which=output&path=" + query(scene)).c_str());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json g = json::parse(res->body);
  const float most = g["deviation_max"];
  EXPECT_GT(most, 0);
  float seen = 0;
  for (const auto& lod : g["lods"])
    for (std::size_t l = 0; l < lod["levels"].size(); ++l)
      for (const auto& m : lod["levels"][l]) {
        const auto d = m["deviation"].get<std::vector<float>>();
        ASSERT_EQ(d.size() * 3, m["positions"].size());
        ASSERT_EQ(m["deviation_colors"].size(), m["positions"].size());
        for (float v : d) {
          if (l == 0) EXPECT_EQ(v, 0);
          EXPECT_LE(v, most);
          seen = std::max(seen, v);
        }
      }
  EXPECT_EQ(seen, most);
}

// The editor's text, re-parsed without saving: a syntax error answers its
// line and column and keeps the scene; a good edit changes the tree and the
// counts while the file on disk stays as it was.
TEST_F(StudioServerTest, ReparseReportsLineAndColumnAndWritesNothing) {
  const std::string scene = (dir_ / "scene.wrl").string();
  const json text = get("/api/text?path=" + query(scene));
  const std::string original = text["text"];
  EXPECT_EQ(text["edited"], false);
  EXPECT_EQ(original.rfind("#VRML V1.0 ascii", 0), 0u);
  const std::size_t before = get("/api/files")["files"][1]["triangles"];

  json r = post(
      "/api/parse",
      {{"path", scene}, {"text", "#VRML V1.0 ascii\nSeparator {\n  Cube {\n    width }\n}\n"}});
  EXPECT_EQ(r["parsed"], false);
  EXPECT_EQ(r["line"], 4);
  EXPECT_EQ(r["column"], 11);
  EXPECT_NE(r["error"].get<std::string>().find(":4:11:"), std::string::npos) << r;
  EXPECT_EQ(get("/api/text?path=" + query(scene))["edited"], false);

  r = post("/api/parse", {{"path", scene},
                          {"text", "#VRML V1.0 ascii\nSeparator {\n  DEF Edited Cube { }\n}\n"}});
  ASSERT_EQ(r["parsed"], true) << r;
  EXPECT_EQ(r["triangles"], 12);
  EXPECT_NE(before, 12u);
  EXPECT_NE(get("/api/tree?path=" + query(scene)).dump().find("Edited"), std::string::npos);
  EXPECT_EQ(get("/api/text?path=" + query(scene))["edited"], true);
  std::ifstream in(scene);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), original);
  post("/api/parse", {{"path", "/etc/passwd"}, {"text", "#VRML V1.0 ascii\n"}}, 403);
}

// An upload lands in the server's own temporary folder and loads from there;
// a name that is not a plain file name is refused and nothing is written.
TEST_F(StudioServerTest, UploadStaysInTheServersFolder) {
  json f = post("/api/upload", {{"name", "up.wrl"}, {"text", "#VRML V1.0 ascii\nSphere { }\n"}});
  const fs::path path = f["path"].get<std::string>();
  EXPECT_EQ(path.filename(), "up.wrl");
  EXPECT_NE(path.parent_path(), dir_);
  EXPECT_EQ(f["shapes"]["Sphere"], 1);
  EXPECT_GT(get("/api/tree?path=" + httplib::detail::encode_query_param(path.string())).size(), 0u);
  for (const char* name : {"../up2.wrl", "/tmp/up2.wrl", "..", "", "a/b.wrl"})
    post("/api/upload", {{"name", name}, {"text", "#VRML V1.0 ascii\n"}}, 400);
  EXPECT_FALSE(fs::exists(path.parent_path().parent_path() / "up2.wrl"));
  EXPECT_FALSE(fs::exists("/tmp/up2.wrl"));
  // A path outside the allowed folders stays refused after an upload.
  post("/api/open", {{"path", "/etc/passwd"}}, 403);
  server_->stop();
  if (thread_.joinable()) thread_.join();
  server_.reset();
  EXPECT_FALSE(fs::exists(path.parent_path())) << "the upload folder outlives the server";
}

// Gzip-compressed scenes (.wrl.gz, .wrz, .iv.gz) open as the CLI reads them:
// the same shape and triangle counts as the plain file. An upload named .gz
// is stored gzip-compressed and loads the same way.
TEST_F(StudioServerTest, GzippedScenesOpenAndUploadLikeThePlainFile) {
  const std::string quads = std::string(LODFORGE_SHARED_DATA) +
                            "/inventor/coin3d__coin/models/oiv_compliance/quadmesh.iv";
  ASSERT_TRUE(fs::exists(quads)) << quads;
  fs::copy_file(quads, dir_ / "quadmesh.iv");
  const std::string example = read_file((dir_ / "scene.wrl").string());
  const auto gzip = [&](const std::string& text, const std::string& name) {
    write_file_atomic((dir_ / (name + ".gz")).string(), text);  // a .gz name writes gzip
    fs::rename(dir_ / (name + ".gz"), dir_ / name);
  };
  gzip(example, "packed.wrl.gz");
  gzip(example, "packed.wrz");
  gzip(read_file(quads), "quadmesh.iv.gz");
  const auto counts = [](const json& f) {
    EXPECT_FALSE(f.contains("error")) << f;
    return json{f["shapes"], f["triangles"]};
  };
  const json plain = counts(post("/api/open", {{"path", (dir_ / "scene.wrl").string()}}));
  ASSERT_GT(plain[1].get<int>(), 0);
  for (const char* name : {"packed.wrl.gz", "packed.wrz"})
    EXPECT_EQ(counts(post("/api/open", {{"path", (dir_ / name).string()}})), plain) << name;
  const json iv = counts(post("/api/open", {{"path", (dir_ / "quadmesh.iv").string()}}));
  ASSERT_GT(iv[1].get<int>(), 0);
  EXPECT_EQ(counts(post("/api/open", {{"path", (dir_ / "quadmesh.iv.gz").string()}})), iv);

  // Make LOD on the compressed scene names a compressed output beside it.
  const json run = run_lod((dir_ / "packed.wrl.gz").string(), json::object());
  EXPECT_EQ(run["state"], "done") << run;
  EXPECT_NE(run["command_line"].get<std::string>().find((dir_ / "packed_lod.wrl.gz").string()),
            std::string::npos)
      << run["command_line"];

  const json up = post("/api/upload", {{"name", "up.wrl.gz"}, {"text", example}});
  EXPECT_EQ(counts(up), plain);
  std::ifstream stored(up["path"].get<std::string>(), std::ios::binary);
  std::string magic(2, '\0');
  stored.read(magic.data(), 2);
  EXPECT_EQ(magic, "\x1f\x8b") << "the .gz upload is not stored gzip-compressed";
}

// A scene's texture file is served from its folder with its image type;
// one outside the allowed folders, or not an image, is not.
TEST_F(StudioServerTest, TexturesAreServedFromTheAllowedFoldersOnly) {
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + "rest of the file";
  std::ofstream(dir_ / "wood.png", std::ios::binary) << png;
  std::ofstream(dir_ / "textured.wrl")
      << "#VRML V1.0 ascii\nSeparator { Texture2 { filename \"wood.png\" } Cube { } }\n";
  post("/api/open", {{"path", (dir_ / "textured.wrl").string()}});
  const std::string scene = query((dir_ / "textured.wrl").string());
  auto geo = client_->Get(("/api/geometry?path=" + scene).c_str());
  ASSERT_TRUE(geo);
  ASSERT_EQ(geo->status, 200) << geo->body;
  const json mesh = json::parse(geo->body)["shapes"][0];
  EXPECT_EQ(mesh["texture"]["file"], "wood.png");
  EXPECT_EQ(mesh["texcoords"].size() * 3, mesh["positions"].size() * 2);
  auto res = client_->Get(("/api/texture?path=" + scene + "&file=wood.png").c_str());
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->body, png);
  EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
  res = client_->Get(("/api/texture?path=" + scene + "&file=..%2F..%2F..%2Fetc%2Fpasswd").c_str());
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 403);
  EXPECT_EQ(res->body.find("root:"), std::string::npos);
  res = client_->Get(("/api/texture?path=" + scene + "&file=textured.wrl").c_str());
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
}

TEST(StudioServer, ListensOnLoopbackByDefault) {
  EXPECT_EQ(StudioOptions{}.host, "127.0.0.1");
  EXPECT_THROW(StudioServer(StudioOptions{.scenes = {"/nonexistent/x.wrl"}}), DataError);
}

}  // namespace
}  // namespace lodforge::studio
