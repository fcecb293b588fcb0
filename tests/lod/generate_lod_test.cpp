// The scene LOD pipeline on scenes built in the test: structure, measured
// errors against the ranges, min diff, export flavours, threads, bad input.
#include "lodforge/lod/generate_lod.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lod/lod_test_support.h"
#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/compare_meshes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include "core/progress_recorder.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/statistics.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::scene_of;

scene::Scene read(const std::string& text) {
  return vrml1::read_vrml1(text).scene;
}

// The levels of the VRML 1.0 output, flattened, within their errors.
void expect_errors_bounded(const LodResult& r, const scene::Scene& out, double error_range,
                           double camera_angle, std::size_t samples) {
  ASSERT_EQ(r.shapes.size(), 1u);
  testing::expect_level_errors_bounded(
      r, [&](int k) { return scene::flatten_scene(out, {.lod_level = k}); }, r.shapes[0].ranges,
      error_range, camera_angle, samples);
}

TEST(GenerateLod, SphereGetsLevelsWithBoundedErrors) {
  const std::string text = scene_of(test::make_icosphere(4), "Scale { scaleFactor 2 2 2 }");
  for (SimplifyMethod m :
       {SimplifyMethod::kQem, SimplifyMethod::kCluster, SimplifyMethod::kDecimate}) {
    LodOptions o{.method = m, .measure_samples = 20000};
    LodResult r = generate_lod(read(text), o);
    ASSERT_EQ(r.shapes.size(), 1u);
    const auto& s = r.shapes[0];
    EXPECT_GE(s.levels.size(), 3u) << to_string(m);
    EXPECT_EQ(s.ranges.size(), s.levels.size());  // + the empty level
    EXPECT_DOUBLE_EQ(s.scale, 2.0);
    for (std::size_t k = 1; k < s.levels.size(); ++k) {
      EXPECT_LE(double(s.levels[k].triangles), 0.8 * double(s.levels[k - 1].triangles) + 1e-9);
      EXPECT_GE(s.levels[k].error, s.levels[k - 1].error * 0.999);
    }
    scene::Scene out = read(vrml1::write_vrml1(r.scene));
    EXPECT_EQ(testing::expect_lod_structure(out), 1u);
    testing::expect_indices_in_range(out);
    expect_errors_bounded(r, out, 0.02, 0.785398, 20000);
    // Level 0 is the input, triangle for triangle.
    EXPECT_EQ(scene::flatten_scene(out, {.lod_level = 0}).triangle_count(), 5120u);
  }
}

// A shape too large for float distances would get an infinite switching
// range, which is not a VRML number: refused with the shape's line.
TEST(GenerateLod, ReportsTheShapesDone) {
  const std::string text = scene_of(test::make_icosphere(3), "Cube {}");
  test::ProgressRecorder progress;
  generate_lod(read(text), {.measure_samples = 20000, .progress = progress.callback()});
  EXPECT_EQ(progress.stages(), (std::vector<std::string>{"shapes"}));
  EXPECT_TRUE(progress.completed("shapes"));
}

TEST(GenerateLod, InfiniteSwitchingRangesAreRefused) {
  for (const char* shape :
       {"Cylinder { radius 1e38 }",
        "Coordinate3 { point [0 0 0, 1e38 0 0, 0 1 0] } IndexedFaceSet { coordIndex [0, 1, 2] }"}) {
    try {
      generate_lod(read(std::string("#VRML V1.0 ascii\nSeparator {\n") + shape + " }\n"),
                   {.measure_samples = 2000});
      ADD_FAILURE() << "no error for " << shape;
    } catch (const DataError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("line 3: "));
      EXPECT_THAT(e.what(), ::testing::HasSubstr("is inf (the shape's bounding radius is inf); "
                                                 "ranges must be finite"));
    }
  }
}

