// `lodforge simplify` as other tools run it: every method on a sphere in OBJ
// and PLY, the JSON keys and how they agree with the written file, error
// budgets, VRML input flattened in world space, and the exit codes (no output
// file on any failure).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/run_command.h"
#include "lodforge/mesh/mesh_io.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::run_lodforge;

class SimplifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lodforge_simplify_cli_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    sphere_ = test::make_uv_sphere(40, 20);  // 1 520 triangles, positions only
    sphere_.normals.clear();
    sphere_.texcoords.clear();
    write_mesh(sphere_, path("sphere.obj"));
    write_mesh(sphere_, path("sphere.ply"));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  TriangleMesh sphere_;
};

TEST_F(SimplifyCli, EveryMethodOnObjAndPlyReportsWhatItWrote) {
  const std::size_t input = sphere_.triangle_count();
  for (const char* method : {"qem", "decimate", "cluster"}) {
    for (const char* ext : {"obj", "ply"}) {
      SCOPED_TRACE(std::string(method) + " " + ext);
      std::string out = path(std::string("out_") + method + "." + ext);
      auto r = run_lodforge("simplify " + path(std::string("sphere.") + ext) + " -o " + out +
                            " --ratio 0.5 --json --method " + method);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      auto j = nlohmann::json::parse(r.out);
      for (const char* k : {"method", "input_triangles", "output_triangles", "error", "stop_reason",
                            "stop_detail", "time_ms", "target_triangles"})
        EXPECT_TRUE(j.contains(k)) << k;
      EXPECT_EQ(j["method"], method);
      EXPECT_EQ(j["input_triangles"].get<std::size_t>(), input);
      EXPECT_EQ(j["target_triangles"].get<std::size_t>(), input / 2);
      const auto got = j["output_triangles"].get<std::size_t>();
      // Every method answers at or below the count here (cluster: the first
      // chain level at or below it), and none throws the sphere away.
      EXPECT_LE(got, input / 2);
      EXPECT_GT(got, input / 20);
      if (std::string(method) != "cluster") EXPECT_GE(got, input / 2 - 8);
      EXPECT_EQ(j["stop_reason"], "target reached");
      const double error = j["error"].get<double>();
      EXPECT_GT(error, 0);
      EXPECT_LT(error, 0.5);
      EXPECT_GE(j["time_ms"].get<double>(), 0);
      TriangleMesh written = read_mesh(out);
      EXPECT_EQ(written.triangle_count(), got);
      EXPECT_EQ(written.vertex_count(), j["output_vertices"].get<std::size_t>());
      if (std::string(method) == "cluster") {
        EXPECT_GE(j["simplifier_runs"].get<std::size_t>(), 1u);
      }
    }
  }
}

