// Coin3D, an independent VRML 1.0 reader, is the oracle: for every file of the
// corpus and every example, Coin must accept what lodforge writes whenever it
// accepted the original, and Coin (on the original and on our output) and
// lodforge must agree on the node counts per type and on the number of
// IndexedFaceSet triangles a renderer draws. Primitives are compared by node
// count only: Coin tessellates them by its complexity setting.
//
// Coin runs in a child process (tests/tools/coin_probe): it crashes on some
// broken inputs, and a crash or a timeout counts as "Coin rejected".
//
// How Coin counts IndexedFaceSet triangles (Coin 4.0 sources,
// SoIndexedFaceSet::generatePrimitives and SoShape.cpp, checked by experiment
// with small files):
//   - faceType CONVEX (the default): a face of n >= 3 indices gives n - 2
//     triangles (3 as a triangle, 4 as two, more as a fan), whether or not
//     indices repeat or the face is degenerate;
//   - faceType UNKNOWN_FACE_TYPE and some face with more than 3 indices: the
//     faces go through SbTesselator (ear cutting in the face's plane); it
//     still gives n - 2 triangles per face, zero-area ones included;
//   - a face of fewer than 3 indices (e.g. "0 1 -1", or "-1 -1") ends the
//     whole shape: the faces after it give no triangles (no message in a
//     release build);
//   - a missing final -1 is supplied; an IndexedFaceSet of fewer than 3
//     indices gives nothing; out-of-range indices are not checked.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/statistics.h"
#include "tools/coin_probe_runner.h"
#include "vrml1/corpus.h"