TEST(GenerateLod, BunnySceneLevelsStayWithinTheErrorRangeOnScreen) {
  const std::string path = std::string(LODFORGE_SHARED_DATA) + "/meshes/bun_zipper.ply";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const std::string text = scene_of(read_mesh(path), "Scale { scaleFactor 10 10 10 }");
  LodResult r = generate_lod(read(text), {.measure_samples = 30000});
  ASSERT_EQ(r.shapes.size(), 1u);
  EXPECT_GE(r.shapes[0].levels.size(), 5u);
  scene::Scene out = read(vrml1::write_vrml1(r.scene));
  testing::expect_indices_in_range(out);
  expect_errors_bounded(r, out, 0.02, 0.785398, 30000);
}

TEST(GenerateLod, TableB5LowerErrorRangeSwitchesFarther) {
  // The original's Table B.5 behaviour on a generated model: the same levels
  // switch farther away as the error range shrinks (0.1 %, 2 %, 10 %), and
  // each level's distance grows with its error. Spacing 1 keeps every
  // candidate, so the levels are the same in all three (up to where each
  // error range lets the object vanish).
  const std::string text = scene_of(test::make_icosphere(4));
  std::vector<std::vector<float>> ranges;
  std::vector<std::vector<LevelStatistics>> levels;
  for (float p : {0.001f, 0.02f, 0.10f}) {
    LodResult r = generate_lod(
        read(text), {.range = {.error_range = p}, .level_spacing = 1.0, .measure_samples = 20000});
    ranges.push_back(r.shapes[0].ranges);
    levels.push_back(r.shapes[0].levels);
    for (std::size_t k = 1; k < r.shapes[0].levels.size(); ++k)
      EXPECT_GT(r.shapes[0].levels[k].error, r.shapes[0].levels[k - 1].error);
  }
  // The last range is the vanishing distance; the ones before it are levels'.
  const std::size_t common = std::min({ranges[0].size(), ranges[1].size(), ranges[2].size()}) - 1;
  ASSERT_GE(common, 3u);
  for (std::size_t i = 0; i < common; ++i) {
    EXPECT_EQ(levels[0][i + 1].triangles, levels[2][i + 1].triangles);
    EXPECT_GT(ranges[0][i], ranges[1][i]);
    EXPECT_GT(ranges[1][i], ranges[2][i]);
  }
}

TEST(GenerateLod, MinDiffControlsTheNumberOfLevels) {
  const std::string text = scene_of(test::make_icosphere(4));
  LodResult many = generate_lod(read(text), {.min_diff = 0.2f, .measure_samples = 20000});
  LodResult two = generate_lod(read(text), {.min_diff = 1.0f, .measure_samples = 20000});
  EXPECT_GE(many.shapes[0].levels.size(), 5u);
  // 100 %: only the original and the empty level.
  EXPECT_EQ(two.shapes[0].levels.size(), 1u);
  EXPECT_EQ(two.shapes[0].ranges.size(), 1u);
}

TEST(GenerateLod, CameraAngleComesFromTheFirstPerspectiveCamera) {
  const std::string text =
      scene_of(test::make_icosphere(2), "PerspectiveCamera { heightAngle 0.3 }");
  LodResult r = generate_lod(read(text), {.measure_samples = 20000});
  EXPECT_FLOAT_EQ(float(r.camera_angle), 0.3f);
  LodResult given = generate_lod(
      read(text),
      {.range = {.camera_angle = 1.0f}, .camera_angle_given = true, .measure_samples = 20000});
  EXPECT_FLOAT_EQ(float(given.camera_angle), 1.0f);
  // A narrower camera magnifies: ranges grow.
  EXPECT_GT(r.shapes[0].ranges[0], given.shapes[0].ranges[0]);
}