TEST_F(SimplifyCli, GzOutputIsGzipInTheFormatOfTheRestOfTheName) {
  std::string out = path("out.ply.gz");
  auto r = run_lodforge("simplify " + path("sphere.obj") + " -o " + out + " --ratio 0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string bytes = testing::read_text(out);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
  // gzip itself reads it, and what it holds is a PLY file.
  ASSERT_EQ(std::system(("gzip -dc " + out + " > " + path("out.ply")).c_str()), 0);
  EXPECT_TRUE(testing::read_text(path("out.ply")).starts_with("ply\n"));
  TriangleMesh written = read_mesh(out);
  EXPECT_EQ(written.triangle_count(),
            nlohmann::json::parse(r.out)["output_triangles"].get<std::size_t>());
}

TEST_F(SimplifyCli, TriangleCountIsAnUpperBoundForQem) {
  std::string out = path("t.ply");
  auto r =
      run_lodforge("simplify " + path("sphere.ply") + " -o " + out + " --triangles 100 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "qem");  // the default
  EXPECT_LE(j["output_triangles"].get<std::size_t>(), 100u);
  EXPECT_GE(j["output_triangles"].get<std::size_t>(), 90u);
  EXPECT_EQ(read_mesh(out).triangle_count(), j["output_triangles"].get<std::size_t>());
}

TEST_F(SimplifyCli, ErrorBudgetAloneAndWithACount) {
  for (const char* method : {"qem", "decimate", "cluster"}) {
    SCOPED_TRACE(method);
    std::string out = path(std::string("e_") + method + ".off");
    // Alone: as far as the budget allows; the error reached stays within it.
    auto r = run_lodforge("simplify " + path("sphere.obj") + " -o " + out +
                          " --error 0.1 --json --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["target_triangles"].is_null());
    EXPECT_DOUBLE_EQ(j["max_error"].get<double>(), 0.1);
    EXPECT_LE(j["error"].get<double>(), 0.1);
    const auto by_error = j["output_triangles"].get<std::size_t>();
    EXPECT_LT(by_error, sphere_.triangle_count());
    EXPECT_EQ(read_mesh(out).triangle_count(), by_error);

    // With a count the budget does not allow, the budget stops first.
    r = run_lodforge("simplify " + path("sphere.obj") + " -o " + out +
                     " --error 0.1 --triangles 10 --json --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["stop_reason"], "error budget reached");
    EXPECT_LE(j["error"].get<double>(), 0.1);
    EXPECT_GT(j["output_triangles"].get<std::size_t>(), 10u);
  }
}

TEST_F(SimplifyCli, HumanSummaryGoesToStderr) {
  std::string out = path("h.stl");
  auto r = run_lodforge("simplify " + path("sphere.ply") + " -o " + out + " --ratio 0.25");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_THAT(r.err, HasSubstr("target reached"));
  EXPECT_THAT(r.err, HasSubstr("(qem)"));
  EXPECT_LE(read_mesh(out).triangle_count(), sphere_.triangle_count() / 4);
}

TEST_F(SimplifyCli, VrmlSceneIsFlattenedInWorldSpace) {
  std::ostringstream points, faces;
  for (const Vec3& p : sphere_.positions) points << p.x << ' ' << p.y << ' ' << p.z << ",\n";
  for (const Triangle& t : sphere_.triangles)
    faces << t[0] << ',' << t[1] << ',' << t[2] << ",-1,\n";
  std::string scene = path("sphere.wrl");
  std::ofstream(scene) << "#VRML V1.0 ascii\nSeparator {\n Translation { translation 10 0 0 }\n"
                          " Coordinate3 { point [\n"
                       << points.str() << "] }\n IndexedFaceSet { coordIndex [\n"
                       << faces.str() << "] }\n}\n";
  for (const char* method : {"qem", "decimate", "cluster"}) {
    SCOPED_TRACE(method);
    std::string out = path(std::string("v_") + method + ".ply");
    auto r =
        run_lodforge("simplify " + scene + " -o " + out + " --ratio 0.3 --json --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["input_triangles"].get<std::size_t>(), sphere_.triangle_count());
    TriangleMesh m = read_mesh(out);
    EXPECT_EQ(m.triangle_count(), j["output_triangles"].get<std::size_t>());
    Box3 b = m.bounds();
    EXPECT_GT(b.lo.x, 8.5f);  // translated: the sphere is around x = 10
    EXPECT_LT(b.hi.x, 11.5f);
  }
}

TEST_F(SimplifyCli, UsageErrorsExitTwoAndWriteNothing) {
  const std::string in = path("sphere.obj");
  const std::string out = path("never.ply");
  for (const std::string& args : {
           " -o " + out,                                   // no target
           " -o " + out + " --ratio 0",                    // ratio outside (0, 1]
           " -o " + out + " --ratio 1.5",                  //
           " -o " + out + " --ratio -0.5",                 //
           " -o " + out + " --ratio 0.5 --triangles 100",  // two counts
           " -o " + out + " --ratio 0.5 --method fancy",   // unknown method
           " -o " + out + " --triangles 0",                //
           " -o " + out + " --error -1",                   //
           " -o " + out + " --ratio abc",                  //
           " -o " + path("never.xyz") + " --ratio 0.5",    // unknown output format
           std::string(" --ratio 0.5"),                    // no output
       }) {
    SCOPED_TRACE(args);
    auto r = run_lodforge("simplify " + in + args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_FALSE(r.err.empty());
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(path("never.xyz")));
  }
}

TEST_F(SimplifyCli, BadInputExitsOneWithAMessageAndWritesNothing) {
  const std::string out = path("never.ply");
  auto r = run_lodforge("simplify " + path("missing.ply") + " -o " + out + " --ratio 0.5");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("missing.ply"));

  std::string empty = path("empty.wrl");
  std::ofstream(empty) << "#VRML V1.0 ascii\nSeparator { }\n";
  r = run_lodforge("simplify " + empty + " -o " + out + " --ratio 0.5");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("empty"));

  std::string garbage = path("garbage.obj");
  std::ofstream(garbage) << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";  // index out of range
  r = run_lodforge("simplify " + garbage + " -o " + out + " --ratio 0.5 --method decimate");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("garbage.obj"));
  EXPECT_FALSE(fs::exists(out));

  // An output that cannot be written: exit 1, nothing left behind.
  const std::string unwritable = path("no_such_dir/out.ply");
  r = run_lodforge("simplify " + path("sphere.ply") + " -o " + unwritable + " --ratio 0.5");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("no_such_dir"));
  EXPECT_FALSE(fs::exists(path("no_such_dir")));
}

}  // namespace
}  // namespace lodforge