namespace lodforge::vrml1 {
namespace {

using testing::CoinResult;
using testing::run_coin_probe;

/// Why Coin rejects a file: the reason it gives (a substring of its read
/// errors), and whether the file uses an extension (a node or field VRML 1.0
/// does not have) or Coin is wrong.
struct Rejection {
  std::string reason;
  bool extension = true;
};

/// Corpus files Coin rejects. A file Coin rejects that is not listed fails the
/// test, and so does a listed file Coin accepts or rejects for another reason:
/// the list cannot silently grow or go stale.
const std::map<std::string, Rejection>& coin_rejections() {
  static const std::map<std::string, Rejection> kList = {
      // castle-engine's VRML 2.0 nodes used in VRML 1.0 files.
      {"castle-engine__demo-models/3ds/include_3ds_from_vrml_1.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/background_alpha_tex.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/background_colors.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/background_one_color.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/background_texture1.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/background_texture2.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/empty_with_background.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/background/vrml_1/empty_with_background_ortho.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/fog/vrml_1/fog_exponential.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/fog/vrml_1/fog_linear.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/fog/vrml_1/fog_linear_locally_disabled.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/fog/vrml_1/fog_points.wrl",
       {"Node type ``Fog'' not recognized."}},
      {"castle-engine__demo-models/lights_materials/raytracer/raytracer_simple_shadow.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/lights_materials/vrml_1/forest-fog/forest-final.wrl",
       {"Node type ``Fog'' not recognized."}},
      {"castle-engine__demo-models/lights_materials/vrml_1/lights.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/speed_2.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/type_examine.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/type_fly.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/type_walk.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/type_walk_no_headlight.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/visibility_limit_1.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/navigation/vrml_1/visibility_limit_2.wrl",
       {"Node type ``NavigationInfo'' not recognized."}},
      {"castle-engine__demo-models/vrml_1/castle_extensions/inline_not_separate.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__demo-models/vrml_1/flat_triangles_octree_test.wrl",
       {"Node type ``KambiNavigationInfo'' not recognized."}},
      {"castle-engine__malfunction/data/vrmls/lake.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__malfunction/data/vrmls/mobius.wrl",
       {"Node type ``Background'' not recognized."}},
      {"castle-engine__malfunction/data/vrmls/wawoz.wrl",
       {"Node type ``Background'' not recognized."}},
      // castle-engine's extra fields of standard nodes.
      {"castle-engine__demo-models/lights_materials/raytracer/office.wrl",
       {"Unknown field \"reflSpecular\" in \"Material\""}},
      {"castle-engine__demo-models/lights_materials/vrml_1/forest-fog/forest.wrl",
       {"Unknown field \"mirror\" in \"Material\""}},
      {"castle-engine__demo-models/navigation/vrml_1/camera_orthographic_nonstandard.wrl",
       {"Unknown field \"direction\" in \"OrthographicCamera\""}},
      {"castle-engine__demo-models/navigation/vrml_1/camera_perspective_nonstandard.wrl",
       {"Unknown field \"direction\" in \"PerspectiveCamera\""}},
      {"castle-engine__demo-models/vrml_1/kings_head.wrl",
       {"Unknown field \"alphaChannel\" in \"Texture2\""}},
      // Not an extension: a Coin bug. Coin's string reader ends a string at an
      // escaped quote that is the last character of a line (`\"` + newline),
      // so the rest of Info's multi-line string is read as fields ("in").
      {"castle-engine__demo-models/vrml_1/cones.wrl",
       {"Unknown field \"in\" in \"Info\"", /*extension=*/false}},
      {"castle-engine__demo-models/vrml_1/cones_gzip_compressed.wrl.gz",
       {"Unknown field \"in\" in \"Info\"", /*extension=*/false}},
  };
  return kList;
}

std::string corpus_key(const std::string& path) {
  const std::string shared = std::string(LODFORGE_SHARED_DATA) + "/vrml1/";
  return path.starts_with(shared) ? path.substr(shared.size()) : path;
}

/// "Node type ``Fog'' ..." -> Fog; "Unknown field \"mirror\" in ..." -> mirror.
std::string extension_name(const std::string& reason) {
  std::size_t begin = reason.find("``");
  std::size_t end = std::string::npos;
  if (begin != std::string::npos) {
    begin += 2;
    end = reason.find("''", begin);
  } else if ((begin = reason.find('"')) != std::string::npos) {
    ++begin;
    end = reason.find('"', begin);
  }
  return end == std::string::npos ? std::string() : reason.substr(begin, end - begin);
}

/// Differences between two count maps, as "Type: a vs b" lines.
std::string count_differences(const std::map<std::string, std::size_t>& a,
                              const std::map<std::string, std::size_t>& b) {
  std::set<std::string> types;
  for (const auto& [type, n] : a) types.insert(type);
  for (const auto& [type, n] : b) types.insert(type);
  std::string out;
  for (const std::string& type : types) {
    const std::size_t na = a.contains(type) ? a.at(type) : 0;
    const std::size_t nb = b.contains(type) ? b.at(type) : 0;
    if (na != nb)
      out += "  " + type + ": " + std::to_string(na) + " vs " + std::to_string(nb) + "\n";
  }
  return out;
}

/// The verbatim pieces lodforge kept: bodies of unknown nodes and unknown fields.
std::vector<std::string> verbatim_texts(const scene::Scene& scene) {
  std::vector<std::string> out;
  std::set<const scene::Node*> seen;
  std::vector<const scene::Node*> stack;
  for (const auto& root : scene.roots) stack.push_back(root.get());
  while (!stack.empty()) {
    const scene::Node* node = stack.back();
    stack.pop_back();
    if (node == nullptr || !seen.insert(node).second) continue;
    if (node->is_raw) out.push_back(node->raw_body);
    for (const scene::Field& field : node->fields) {
      if (field.is_raw) out.push_back(field.raw);
    }
    for (const auto& child : node->children) stack.push_back(child.get());
  }
  return out;
}

std::string trimmed(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t\r\n") - begin + 1);
}

class CoinConformance : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
#ifndef LODFORGE_COIN_PROBE
    GTEST_SKIP() << "Coin3D (libcoin-dev) not found: no oracle";
#endif
    output_ = (std::filesystem::temp_directory_path() /
               ("lodforge_coin_" + std::to_string(getpid()) + "_" +
                testing::test_name_for(GetParam()) + ".wrl"))
                  .string();
  }
  void TearDown() override {
    std::error_code ec;
    if (!output_.empty()) std::filesystem::remove(output_, ec);
  }
  std::string output_;
};