TEST(GenerateLod, ExportFlavoursAgreeOnTheWorldCentre) {
  // The original's example: a shape under Translation { 0 0 5 }, here a cube
  // whose own centre is off its origin.
  TriangleMesh cube = test::make_cube(2);
  for (auto& p : cube.positions) p.x += 1;
  const std::string text = scene_of(cube, "Translation { translation 0 0 5 }");
  auto world_centre = [&](ExportFlavour f) {
    LodResult r = generate_lod(read(text), {.export_flavour = f, .measure_samples = 20000});
    scene::Scene out = read(vrml1::write_vrml1(r.scene));
    // The centre as each target reads it: spec = local centre under the
    // shape's transform; performer = global already; reducer = the shape's
    // origin (its Translation) under the transform.
    Vec3 c{};
    Mat4 m;
    scene::traverse(out, [&](const scene::ShapeVisit& v) {
      m = v.state.transform;
      for (const auto* n : v.path) {
        if (n->type != "LOD") continue;
        const scene::FieldValue* center = n->value("center");
        if (f == ExportFlavour::kReducer) {
          EXPECT_EQ(center, nullptr);
        } else {
          c = {center->floats[0], center->floats[1], center->floats[2]};
        }
      }
    });
    if (f == ExportFlavour::kPerformer) return c;
    return m.transform_point(c);
  };
  const Vec3 expected = cube.bounds().center() + Vec3{0, 0, 5};
  for (ExportFlavour f :
       {ExportFlavour::kSpec, ExportFlavour::kPerformer, ExportFlavour::kReducer}) {
    Vec3 c = world_centre(f);
    EXPECT_NEAR(c.x, expected.x, 1e-5);
    EXPECT_NEAR(c.y, expected.y, 1e-5);
    EXPECT_NEAR(c.z, expected.z, 1e-5);
  }
}

TEST(GenerateLod, OneThreadAndAllThreadsWriteTheSameFile) {
  std::string text = "#VRML V1.0 ascii\nSeparator {\n";
  for (int i = 0; i < 6; ++i) {
    std::string part = scene_of(test::make_icosphere(2 + i % 2),
                                "Translation { translation " + std::to_string(3 * i) + " 0 0 }");
    text += part.substr(part.find('\n') + 1);
  }
  text += "Sphere {} Cone {} Cube {} }\n";
  scene::Scene in = read(text);
  std::string one =
      vrml1::write_vrml1(generate_lod(in, {.measure_samples = 20000, .threads = 1}).scene);
  std::string all =
      vrml1::write_vrml1(generate_lod(in, {.measure_samples = 20000, .threads = 0}).scene);
  EXPECT_EQ(one, all);
}

TEST(GenerateLod, SharedShapeIsSimplifiedOnceAndItsLevelsShared) {
  std::string part = scene_of(test::make_icosphere(3));
  std::string text = part;
  text.replace(text.find("IndexedFaceSet"), 14, "DEF Ball IndexedFaceSet");
  text.insert(text.rfind('}'), "Translation { translation 5 0 0 } USE Ball\n");
  LodResult r = generate_lod(read(text), {.measure_samples = 20000});
  ASSERT_EQ(r.shapes.size(), 1u);
  EXPECT_EQ(r.shapes[0].occurrences, 2u);
  scene::Scene out = read(vrml1::write_vrml1(r.scene));
  EXPECT_EQ(testing::expect_lod_structure(out), 2u);
  scene::SceneStatistics st = scene::scene_statistics(out);
  EXPECT_EQ(st.node_counts["LOD"], 2u);
  // Level nodes are shared: as many IndexedFaceSets as levels, not twice.
  EXPECT_EQ(st.node_counts["IndexedFaceSet"], r.shapes[0].levels.size());
}

TEST(GenerateLod, PerFaceMaterialsBecomeIndexedAndSurviveSimplification) {
  TriangleMesh m = test::make_icosphere(3);
  std::string text = scene_of(m, "", true);
  // PER_FACE needs one material per face: three bands of colour by height
  // (regions a simplifier can reduce inside).
  std::string colours;
  for (const auto& t : m.triangles) {
    const float z = (m.positions[t[0]].z + m.positions[t[1]].z + m.positions[t[2]].z) / 3;
    colours += z < -0.33f ? "1 0 0," : z < 0.33f ? "0 1 0," : "0 0 1,";
  }
  text.replace(text.find("[1 0 0, 0 1 0, 0 0 1]"), 21, "[" + colours + "]");
  LodResult r = generate_lod(read(text), {.measure_samples = 20000});
  ASSERT_GE(r.shapes[0].levels.size(), 2u);
  scene::Scene out = read(vrml1::write_vrml1(r.scene));
  testing::expect_indices_in_range(out);
  std::string written = vrml1::write_vrml1(out);
  // Level 0 is the input (PER_FACE); the simplified levels are indexed.
  EXPECT_THAT(written, HasSubstr("value PER_FACE\n"));
  EXPECT_THAT(written, HasSubstr("PER_FACE_INDEXED"));
  // Three distinct materials remain after de-duplication.
  scene::SceneStatistics st = scene::scene_statistics(out);
  EXPECT_EQ(st.node_counts["Material"], 2u);  // the original (kept) and the de-duplicated one
}

