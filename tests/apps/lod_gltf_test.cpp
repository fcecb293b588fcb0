// `lodforge lod` on glTF scenes, judged by the Khronos glTF-Validator (npm
// gltf-validator, run with node): every corpus scene gives a file with no
// validator error, MSFT_lod on the simplified nodes (with a screen coverage
// per level), and the input's materials, textures and images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>

#include "apps/run_command.h"
#include "core/temp_dir.h"
#include "gltf/gltf_corpus.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/scene_mesh.h"
#include "lodforge/render/texture_image.h"
#include "lodforge/render/write_png.h"
#include "vrml97/vrml97_corpus.h"

namespace lodforge::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kRepository = fs::path(LODFORGE_EXAMPLES).parent_path();

// Runs shell text, returning its exit code and standard output.
std::pair<int, std::string> shell(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, ""};
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// The validator's summary of `file` ({"errors", "warnings", "messages"}), or
// a skip when node is missing.
class LodGltf : public TempDirTest, public ::testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    if (shell("command -v node >/dev/null 2>&1").first != 0)
      GTEST_SKIP() << "node is not installed (scripts/install-deps.sh installs it): the glTF "
                      "validator cannot run";
    const auto [code, out] =
        shell((kRepository / "scripts/install-gltf-validator.sh").string() + " 2>&1");
    ASSERT_EQ(code, 0) << "scripts/install-gltf-validator.sh failed: " << out;
  }
  nlohmann::json validate(const std::string& file) {
    const auto [code, out] =
        shell("node " + (kRepository / "tests/tools/validate_gltf.js").string() + " " +
              (kRepository / ".tools/gltf-validator").string() + " '" + file + "'");
    EXPECT_EQ(code, 0) << out;
    return nlohmann::json::parse(out);
  }
};