TEST_P(CoinConformance, CoinAcceptsOurOutputAndAgreesOnCounts) {
  const std::string& path = GetParam();
  const auto& rejections = coin_rejections();
  const auto listed = rejections.find(corpus_key(path));

  const CoinResult original = run_coin_probe(path);
  if (listed == rejections.end()) {
    ASSERT_TRUE(original.accepted())
        << "Coin rejects " << path << " and the file is not listed in coin_rejections():\n"
        << original.why_rejected();
  } else {
    ASSERT_FALSE(original.accepted()) << "listed as rejected by Coin, but Coin accepts it";
    ASSERT_NE(original.why_rejected().find(listed->second.reason), std::string::npos)
        << "Coin rejects it for another reason than the listed \"" << listed->second.reason
        << "\":\n"
        << original.why_rejected();
  }

  ReadResult ours;
  ASSERT_NO_THROW(ours = read_vrml1_file(path)) << path;
  ASSERT_NO_THROW(write_vrml1_file(ours.scene, output_));
  const CoinResult written = run_coin_probe(output_);

  if (listed != rejections.end()) {
    const Rejection& rejection = listed->second;
    const std::string text = read_file(output_);
    if (rejection.extension) {
      // An extension Coin does not know: lodforge reads it with a warning and
      // writes the unknown node or field back unchanged.
      EXPECT_GT(ours.log.count(LogLevel::kWarning), 0u) << "no warning for " << rejection.reason;
      const std::string name = extension_name(rejection.reason);
      EXPECT_NE(text.find(name), std::string::npos) << name << " missing from our output";
    }
    const std::string source = read_file(path);
    for (const std::string& verbatim : verbatim_texts(ours.scene)) {
      const std::string piece = trimmed(verbatim);
      EXPECT_NE(source.find(piece), std::string::npos) << "kept text is not the original's:\n"
                                                       << piece;
      EXPECT_NE(text.find(piece), std::string::npos) << "kept text missing from our output:\n"
                                                     << piece;
    }
    // What made Coin reject the original is in our output too.
    EXPECT_FALSE(written.accepted()) << "Coin accepts our output: the extension was lost";
    EXPECT_NE(written.why_rejected().find(rejection.reason), std::string::npos)
        << "Coin rejects our output for another reason:\n"
        << written.why_rejected();
    return;
  }

  // (a) Coin accepts what we write.
  ASSERT_TRUE(written.accepted()) << "Coin rejects our output of " << path << ":\n"
                                  << written.why_rejected();
  // (b) Node counts per type: Coin on the original, Coin on ours, lodforge.
  const scene::SceneStatistics stats = scene::scene_statistics(ours.scene);
  EXPECT_EQ(original.node_counts, written.node_counts)
      << "node counts, Coin on the original vs Coin on our output:\n"
      << count_differences(original.node_counts, written.node_counts);
  EXPECT_EQ(original.node_counts, stats.node_counts)
      << "node counts, Coin vs lodforge:\n"
      << count_differences(original.node_counts, stats.node_counts);
  // Shapes met by a rendering traversal, per type: Coin against itself.
  EXPECT_EQ(original.primitive_counts, written.primitive_counts)
      << "shapes traversed, Coin on the original vs Coin on our output:\n"
      << count_differences(original.primitive_counts, written.primitive_counts);
  // (c) IndexedFaceSet triangles.
  EXPECT_EQ(original.ifs_triangles, written.ifs_triangles)
      << "IndexedFaceSet triangles, Coin on the original vs Coin on our output";
  EXPECT_EQ(original.ifs_triangles, stats.ifs_triangles)
      << "IndexedFaceSet triangles, Coin vs lodforge";
}