// A wavy grid of bent quads: level 0 must be the input node as it is (quads
// a reader splits its own way), and the simplified levels index one shared
// Coordinate3 that holds each position once.
TEST(GenerateLod, LevelZeroIsTheInputAndLevelsShareTheirCoordinates) {
  constexpr int n = 24;
  std::string text =
      "#VRML V1.0 ascii\nSeparator {\nShapeHints { faceType UNKNOWN_FACE_TYPE }\n"
      "Coordinate3 { point [\n";
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x)
      text += fmt::format("{} {} {},\n", x, y, 2 * std::sin(x * 0.7) * std::cos(y * 0.5));
  text += "] }\nIndexedFaceSet { coordIndex [\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x;
      text += fmt::format("{}, {}, {}, {}, -1,\n", a, a + 1, a + n + 2, a + n + 1);
    }
  text += "] }\n}\n";
  const scene::Scene in = read(text);
  LodResult r = generate_lod(in, {.measure_samples = 20000});
  ASSERT_EQ(r.shapes.size(), 1u);
  ASSERT_GE(r.shapes[0].levels.size(), 3u);
  const scene::Scene out = read(vrml1::write_vrml1(r.scene));
  // Per level: the face set drawn, and the Coordinate3 and ShapeHints it is drawn under.
  struct Drawn {
    const scene::Node *shape, *coords, *hints;
  };
  auto drawn = [](const scene::Scene& s, int level) {
    std::vector<Drawn> d;
    scene::traverse(s,
                    [&](const scene::ShapeVisit& v) {
                      if (v.shape.type == "IndexedFaceSet")
                        d.push_back({&v.shape, v.state.coordinate3, v.state.shape_hints});
                    },
                    {.lod_level = level});
    return d;
  };
  const auto input = drawn(in, 0), level0 = drawn(out, 0);
  ASSERT_EQ(input.size(), 1u);
  ASSERT_EQ(level0.size(), 1u);
  EXPECT_EQ(level0[0].shape->value("coordIndex")->ints, input[0].shape->value("coordIndex")->ints);
  EXPECT_EQ(level0[0].coords->value("point")->floats, input[0].coords->value("point")->floats);
  EXPECT_EQ(scene::field_or_default(*level0[0].hints, "faceType")->strings,
            std::vector<std::string>{"UNKNOWN_FACE_TYPE"});
  const scene::Node* shared = nullptr;
  std::size_t vertices = 0;
  for (std::size_t k = 1; k < r.shapes[0].levels.size(); ++k) {
    const auto level = drawn(out, int(k));
    ASSERT_EQ(level.size(), 1u) << k;
    if (!shared) shared = level[0].coords;
    EXPECT_EQ(level[0].coords, shared) << "level " << k << " has a Coordinate3 of its own";
    EXPECT_EQ(scene::field_or_default(*level[0].hints, "faceType")->strings,
              std::vector<std::string>{"CONVEX"});
    vertices += r.shapes[0].levels[k].vertices;
  }
  // Each position once: no more points than the levels' vertices together.
  ASSERT_NE(shared, nullptr);
  EXPECT_LE(shared->value("point")->floats.size() / 3, vertices);
  testing::expect_indices_in_range(out);
}