TEST_P(LodGltf, OutputIsValidWithMsftLodAndTheInputsMaterials) {
  const std::string input = GetParam();
  const std::string output = path("out.glb"), stats = path("stats.json");
  const CommandResult r =
      run_lodforge("lod '" + input + "' -o " + output + " --stats " + stats + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = validate(output);
  EXPECT_EQ(report["errors"], 0) << input << ": " << report.dump(1);

  const auto in = gltf::read_gltf_file(input).scene.model;
  const auto out = gltf::read_gltf_file(output).scene.model;
  // Materials, textures and images of the input, in the same places.
  ASSERT_EQ(in.materials.size(), out.materials.size());
  for (std::size_t i = 0; i < in.materials.size(); ++i)
    EXPECT_EQ(in.materials[i].name, out.materials[i].name);
  EXPECT_EQ(in.textures, out.textures);
  ASSERT_EQ(in.images.size(), out.images.size());
  for (std::size_t i = 0; i < in.images.size(); ++i)
    EXPECT_EQ(in.images[i].image, out.images[i].image);

  // Every shape the statistics give levels has its nodes carry MSFT_lod.
  const auto j = nlohmann::json::parse(read_text(stats));
  std::size_t expected = 0;
  for (const auto& s : j["shapes"])
    if (!s["ranges"].empty()) expected += s["occurrences"].get<std::size_t>();
  std::size_t with_lod = 0;
  for (const auto& node : out.nodes) {
    const auto lod = node.extensions.find("MSFT_lod");
    if (lod == node.extensions.end()) continue;
    ++with_lod;
    const auto& ids = lod->second.Get("ids");
    ASSERT_TRUE(ids.IsArray());
    for (std::size_t k = 0; k < ids.ArrayLen(); ++k) {
      const int id = ids.Get(int(k)).GetNumberAsInt();
      ASSERT_TRUE(id >= 0 && std::size_t(id) < out.nodes.size());
      EXPECT_GE(out.nodes[std::size_t(id)].mesh, 0);
    }
    // One coverage per level and one where the mesh vanishes, decreasing.
    const auto& coverage = node.extras.Get("MSFT_screencoverage");
    ASSERT_EQ(coverage.ArrayLen(), ids.ArrayLen() + 1);
    for (std::size_t k = 1; k < coverage.ArrayLen(); ++k)
      EXPECT_LT(coverage.Get(int(k)).GetNumberAsDouble(),
                coverage.Get(int(k - 1)).GetNumberAsDouble());
  }
  EXPECT_EQ(with_lod, expected) << input;
  if (expected > 0)
    EXPECT_NE(std::find(out.extensionsUsed.begin(), out.extensionsUsed.end(), "MSFT_lod"),
              out.extensionsUsed.end());
  EXPECT_EQ(std::find(out.extensionsRequired.begin(), out.extensionsRequired.end(), "MSFT_lod"),
            out.extensionsRequired.end());
}

INSTANTIATE_TEST_SUITE_P(Corpus, LodGltf, ::testing::ValuesIn(gltf_corpus_files()),
                         [](const auto& info) { return gltf_test_name(info.param); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(LodGltf);

// The torus (one mesh, no skin): levels exist, and a JSON .gltf is written
// for a .gltf name or --format gltf.
// VRML 1.0 scenes written as glTF: valid for the validator, each LOD node an
// MSFT_lod node with its screen coverages, level 0 drawing what the input
// draws. The example, and corpus scenes with textures, inline images and
// primitives.
using LodVrml1ToGltf = LodGltf;
TEST_F(LodVrml1ToGltf, ScenesBecomeValidGltfWithMsftLod) {
  const fs::path data = fs::path(LODFORGE_SHARED_DATA) / "vrml1";
  std::vector<std::string> inputs = {(kRepository / "examples/scene.wrl").string(),
                                     (kRepository / "examples/primitives.wrl").string()};
  for (const char* f : {"castle-engine__demo-models/shadow_maps/spider_stand_without_shadow.wrl",
                        "coin3d__coin/models/vrml1.0/shapes/cone.wrl",
                        "michal-josef-spacek__VRML/examples/std1coo3.wrl"})
    if (fs::exists(data / f)) inputs.push_back((data / f).string());
  for (const std::string& input : inputs) {
    const std::string output = path("out.glb");
    const CommandResult r = run_lodforge("lod '" + input + "' -o " + output + " -q");
    ASSERT_EQ(r.exit_code, 0) << input << ": " << r.err;
    const nlohmann::json report = validate(output);
    EXPECT_EQ(report["errors"], 0) << input << ": " << report.dump(1);
    const auto model = gltf::read_gltf_file(output).scene.model;
    // Every LOD node switches: coverages in extras, one per MSFT_lod level
    // and one where its empty last level begins.
    std::size_t switching = 0;
    for (const auto& node : model.nodes) {
      if (!node.extras.Has("MSFT_screencoverage")) continue;
      ++switching;
      const std::size_t levels = node.extensions.count("MSFT_lod")
                                     ? node.extensions.at("MSFT_lod").Get("ids").ArrayLen()
                                     : 0;
      EXPECT_EQ(node.extras.Get("MSFT_screencoverage").ArrayLen(), levels + 1) << input;
    }
    EXPECT_GT(switching, 0u) << input;
    // Level 0 draws what the VRML output's level 0 draws.
    const std::string vrml = path("out.wrl");
    ASSERT_EQ(run_lodforge("lod '" + input + "' -o " + vrml + " -q").exit_code, 0);
    const auto in = nlohmann::json::parse(run_lodforge("info --json " + vrml).out);
    const auto out = nlohmann::json::parse(run_lodforge("info --json " + output).out);
    EXPECT_EQ(in["triangles"], out["triangles"]) << input;
  }
}

TEST_F(TempDirTest, LodGltfWritesJsonForGltfNamesAndFormat) {
  const std::string input = std::string(LODFORGE_SHARED_DATA) +
                            "/gltf/castle-engine__demo-models/x3d/inline_geometry/torus.glb";
  if (!fs::exists(input)) GTEST_SKIP() << "corpus missing: " << input;
  ASSERT_EQ(run_lodforge("lod " + input + " -o " + path("a.gltf") + " -q").exit_code, 0);
  EXPECT_EQ(read_text(path("a.gltf")).front(), '{');
  ASSERT_EQ(run_lodforge("lod " + input + " -o " + path("b.out") + " --format gltf -q").exit_code,
            0);
  EXPECT_EQ(read_text(path("b.out")).front(), '{');
  ASSERT_EQ(run_lodforge("lod " + input + " -o " + path("c.glb") + " -q").exit_code, 0);
  EXPECT_TRUE(read_text(path("c.glb")).starts_with("glTF"));
  // A name that is neither glTF nor VRML / X3D, without --format.
  const CommandResult bad = run_lodforge("lod " + input + " -o " + path("d.txt") + " -q");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("written as .gltf or .glb"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("d.txt")));
}

// `format` of every corpus glTF file as GLB and as glTF JSON: valid, the
// same triangles as the input (`info`), and a name of no scene format
// refused, nothing written. A VRML 1.0 scene goes to a glTF stream by --format.
using FormatGltf = LodGltf;
TEST_F(FormatGltf, CorpusScenesAreWrittenBackAsGlbAndJson) {
  const auto files = gltf_corpus_files();
  if (files.empty()) GTEST_SKIP() << "no glTF corpus";
  for (const std::string& input : files) {
    const auto in = nlohmann::json::parse(run_lodforge("info --json '" + input + "'").out);
    for (const char* name : {"f.glb", "f.gltf"}) {
      const std::string output = path(name);
      const CommandResult r = run_lodforge("format -q '" + input + "' -o " + output);
      ASSERT_EQ(r.exit_code, 0) << input << ": " << r.err;
      EXPECT_EQ(read_text(output).starts_with("glTF"), std::string(name) == "f.glb") << input;
      EXPECT_EQ(validate(output)["errors"], 0) << input << " -> " << name;
      const auto out = nlohmann::json::parse(run_lodforge("info --json " + output).out);
      EXPECT_EQ(in["triangles"], out["triangles"]) << input << " -> " << name;
      fs::remove(output);
    }
  }
  const CommandResult bad = run_lodforge("format '" + files.front() + "' -o " + path("f.txt"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("written as .gltf or .glb"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("f.txt")));
  const CommandResult piped = run_lodforge(
      "format -q " + (kRepository / "examples/scene.wrl").string() + " -o - --format glb");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_TRUE(piped.out.starts_with("glTF"));
}

// The corpus torus through `lod` to t.glb.
class TorusLod : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    const std::string input = std::string(LODFORGE_SHARED_DATA) +
                              "/gltf/castle-engine__demo-models/x3d/inline_geometry/torus.glb";
    if (!fs::exists(input)) GTEST_SKIP() << "corpus missing: " << input;
    ASSERT_EQ(run_lodforge("lod " + input + " -o " + path("t.glb") + " -q").exit_code, 0);
  }
};

// The contact sheet of a glTF output's levels, one panel per MSFT_lod level.
TEST_F(TorusLod, LevelsSheetAndDistances) {
  const CommandResult r = run_lodforge("render " + path("t.glb") + " --levels -o " + path("t.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("t.png")));
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, std::regex(R"(\((\d+)x(\d+), (\d+) levels\))"))) << r.err;
  EXPECT_GE(std::stoi(m[3]), 3) << r.err;
  const CommandResult d =
      run_lodforge("render " + path("t.glb") + " --distances 1,10,100 -o " + path("d.png"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NE(d.err.find("3 distances"), std::string::npos) << d.err;
  EXPECT_TRUE(fs::exists(path("d.png")));
}

// What a viewer draws of a glTF output from a camera: each MSFT_lod node at
// the level its MSFT_screencoverage chooses. Just inside and just beyond each
// switching distance lodforge wrote (lodforge_lod, measured from the centre
// of the mesh's box), the level before and the level after; beyond the
// vanishing distance nothing.
TEST_F(TorusLod, LevelSeenFromADistanceIsTheOneItsCoverageChooses) {
  const tinygltf::Model model = gltf::read_gltf_file(path("t.glb")).scene.model;
  const auto lod = std::find_if(model.nodes.begin(), model.nodes.end(),
                                [](const auto& n) { return n.extensions.count("MSFT_lod") > 0; });
  ASSERT_NE(lod, model.nodes.end());
  const tinygltf::Value& info = lod->extras.Get("lodforge_lod");
  const tinygltf::Value& levels = info.Get("levels");
  ASSERT_GE(levels.ArrayLen(), 3u);
  // The scene is the torus node alone: its box centre is the scene's.
  const TriangleMesh full = gltf::scene_mesh(model);
  Box3 box;
  for (const Vec3& p : full.positions) box.add(p);
  const Vec3 along{0.6f, 0.0f, 0.8f};
  const double angle = info.Get("camera_angle").GetNumberAsDouble();
  auto drawn_at = [&](double d) {
    return gltf::scene_mesh_seen_from(model, {box.center() + along * float(d), angle})
        .triangle_count();
  };
  for (std::size_t k = 1; k < levels.ArrayLen(); ++k) {
    const double at = levels.Get(int(k)).Get("switch_distance").GetNumberAsDouble();
    const auto before = std::size_t(levels.Get(int(k) - 1).Get("triangles").GetNumberAsInt());
    const auto after = std::size_t(levels.Get(int(k)).Get("triangles").GetNumberAsInt());
    EXPECT_EQ(drawn_at(at * 0.999), before) << "level " << k << " at " << at;
    EXPECT_EQ(drawn_at(at * 1.001), after) << "level " << k << " at " << at;
  }
  const double vanish = info.Get("vanishing_distance").GetNumberAsDouble();
  EXPECT_GT(drawn_at(vanish * 0.999), 0u);
  EXPECT_EQ(drawn_at(vanish * 1.001), 0u);
}

// `render` draws a glTF scene in its materials' base colours (the Stag's
// browns and blacks), not grey.
TEST_F(TempDirTest, RenderGltfInItsMaterialsColours) {
  const std::string input = std::string(LODFORGE_SHARED_DATA) +
                            "/gltf/castle-engine__demo-models/animation/gltf_skinned_animation/"
                            "animals_from_quaternius/Stag.gltf";
  if (!fs::exists(input)) GTEST_SKIP() << "corpus missing: " << input;
  const CommandResult r =
      run_lodforge("render " + input + " -o " + path("stag.png") + " --size 200x200");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image image = read_texture(path("stag.png")).image;
  std::size_t brown = 0;
  for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4)
    if (image.pixels[i] > image.pixels[i + 2] + 30) ++brown;
  EXPECT_GT(brown, 500u);
}

// `render` draws a glTF scene's base-colour textures: the Fox (a white
// material with an orange texture, an external PNG) is orange, white with
// --no-textures; its levels in a .glb written by `lod` are orange too.
TEST_F(TempDirTest, RenderGltfTextures) {
  const std::string input = std::string(LODFORGE_SHARED_DATA) +
                            "/gltf/castle-engine__demo-models/animation/gltf_skinned_animation/"
                            "fox_from_khronos/Fox.gltf";
  if (!fs::exists(input)) GTEST_SKIP() << "corpus missing: " << input;
  auto orange = [&](const std::string& png) {
    const Image image = read_texture(png).image;
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4)
      if (image.pixels[i] > 120 && image.pixels[i] > image.pixels[i + 2] + 60) ++n;
    return n;
  };
  ASSERT_EQ(run_lodforge("render " + input + " -o " + path("a.png") + " --size 200x200").exit_code,
            0);
  EXPECT_GT(orange(path("a.png")), 500u);
  ASSERT_EQ(
      run_lodforge("render " + input + " -o " + path("b.png") + " --size 200x200 --no-textures")
          .exit_code,
      0);
  EXPECT_EQ(orange(path("b.png")), 0u);
  ASSERT_EQ(run_lodforge("lod " + input + " -o " + path("fox.glb") + " -q").exit_code, 0);
  const CommandResult r =
      run_lodforge("render " + path("fox.glb") + " --levels --size 200x200 -o " + path("c.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(orange(path("c.png")), 1000u);
}

// `render` draws a glTF base-colour texture as glTF viewers do: the texel
// scales the base colour (factor x texture), a texture's alpha cuts holes
// only in alphaMode MASK, and KHR_texture_transform moves the coordinates.
// A quad facing the camera, textured with a 2 x 1 image: a transparent white
// texel (left half) and an opaque blue one (right half), clamped at the edges.
TEST_F(TempDirTest, RenderGltfTextureAsGltfViewersDraw) {
  Image texels(2, 1);
  texels.pixels = {255, 255, 255, 0, 0, 0, 255, 255};
  write_png(texels, path("texels.png"));
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const float uvs[] = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string bin(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
  bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
  write("quad.bin", bin);
  auto scene = [&](const std::string& name, const std::string& material,
                   const std::string& transform) {
    return write(name, R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                  "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.5, 1],
                     "baseColorTexture": {"index": 0)" +
                           transform + R"(}})" + material + R"(}],
      "textures": [{"source": 0, "sampler": 0}],
      "samplers": [{"wrapS": 33071, "wrapT": 33071}],
      "images": [{"uri": "texels.png"}],
      "buffers": [{"uri": "quad.bin", "byteLength": 92}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                      {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                      {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
         "min": [-1, -1, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
  };
  struct Counts {
    std::size_t pink = 0, blue = 0;
  };
  auto drawn = [&](const std::string& gltf) {
    const std::string png = gltf + ".png";
    const CommandResult r =
        run_lodforge("render " + gltf + " -o " + png + " --size 200x200 --view 0,0");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    Counts c;
    const Image image = read_texture(png).image;
    for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
      const int red = image.pixels[i], green = image.pixels[i + 1], blue = image.pixels[i + 2];
      c.pink += red > green + 60 && red > blue + 60;  // white x (1, 0.5, 0.5)
      c.blue += blue > red + 60;                      // blue x (1, 0.5, 0.5)
    }
    return c;
  };
  // OPAQUE (the default): the transparent texel is drawn, scaled to pink.
  const Counts opaque = drawn(scene("opaque.gltf", "", ""));
  EXPECT_GT(opaque.pink, 2000u);
  EXPECT_GT(opaque.blue, 2000u);
  // MASK: below the cutoff, a hole.
  const Counts mask = drawn(scene("mask.gltf", R"(, "alphaMode": "MASK", "alphaCutoff": 0.5)", ""));
  EXPECT_EQ(mask.pink, 0u);
  EXPECT_GT(mask.blue, 2000u);
  // The transform maps every u into the blue texel's quarter.
  const Counts moved = drawn(scene(
      "moved.gltf", "",
      R"(, "extensions": {"KHR_texture_transform": {"offset": [0.75, 0], "scale": [0.25, 1]}})"));
  EXPECT_EQ(moved.pink, 0u);
  EXPECT_GT(moved.blue, 2 * opaque.blue * 9 / 10);
}

TEST_F(TempDirTest, LodGltfBadInputIsExitOneNamingTheFile) {
  const std::string bad =
      write("bad.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 3}]})");
  const CommandResult r = run_lodforge("lod " + bad + " -o " + path("out.glb") + " -q");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(bad + ": node 0 refers to mesh 3, but there are 0"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("out.glb")));
}

// VRML97 and X3D scenes (classic and XML) written as glTF: every corpus
// scene gives a file without a validator error whose level 0 draws the
// triangles `info` counts in the input; the LOD nodes `lod` writes become
// MSFT_lod nodes; PNG / JPEG ImageTextures are carried as images.
using LodVrml97ToGltf = LodGltf;
TEST_F(LodVrml97ToGltf, EveryCorpusSceneBecomesValidGltf) {
  const auto files = vrml97_corpus_files(true);
  ASSERT_GE(files.size(), 50u) << "expected the corpus at " << LODFORGE_SHARED_DATA;
  std::size_t with_lod = 0, with_images = 0, drawing = 0;
  for (const std::string& input : files) {
    const std::string output = path("out.glb");
    fs::remove(output);
    const CommandResult r = run_lodforge("lod -q '" + input + "' -o " + output);
    ASSERT_EQ(r.exit_code, 0) << input << ": " << r.err;
    const nlohmann::json report = validate(output);
    EXPECT_EQ(report["errors"], 0) << input << ": " << report.dump(1);
    auto triangles = [](const std::string& file) {
      const CommandResult info = run_lodforge("info --json -q '" + file + "'");
      EXPECT_EQ(info.exit_code, 0) << file << ": " << info.err;
      return info.exit_code ? SIZE_MAX
                            : nlohmann::json::parse(info.out)["triangles"].get<std::size_t>();
    };
    const std::size_t drawn = triangles(input);
    EXPECT_EQ(triangles(output), drawn) << input;
    drawing += drawn > 0;
    const auto out = gltf::read_gltf_file(output).scene.model;
    const bool lod = std::any_of(out.nodes.begin(), out.nodes.end(),
                                 [](const auto& n) { return n.extensions.count("MSFT_lod") > 0; });
    with_lod += lod;
    with_images += !out.images.empty();
  }
  // Most scenes that draw get LODs (the rest are too small to simplify);
  // the textured ones keep their images.
  EXPECT_GE(with_lod * 2, drawing) << with_lod << " of " << drawing;
  EXPECT_GE(with_images, 10u);
}

}  // namespace
}  // namespace lodforge::testing
