// read_gltf: the corpus reads, writing and reading back gives the same scene,
// and bad files are DataErrors naming the file and what is wrong.
#include "lodforge/io/gltf/read_gltf.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "gltf/gltf_corpus.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/gltf/accessor_data.h"
#include "lodforge/io/gltf/write_gltf.h"

namespace lodforge::gltf {
namespace {

// The bytes a buffer view holds.
std::vector<unsigned char> view_bytes(const tinygltf::Model& m, int view) {
  const auto& v = m.bufferViews[std::size_t(view)];
  const auto& data = m.buffers[std::size_t(v.buffer)].data;
  return {data.begin() + long(v.byteOffset), data.begin() + long(v.byteOffset + v.byteLength)};
}

// Same scene: every object except the buffer layout equal, accessors decoding
// to the same values, buffer-view images holding the same bytes.
void expect_same_scene(const tinygltf::Model& a, const tinygltf::Model& b,
                       const std::string& what) {
  EXPECT_EQ(a.meshes, b.meshes) << what;
  EXPECT_EQ(a.nodes, b.nodes) << what;
  EXPECT_EQ(a.textures, b.textures) << what;
  EXPECT_EQ(a.samplers, b.samplers) << what;
  EXPECT_EQ(a.skins, b.skins) << what;
  EXPECT_EQ(a.scenes, b.scenes) << what;
  EXPECT_EQ(a.defaultScene, b.defaultScene) << what;
  EXPECT_EQ(a.extensionsUsed, b.extensionsUsed) << what;
  EXPECT_EQ(a.extensionsRequired, b.extensionsRequired) << what;
  ASSERT_EQ(a.accessors.size(), b.accessors.size()) << what;
  for (std::size_t i = 0; i < a.accessors.size(); ++i) {
    EXPECT_EQ(a.accessors[i].count, b.accessors[i].count) << what << " accessor " << i;
    EXPECT_EQ(a.accessors[i].componentType, b.accessors[i].componentType) << what;
    EXPECT_EQ(read_accessor(a, int(i)).values, read_accessor(b, int(i)).values)
        << what << " accessor " << i;
  }
  ASSERT_EQ(a.images.size(), b.images.size()) << what;
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].uri, b.images[i].uri) << what << " image " << i;
    EXPECT_EQ(a.images[i].image, b.images[i].image) << what << " image " << i;
    EXPECT_EQ(a.images[i].mimeType, b.images[i].mimeType) << what << " image " << i;
    ASSERT_EQ(a.images[i].bufferView >= 0, b.images[i].bufferView >= 0) << what;
    if (a.images[i].bufferView >= 0)
      EXPECT_EQ(view_bytes(a, a.images[i].bufferView), view_bytes(b, b.images[i].bufferView))
          << what << " image " << i;
  }
}