TEST(GenerateLod, ExtractWritesOneLevelWithoutLodNodes) {
  const std::string text = scene_of(test::make_icosphere(3));
  LodResult full = generate_lod(read(text), {.measure_samples = 20000});
  ASSERT_GE(full.shapes[0].levels.size(), 2u);
  const int k = int(full.shapes[0].levels.size()) - 1;  // the coarsest simplified level
  LodResult one = generate_lod(read(text), {.extract = k, .measure_samples = 20000});
  scene::Scene out = read(vrml1::write_vrml1(one.scene));
  EXPECT_EQ(testing::expect_lod_structure(out), 0u);
  EXPECT_EQ(scene::flatten_scene(out).triangle_count(), full.shapes[0].levels[k].triangles);
  // Past the last level: the empty level.
  LodResult past = generate_lod(read(text), {.extract = k + 1, .measure_samples = 20000});
  EXPECT_EQ(scene::flatten_scene(read(vrml1::write_vrml1(past.scene))).triangle_count(), 0u);
  LodResult clean = generate_lod(read(text), {.extract = -1});
  EXPECT_EQ(scene::flatten_scene(read(vrml1::write_vrml1(clean.scene))).triangle_count(), 1280u);
}

TEST(GenerateLod, ManualQualityAndRanges) {
  const std::string text = scene_of(test::make_icosphere(3));
  LodOptions o{.measure_samples = 20000};
  o.manual["polygon"] = {.quality = 4, .ranges = {10, 20, 30}};
  LodResult r = generate_lod(read(text), o);
  ASSERT_EQ(r.shapes[0].levels.size(), 3u);  // original, 2 simplified; + empty
  EXPECT_THAT(r.shapes[0].ranges, ::testing::ElementsAre(10, 20, 30));
  o.manual["polygon"] = {.quality = 0};
  scene::Scene removed = read(vrml1::write_vrml1(generate_lod(read(text), o).scene));
  EXPECT_EQ(scene::flatten_scene(removed).triangle_count(), 0u);
  o.manual["polygon"] = {.quality = 1};
  scene::Scene kept = read(vrml1::write_vrml1(generate_lod(read(text), o).scene));
  EXPECT_EQ(testing::expect_lod_structure(kept), 0u);
  EXPECT_EQ(scene::flatten_scene(kept).triangle_count(), 1280u);
}

TEST(GenerateLod, BadInputNamesTheLine) {
  const std::string text =
      "#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [0 0 0, 1 0 0, 0 1 0] }\n"
      "IndexedFaceSet { coordIndex [0, 1, 7, -1] }\n}\n";
  try {
    generate_lod(read(text));
    FAIL();
  } catch (const DataError& e) {
    EXPECT_STREQ(e.what(),
                 "line 4: IndexedFaceSet coordIndex[2] = 7 is out of range (the current "
                 "Coordinate3 has 3 points)");
  }
}

// A group USEd three times (forest-style placement) draws its shape three
// times: occurrences and the triangles-by-distance table count each instance,
// each with the ranges of the LOD node it draws.
TEST(GenerateLod, InstancesOfAUsedGroupAreCounted) {
  std::string ball = scene_of(test::make_icosphere(2));
  std::string text =
      "#VRML V1.0 ascii\nSeparator {\nDEF Tree " + ball.substr(ball.find("Separator"));
  text += "Translation { translation 5 0 0 } USE Tree\n";
  text += "Translation { translation 5 0 0 } Scale { scaleFactor 3 3 3 } USE Tree\n}\n";
  LodResult r = generate_lod(read(text), {.measure_samples = 20000});
  ASSERT_EQ(r.shapes.size(), 1u);
  const ShapeStatistics& s = r.shapes[0];
  EXPECT_EQ(s.occurrences, 3u);
  EXPECT_DOUBLE_EQ(s.scale, 3.0);
  ASSERT_FALSE(r.triangles_by_distance.empty());
  EXPECT_EQ(r.triangles_by_distance.front().first, 0.0);
  EXPECT_EQ(r.triangles_by_distance.front().second, 3 * s.levels[0].triangles);
  // Far enough away every instance is gone.
  EXPECT_EQ(r.triangles_by_distance.back().second, 0u);
}