INSTANTIATE_TEST_SUITE_P(Corpus, CoinConformance,
                         ::testing::ValuesIn(testing::all_vrml_test_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return testing::test_name_for(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(CoinConformance);

// Small IndexedFaceSets on the edges of triangulation: Coin and lodforge
// count the same triangles (n - 2 per face of n >= 3 indices, whatever the
// faceType, repeated indices and zero-area faces included).
TEST(CoinTriangulation, SmallFaceSetsAgree) {
#ifndef LODFORGE_COIN_PROBE
  GTEST_SKIP() << "Coin3D (libcoin-dev) not found: no oracle";
#endif
  const std::string coords =
      "Coordinate3 { point [ 0 0 0, 1 0 0, 1 1 0, 0.5 0.2 0, 0 1 0, 2 0 0, 2 2 0, 0 0 5 ] }\n";
  const std::string unknown = "ShapeHints { faceType UNKNOWN_FACE_TYPE }\n";
  const std::vector<std::pair<std::string, std::size_t>> cases = {
      {"IndexedFaceSet { coordIndex [ 0, 1, 2, 3, 4, -1 ] }", 3},               // concave, CONVEX
      {unknown + "IndexedFaceSet { coordIndex [ 0, 1, 2, 3, 4, -1 ] }", 3},     // SbTesselator
      {unknown + "IndexedFaceSet { coordIndex [ 0, 2, 1, 4, -1 ] }", 2},        // self-crossing
      {unknown + "IndexedFaceSet { coordIndex [ 0, 1, 5, 1, 0, -1 ] }", 3},     // zero area
      {unknown + "IndexedFaceSet { coordIndex [ 0, 1, 7, 2, 4, -1 ] }", 3},     // not planar
      {"IndexedFaceSet { coordIndex [ 0, 1, 1, 2, 4, -1 ] }", 3},               // repeated index
      {"IndexedFaceSet { coordIndex [ 0, 1, 2, -1, 1, 2, 4, 5, 6, -1 ] }", 4},  // mixed sizes
      {"IndexedFaceSet { coordIndex [ 0, 1, 2, 4 ] }", 2},                      // no final -1
  };
  const std::string file = (std::filesystem::temp_directory_path() /
                            ("lodforge_coin_triangulation_" + std::to_string(getpid()) + ".wrl"))
                               .string();
  for (const auto& [shape, expected] : cases) {
    const std::string text = "#VRML V1.0 ascii\nSeparator {\n" + coords + shape + "\n}\n";
    write_file_atomic(file, text);
    const CoinResult coin = run_coin_probe(file);
    ASSERT_TRUE(coin.accepted()) << shape << "\n" << coin.why_rejected();
    EXPECT_EQ(coin.ifs_triangles, expected) << "Coin, " << shape;
    const scene::SceneStatistics stats =
        scene::scene_statistics(read_vrml1(text, {.source_name = "case"}).scene);
    EXPECT_EQ(stats.ifs_triangles, coin.ifs_triangles) << "lodforge vs Coin, " << shape;
  }
  // Where lodforge deliberately differs: a face of fewer than 3 indices makes
  // Coin drop the rest of the shape (an assert in its debug build); lodforge
  // skips only that face. The corpus has no such face.
  write_file_atomic(file, "#VRML V1.0 ascii\nSeparator {\n" + coords +
                              "IndexedFaceSet { coordIndex [ 0, 1, 2, -1, 0, 1, -1, 1, 2, 4, -1 ] }"
                              "\n}\n");
  EXPECT_EQ(run_coin_probe(file).ifs_triangles, 1u);
  std::error_code ec;
  std::filesystem::remove(file, ec);
}

// Every listed rejection names a file of the corpus (when the corpus is there).
TEST(CoinConformanceList, ListedFilesExist) {
  const std::string root = std::string(LODFORGE_SHARED_DATA) + "/vrml1/";
  if (!std::filesystem::is_directory(root)) GTEST_SKIP() << "no corpus at " << root;
  for (const auto& [file, rejection] : coin_rejections()) {
    EXPECT_TRUE(std::filesystem::exists(root + file)) << file;
    EXPECT_FALSE(extension_name(rejection.reason).empty()) << rejection.reason;
  }
}

}  // namespace
}  // namespace lodforge::vrml1