// The JSON of a .gltf file, or the JSON chunk of a .glb.
nlohmann::json gltf_json(const std::string& bytes) {
  if (!bytes.starts_with("glTF")) return nlohmann::json::parse(bytes);
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

// Removes, at any depth, properties holding their glTF 2.0 default value,
// which a writer may spell out or leave out.
void strip_defaults(nlohmann::json& j) {
  static const nlohmann::json kDefaults = {{"mode", 4},      {"interpolation", "LINEAR"},
                                           {"wrapS", 10497}, {"wrapT", 10497},
                                           {"texCoord", 0},  {"emissiveFactor", {0, 0, 0}}};
  if (j.is_object()) {
    for (auto it = kDefaults.begin(); it != kDefaults.end(); ++it)
      if (j.contains(it.key()) && j[it.key()] == it.value()) j.erase(it.key());
    for (auto& [key, value] : j.items()) strip_defaults(value);
  } else if (j.is_array()) {
    for (auto& e : j) strip_defaults(e);
  }
}

// The document without what the writer lays out anew (buffers, where
// accessors and images keep their bytes; compared apart) and without
// properties at their default values.
nlohmann::json without_layout(nlohmann::json j) {
  strip_defaults(j);
  j.erase("buffers");
  j.erase("bufferViews");
  for (auto& a : j["accessors"]) {
    a.erase("bufferView");
    a.erase("byteOffset");
    if (a.contains("sparse")) a.erase("sparse");
  }
  for (auto& i : j["images"]) {
    i.erase("uri");
    i.erase("bufferView");
    i.erase("mimeType");
  }
  return j;
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, WrittenDocumentHoldsEverythingTheInputHeld) {
  const GltfReadResult first = read_gltf_file(GetParam());
  const nlohmann::json input = without_layout(gltf_json(read_file(GetParam())));
  for (bool binary : {true, false}) {
    const nlohmann::json output =
        without_layout(gltf_json(write_gltf(first.scene, {.binary = binary})));
    // Numbers compare by value (1 == 1.0), as a glTF reader sees them.
    EXPECT_EQ(input, output) << GetParam() << ": "
                             << nlohmann::json::diff(input, output).dump().substr(0, 1000);
  }
}

TEST_P(RoundTrip, WriteThenReadGivesTheSameScene) {
  const GltfReadResult first = read_gltf_file(GetParam());
  ASSERT_FALSE(first.scene.model.meshes.empty()) << GetParam();
  for (bool binary : {true, false}) {
    const std::string bytes = write_gltf(first.scene, {.binary = binary});
    EXPECT_EQ(bytes.starts_with("glTF"), binary);
    const GltfReadResult second =
        read_gltf(bytes, {.source_name = "written", .base_dir = first.scene.base_dir});
    expect_same_scene(first.scene.model, second.scene.model,
                      GetParam() + (binary ? " as GLB" : " as glTF"));
    // Writing is deterministic.
    EXPECT_EQ(bytes, write_gltf(second.scene, {.binary = binary}));
  }
}

// The file is written piece by piece from the model's own buffer (a GLB's BIN
// chunk is not copied into a string first): the same bytes as write_gltf.
TEST_P(RoundTrip, FileHoldsTheBytesOfTheWriter) {
  const GltfReadResult first = read_gltf_file(GetParam());
  const std::string out =
      (std::filesystem::temp_directory_path() / ("lodforge_write_gltf_" + std::to_string(getpid())))
          .string();
  for (bool binary : {true, false}) {
    const GltfWriteOptions o{.binary = binary, .output_dir = "."};
    write_gltf_file(first.scene, out, o);
    EXPECT_EQ(read_file(out), write_gltf(first.scene, o)) << GetParam();
  }
  std::filesystem::remove(out);
}

INSTANTIATE_TEST_SUITE_P(Corpus, RoundTrip,
                         ::testing::ValuesIn(lodforge::testing::gltf_corpus_files()),
                         [](const auto& info) {
                           return lodforge::testing::gltf_test_name(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(RoundTrip);

TEST(GltfCorpus, IsPresent) {
  EXPECT_GE(lodforge::testing::gltf_corpus_files().size(), 20u)
      << "expected the corpus at " << LODFORGE_SHARED_DATA << "/gltf";
}

// The message of the DataError that reading `text` throws ("" if none).
std::string read_error(const std::string& text) {
  try {
    read_gltf(text, {.source_name = "bad.gltf"});
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

const std::string kAsset = R"("asset": {"version": "2.0"})";
// A buffer of 36 bytes: three float positions.
const std::string kBuffer =
    R"("buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
       "bufferViews": [{"buffer": 0, "byteLength": 36}])";

TEST(ReadGltf, ReadsATriangle) {
  const auto r = read_gltf("{" + kAsset + "," + kBuffer + R"(,
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
  const auto v = read_accessor(r.scene.model, 0);
  EXPECT_EQ(v.values, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
}

TEST(ReadGltf, BadFilesAreDataErrorsNamingFileAndProblem) {
  // Not JSON at all.
  EXPECT_NE(read_error("not json").find("bad.gltf: "), std::string::npos);
  // A GLB container cut short.
  EXPECT_NE(read_error(std::string("glTF\x02\0\0\0", 8)).find("bad.gltf: GLB"), std::string::npos);
  // An accessor past its buffer view's end.
  EXPECT_NE(read_error("{" + kAsset + "," + kBuffer +
                       R"(, "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4,
                             "type": "VEC3"}]})")
                .find("accessor 0: data of 4 elements"),
            std::string::npos);
  // A mesh naming an accessor that does not exist.
  EXPECT_NE(read_error("{" + kAsset +
                       R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 5}}]}]})")
                .find("mesh 0 refers to accessor 5, but there are 0"),
            std::string::npos);
  // A node that is its own grandparent, and a node with two parents.
  EXPECT_NE(read_error("{" + kAsset + R"(, "nodes": [{"children": [1]}, {"children": [0]}]})")
                .find("is its own ancestor"),
            std::string::npos);
  EXPECT_NE(read_error("{" + kAsset + R"(, "nodes": [{"children": [2]}, {"children": [2]}, {}]})")
                .find("node 2 is a child of nodes 0 and 1"),
            std::string::npos);
  // A buffer view past its buffer.
  EXPECT_NE(
      read_error(
          "{" + kAsset +
          R"(, "buffers": [{"byteLength": 4, "uri": "data:application/octet-stream;base64,AAAAAA=="}],
                        "bufferViews": [{"buffer": 0, "byteOffset": 2, "byteLength": 4}]})")
          .find("bufferView 0 (bytes 2 to 6) goes past the end of buffer 0"),
      std::string::npos);
}

TEST(ReadGltf, MissingExternalBufferIsADataError) {
  const std::string text =
      "{" + kAsset + R"(, "buffers": [{"byteLength": 4, "uri": "missing.bin"}]})";
  try {
    read_gltf(text, {.source_name = "x.gltf", .base_dir = "/nonexistent"});
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("x.gltf: "), std::string::npos) << e.what();
  }
}

TEST(ReadGltf, WithoutAFolderNoExternalFileIsRead) {
  // A model read from memory without base_dir may not reach into the file system.
  const std::string text =
      "{" + kAsset + R"(, "buffers": [{"byteLength": 4, "uri": "/etc/hostname"}]})";
  EXPECT_THROW(read_gltf(text, {.source_name = "x.gltf"}), DataError);
}

TEST(IsGltfPath, ByExtension) {
  EXPECT_TRUE(is_gltf_path("a/b.GLB"));
  EXPECT_TRUE(is_gltf_path("a.gltf.gz"));
  EXPECT_FALSE(is_gltf_path("a.wrl"));
}

}  // namespace
}  // namespace lodforge::gltf