// A group USEd under other property nodes (here: another Coordinate3 before
// each use, in one parent) gets LODs for each context; uses in a context met
// before share that context's LOD.
TEST(GenerateLod, SharedGroupGetsLodsForEveryPropertyContext) {
  constexpr int n = 16;
  auto points = [&](const char* def, float dx) {
    std::string t = fmt::format("DEF {} Coordinate3 {{ point [\n", def);
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x)
        t += fmt::format("{} {} {},\n", x + dx, y, 2 * std::sin(x * 0.7 + dx) * std::cos(y * 0.5));
    return t + "] }\n";
  };
  std::string text = "#VRML V1.0 ascii\nSeparator {\n" + points("A", 0) +
                     "DEF G Group { IndexedFaceSet { coordIndex [\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x;
      text += fmt::format("{}, {}, {}, -1, {}, {}, {}, -1,\n", a, a + 1, a + n + 2, a, a + n + 2,
                          a + n + 1);
    }
  text += "] } }\n" + points("B", 100) + "USE G\nUSE A\nUSE G\n}\n";
  const scene::Scene in = read(text);
  LodResult r = generate_lod(in, {.measure_samples = 20000});
  ASSERT_EQ(r.shapes.size(), 2u);
  std::vector<std::size_t> occurrences = {r.shapes[0].occurrences, r.shapes[1].occurrences};
  std::sort(occurrences.begin(), occurrences.end());
  EXPECT_EQ(occurrences, (std::vector<std::size_t>{1, 2}));
  for (const Diagnostic& d : r.log.entries())
    EXPECT_THAT(d.text, Not(HasSubstr("different properties")));
  const scene::Scene out = read(vrml1::write_vrml1(r.scene));
  EXPECT_EQ(scene::flatten_scene(out, {.lod_level = 0}).triangle_count(),
            scene::flatten_scene(in, {}).triangle_count());
  // Every level is drawn where its context puts it: some at x < 50 (A, twice),
  // some at x > 50 (B).
  for (std::size_t k = 1; k < std::min(r.shapes[0].levels.size(), r.shapes[1].levels.size()); ++k) {
    const TriangleMesh level = scene::flatten_scene(out, {.lod_level = int(k)});
    std::size_t a = 0, b = 0;
    for (const Vec3& p : level.positions) (p.x < 50 ? a : b) += 1;
    EXPECT_GT(a, 0u) << "level " << k;
    EXPECT_GT(b, 0u) << "level " << k;
  }
  testing::expect_indices_in_range(out);
}

// Whole chains spaced by what a viewer notices: the bunny-like smooth sphere
// reaches a few percent of its triangles, and every kept level is shown over
// at least 1.25x of distance (the last one before the object vanishes).
TEST(GenerateLod, ChainReachesACoarseLevelAndLevelsAreSpaced) {
  const std::string text = scene_of(test::make_icosphere(5));
  LodResult r = generate_lod(read(text), {.measure_samples = 20000});
  ASSERT_EQ(r.shapes.size(), 1u);
  const ShapeStatistics& s = r.shapes[0];
  ASSERT_GE(s.levels.size(), 3u);
  EXPECT_LE(double(s.levels.back().triangles), 0.05 * double(s.levels[0].triangles))
      << s.stop_reason;
  ASSERT_EQ(s.ranges.size(), s.levels.size());
  for (std::size_t i = 1; i < s.ranges.size(); ++i)
    EXPECT_GE(s.ranges[i], 1.25f * s.ranges[i - 1] * (1 - 1e-6f)) << i;
  // Switching later than the error allows is safe, never earlier.
  RangeOptions ro;
  for (std::size_t k = 1; k < s.levels.size(); ++k)
    EXPECT_GE(s.ranges[k - 1] * (1 + 1e-6), switch_distance(s.levels[k].error, 1, s.radius, ro));
  EXPECT_FALSE(s.stop_reason.empty());
  // Spacing 1 keeps more of the candidates.
  LodResult dense = generate_lod(read(text), {.level_spacing = 1.0, .measure_samples = 20000});
  EXPECT_GT(dense.shapes[0].levels.size(), s.levels.size());
}

}  // namespace
}  // namespace lodforge
