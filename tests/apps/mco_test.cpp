// `lodforge mco build | extract | info | query | scan` as a user runs them: exit
// codes, outputs, the range-scan path end to end, and bad model files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/run_command.h"
#include "lodforge/mesh/mesh_io.h"
#include "mesh/test_meshes.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::read_text;
using testing::run_lodforge;

class McoCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lodforge_mco_cli_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    mesh_ = path("torus.ply");
    write_mesh(test::make_torus(1.0f, 0.35f, 32, 16), mesh_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Builds the torus model (once per test, or with further `flags` into `name`).
  std::string model(const std::string& name = "torus.mco", const std::string& flags = "") {
    std::string m = path(name);
    auto r =
        run_lodforge("mco build " + mesh_ + " -o " + m + " --resolution 20 --threads 2" + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return m;
  }
  // `mco info MODEL --json`, parsed.
  static nlohmann::json info_json(const std::string& m) {
    return nlohmann::json::parse(run_lodforge("mco info " + m + " --json").out);
  }
  fs::path dir_;
  std::string mesh_;
};

TEST_F(McoCli, BuildInfoExtract) {
  std::string m = model();
  ASSERT_TRUE(fs::exists(m));
  auto info = run_lodforge("mco info " + m + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  auto j = nlohmann::json::parse(info.out);
  for (const char* k : {"version", "depth", "cells", "priorities", "full_triangles", "levels"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["version"].get<int>(), 4);
  const auto full = j["full_triangles"].get<std::uint64_t>();
  const auto priorities = j["priorities"].get<std::uint64_t>();

  auto text = run_lodforge("mco info " + m);
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_THAT(text.err, HasSubstr("marching-cube octree, version 4"));

  std::string out = path("full.ply");
  auto r = run_lodforge("mco extract " + m + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_mesh(out).triangle_count(), full);

  r = run_lodforge("mco extract " + m + " -o " + path("half.obj") + " --percent 50");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("nearest reachable"));
  auto half = read_mesh(path("half.obj")).triangle_count();
  EXPECT_NEAR(static_cast<double>(half), full / 2.0, full * 0.05);

  r = run_lodforge("mco extract " + m + " -o " + path("p.ply") + " --priority 10");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("priority 10 of 10 read"));

  r = run_lodforge("mco extract " + m + " -o " + path("big.ply") + " --priority " +
                   std::to_string(priorities + 100));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("clamped"));
  // -q, as for the other commands: no warning, the summary line stays.
  r = run_lodforge("mco extract -q " + m + " -o " + path("big.ply") + " --priority " +
                   std::to_string(priorities + 100));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, Not(HasSubstr("warning")));
  EXPECT_THAT(r.err, HasSubstr("triangles"));
}

// --metric distance orders the expansions by the distance metric: a model of
// the same full resolution, numbered differently; an unknown metric is a usage error.
// A part thinner than a cell comes apart (unless the mesh is closed: then
// bridges keep it whole), parts closer than a cell join: the build says so
// (and where), and says nothing when the parts are kept.
TEST_F(McoCli, BuildSaysWhenTheModelDoesNotKeepTheInputsParts) {
  auto kept = run_lodforge("mco build " + mesh_ + " -o " + path("t.mco") + " --resolution 20");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_EQ(kept.err.find("connected part"), std::string::npos) << kept.err;
  // A tube half a cell thick: closed, it is kept whole by bridges; open (one
  // triangle missing: no bridges), it comes apart.
  TriangleMesh tube = test::make_torus(1.0f, 0.03f, 64, 8);
  const std::string thin = path("thin.ply"), open = path("open.ply");
  write_mesh(tube, thin);
  auto bridged = run_lodforge("mco build " + thin + " -o " + path("thin.mco") + " --resolution 20");
  ASSERT_EQ(bridged.exit_code, 0) << bridged.err;
  EXPECT_EQ(bridged.err.find("connected part"), std::string::npos) << bridged.err;
  EXPECT_NE(bridged.err.find("part bridges)"), std::string::npos) << bridged.err;
  tube.triangles.pop_back();
  write_mesh(tube, open);
  auto apart = run_lodforge("mco build " + open + " -o " + path("open.mco") + " --resolution 20");
  ASSERT_EQ(apart.exit_code, 0) << apart.err;
  EXPECT_NE(apart.err.find("where the input has 1"), std::string::npos) << apart.err;
  EXPECT_NE(apart.err.find("A finer --resolution"), std::string::npos) << apart.err;
  // A closed part smaller than a cell leaves no surface: the build names it
  // and the resolution that keeps it, and at that resolution it is kept.
  TriangleMesh speck = test::make_icosphere(2);
  const TriangleMesh tiny = test::make_cube(0.03f, {3, 0, 0});
  const auto base = static_cast<std::uint32_t>(speck.positions.size());
  speck.positions.insert(speck.positions.end(), tiny.positions.begin(), tiny.positions.end());
  for (Triangle t : tiny.triangles)
    speck.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const std::string specks = path("speck.ply");
  write_mesh(speck, specks);
  auto gone = run_lodforge("mco build " + specks + " -o " + path("speck.mco") + " --resolution 20");
  ASSERT_EQ(gone.exit_code, 0) << gone.err;
  const std::string keep = "--resolution 269 would keep it";  // 2 x 4.03 / 0.03
  EXPECT_NE(gone.err.find("the input's part of 12 triangles in [3 0 0]..[3.03 0.03 0.03] left no "
                          "surface"),
            std::string::npos)
      << gone.err;
  EXPECT_NE(gone.err.find(keep), std::string::npos) << gone.err;
  auto kept_at =
      run_lodforge("mco build " + specks + " -o " + path("speck.mco") + " --resolution 269");
  ASSERT_EQ(kept_at.exit_code, 0) << kept_at.err;
  EXPECT_EQ(kept_at.err.find("connected part"), std::string::npos) << kept_at.err;
  // The teapot's lid, body and handle touch: at the default resolution they join.
  const std::string teapot = std::string(LODFORGE_SHARED_DATA) + "/meshes/teapot.obj";
  if (!fs::exists(teapot)) GTEST_SKIP() << teapot << " missing";
  auto join = run_lodforge("mco build " + teapot + " -o " + path("teapot.mco"));
  ASSERT_EQ(join.exit_code, 0) << join.err;
  EXPECT_NE(join.err.find("has 1 connected part where the input has 3: parts closer than"),
            std::string::npos)
      << join.err;
}

TEST_F(McoCli, PriorityMetricChoice) {
  std::string area = model(), distance = model("distance.mco", " --metric distance");
  ASSERT_TRUE(fs::exists(distance));
  EXPECT_EQ(info_json(area)["full_triangles"], info_json(distance)["full_triangles"]);
  EXPECT_NE(read_text(area), read_text(distance));
  auto r = run_lodforge("mco build " + mesh_ + " -o " + path("v.mco") + " --metric volume");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("volume"));
  EXPECT_FALSE(fs::exists(path("v.mco")));
}

// --surface-vertices keeps every level's vertices on the surface: the same
// model but for the coarse levels' own, placed vertices (fewer vertices).
TEST_F(McoCli, SurfaceVerticesChoice) {
  std::string placed = model(), surface = model("surface.mco", " --surface-vertices");
  ASSERT_TRUE(fs::exists(surface));
  EXPECT_EQ(info_json(placed)["full_triangles"], info_json(surface)["full_triangles"]);
  EXPECT_EQ(info_json(placed)["cells"], info_json(surface)["cells"]);
  EXPECT_GT(info_json(placed)["vertices"].get<std::uint64_t>(),
            info_json(surface)["vertices"].get<std::uint64_t>());
}

// A progressive file cut anywhere (a partial download) answers info and
// extract for the levels it holds: a percentage of the whole model beyond
// them is clamped to the finest level held, with a message; a cut before
// the first level is an error without output.
TEST_F(McoCli, TruncatedFilesAnswerForTheLevelsTheyHold) {
  std::string m = model();
  const std::string data = read_text(m);
  const auto whole = info_json(m);
  const auto full = whole["full_triangles"].get<std::uint64_t>();
  const auto priorities = whole["priorities"].get<std::uint64_t>();
  std::string cut = path("cut.mco");
  std::size_t answered = 0;
  std::uint64_t previous_held = 0;
  for (int i = 1; i <= 50; ++i) {
    const std::size_t size = data.size() * std::size_t(i) / 51;
    std::ofstream(cut, std::ios::binary) << data.substr(0, size);
    const std::string out = path("cut.ply");
    fs::remove(out);
    auto info = run_lodforge("mco info " + cut + " --json");
    auto extract = run_lodforge("mco extract " + cut + " -o " + out + " --percent 50");
    if (info.exit_code != 0) {
      // Only a cut before the first level's end is refused.
      EXPECT_EQ(answered, 0u) << "cut at " << size;
      EXPECT_EQ(info.exit_code, 1);
      EXPECT_THAT(info.err, HasSubstr("truncated .mco file"));
      EXPECT_EQ(extract.exit_code, 1);
      EXPECT_FALSE(fs::exists(out));
      continue;
    }
    ++answered;
    const auto j = nlohmann::json::parse(info.out);
    EXPECT_TRUE(j["truncated"].get<bool>());
    EXPECT_EQ(j["file_priorities"].get<std::uint64_t>(), priorities);
    EXPECT_EQ(j["full_triangles"].get<std::uint64_t>(), full);
    const auto held = j["held_triangles"].get<std::uint64_t>();
    EXPECT_GE(held, previous_held) << "a longer prefix holds at least as much";
    previous_held = held;
    EXPECT_LT(j["priorities"].get<std::uint64_t>(), priorities);
    EXPECT_THAT(info.err, HasSubstr("the file ends after priority"));
    ASSERT_EQ(extract.exit_code, 0) << extract.err;
    const std::size_t got = read_mesh(out).triangle_count();
    if (held < full / 2) {
      EXPECT_EQ(got, held);  // clamped to the finest level held
      EXPECT_THAT(extract.err, HasSubstr("clamped"));
    } else {
      EXPECT_LE(got, held);
      EXPECT_NEAR(double(got), double(full) / 2, 0.1 * double(full));
    }
  }
  EXPECT_GE(answered, 40u);
  // The whole file is not truncated.
  EXPECT_FALSE(whole["truncated"].get<bool>());
}

TEST_F(McoCli, CorruptedOrWrongFilesAreErrorsWithoutOutput) {
  std::string m = model();
  std::string data = read_text(m);
  std::string bad = path("bad.mco");
  data[data.size() / 3] ^= 0x40;
  std::ofstream(bad, std::ios::binary) << data;
  std::string out = path("out.ply");
  auto r = run_lodforge("mco extract " + bad + " -o " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("checksum mismatch"));
  EXPECT_FALSE(fs::exists(out));

  r = run_lodforge("mco extract " + mesh_ + " -o " + out);  // a mesh, not a model
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("not a .mco model"));
  EXPECT_FALSE(fs::exists(out));

  r = run_lodforge("mco info " + path("none.mco"));
  EXPECT_EQ(r.exit_code, 1);
  r = run_lodforge("mco build " + path("none.ply") + " -o " + path("none.mco"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_FALSE(fs::exists(path("none.mco")));
  // Usage errors: two targets, a resolution out of range, no subcommand.
  EXPECT_EQ(run_lodforge("mco extract " + m + " -o " + out + " --percent 5 --priority 3").exit_code,
            2);
  EXPECT_EQ(run_lodforge("mco build " + mesh_ + " -o x.mco --resolution 1").exit_code, 2);
  EXPECT_EQ(run_lodforge("mco").exit_code, 2);
}

// `mco query` on the torus (ring in the xy plane, R = 1, r = 0.35): answers in
// the order of the options; a ray through the hole misses, one from +x hits
// the outer side; the tube's centre line is inside, the torus's centre not.
TEST_F(McoCli, QueryRaysAndPoints) {
  std::string m = model();
  auto r = run_lodforge("mco query " + m +
                        " --ray 0,0,5,0,0,-1 --point 1,0,0 --ray 5,0,0,-2,0,0 --point 0,0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 4u);
  const double cell = info_json(m)["cell_size"].get<double>();
  EXPECT_EQ(j[0]["ray"], nlohmann::json::parse("[0, 0, 5, 0, 0, -1]"));
  EXPECT_FALSE(j[0]["hit"].get<bool>());
  EXPECT_FALSE(j[0].contains("distance"));

  EXPECT_EQ(j[1]["point"], nlohmann::json::parse("[1, 0, 0]"));
  EXPECT_TRUE(j[1]["inside"].get<bool>());
  EXPECT_TRUE(j[1]["side_known"].get<bool>());
  EXPECT_NEAR(j[1]["distance"].get<double>(), -0.35, cell);
  EXPECT_EQ(j[1]["closest"].size(), 3u);

  ASSERT_TRUE(j[2]["hit"].get<bool>());
  EXPECT_NEAR(j[2]["distance"].get<double>(), 5 - 1.35, cell);
  EXPECT_NEAR(j[2]["point"][0].get<double>(), 1.35, cell);
  EXPECT_NEAR(j[2]["normal"][0].get<double>(), 1, 0.1);
  EXPECT_TRUE(j[2]["triangle"].is_number_unsigned());

  EXPECT_FALSE(j[3]["inside"].get<bool>());
  EXPECT_NEAR(j[3]["distance"].get<double>(), 0.65, cell);

  // A coarse level answers too, from fewer triangles.
  r = run_lodforge("mco query " + m + " --point 0,0,0 --percent 10");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).size(), 1u);
  EXPECT_THAT(r.err, HasSubstr("priority"));
}

// Bad numbers: exit 1, the option and the expected form named, nothing on
// stdout; no query at all is a usage error.
TEST_F(McoCli, QueryBadArguments) {
  std::string m = model();
  const std::pair<const char*, const char*> bad[] = {
      {"--ray", "1,2,3"},     {"--ray", "0,0,0,1,0,x"}, {"--point", "1,2"},     {"--point", "1,,2"},
      {"--point", "1,2,3,4"}, {"--point", "1,2,nan"},   {"--point", "1,2,1e99"}};
  for (auto [option, value] : bad) {
    auto r = run_lodforge("mco query " + m + " " + option + " " + value);
    EXPECT_EQ(r.exit_code, 1) << option << " " << value;
    EXPECT_TRUE(r.out.empty()) << option << " " << value;
    EXPECT_THAT(r.err, HasSubstr(std::string(option) + " '" + value + "': expected "))
        << option << " " << value;
    EXPECT_THAT(r.err, HasSubstr(std::string(option) == "--ray" ? "OX,OY,OZ,DX,DY,DZ (6 finite"
                                                                : "X,Y,Z (3 finite"));
  }
  auto r = run_lodforge("mco query " + m + " --point 1,2,3 --ray 1,2,3,0,0,0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("direction DX,DY,DZ is zero"));
  r = run_lodforge("mco query " + m);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--ray or --point"));
}

// View-dependent extraction: the camera's options, the summary line, fewer
// triangles looking away, and a coarser budget giving fewer triangles.
TEST_F(McoCli, ExtractViewDependent) {
  std::string m = model();
  const auto full = info_json(m)["full_triangles"].get<std::size_t>();
  auto view = [&](const std::string& name, const std::string& flags) {
    auto r = run_lodforge("mco extract " + m + " -o " + path(name) + " " + flags);
    EXPECT_EQ(r.exit_code, 0) << flags << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("view-dependent")) << flags;
    EXPECT_THAT(r.err, HasSubstr("worst projected error")) << flags;
    return read_mesh(path(name)).triangle_count();
  };
  const auto fine = view("fine.ply", "--camera 0,0,4 --look-at 0,0,0 --pixels 400");
  const auto coarse = view("coarse.ply",
                           "--camera 0,0,4 --look-at 0,0,0 --up 0,1,0 --fov 0.8 --pixels 400 "
                           "--pixel-error 20");
  const auto away = view("away.obj", "--camera 0,0,4 --look-at 0,0,8");
  EXPECT_LE(fine, full);
  EXPECT_LT(coarse, fine);
  EXPECT_LE(away * 20, full);
  // From near, a narrow screen culls what a wide one shows.
  const auto narrow = view("narrow.ply", "--camera 0,0,1.6 --look-at 0,0,0 --aspect 1:4");
  const auto wide = view("wide.ply", "--camera 0,0,1.6 --look-at 0,0,0 --aspect 4/1");
  EXPECT_LT(narrow, wide);
  EXPECT_EQ(view("square.ply", "--camera 0,0,1.6 --look-at 0,0,0 --aspect 1"),
            view("square2.ply", "--camera 0,0,1.6 --look-at 0,0,0 --aspect 3:3"));
}

// Bad numbers name the option and the expected form (exit 1, nothing
// written); --camera excludes the uniform targets and needs --look-at, and
// the view options need --camera (usage errors, exit 2).
TEST_F(McoCli, ExtractViewDependentBadArguments) {
  std::string m = model();
  const std::string out = path("v.ply");
  const std::string base = "mco extract " + m + " -o " + out + " ";
  const std::pair<const char*, const char*> bad[] = {
      {"--camera", "1,2"},     {"--look-at", "1,x,2"},   {"--up", "0,1,0,1"},
      {"--fov", "wide"},       {"--fov", "4"},           {"--pixels", "0"},
      {"--pixel-error", "-1"}, {"--pixel-error", "nan"}, {"--aspect", "0"},
      {"--aspect", "4:0"},     {"--aspect", "wide"}};
  for (auto [option, value] : bad) {
    std::string flags = "--camera 0,0,4 --look-at 0,0,0";
    if (std::string(option) == "--camera") flags = "--look-at 0,0,0";
    if (std::string(option) == "--look-at") flags = "--camera 0,0,4";
    auto r = run_lodforge(base + flags + " " + option + " " + value);
    EXPECT_EQ(r.exit_code, 1) << option << " " << value << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(std::string(option) + " '" + value + "': expected "))
        << option << " " << value;
    EXPECT_FALSE(fs::exists(out));
  }
  auto r = run_lodforge(base + "--camera 0,0,4 --look-at 0,0,4");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("look-at equals the camera position"));
  for (const char* target : {"--percent 50", "--triangles 100", "--priority 3"}) {
    r = run_lodforge(base + "--camera 0,0,4 --look-at 0,0,0 " + target);
    EXPECT_EQ(r.exit_code, 2) << target;
    EXPECT_THAT(r.err, HasSubstr("excludes")) << target;
  }
  r = run_lodforge(base + "--camera 0,0,4");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--look-at"));
  r = run_lodforge(base + "--pixel-error 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("requires --camera"));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(McoCli, ScanThenBuildFromTheScans) {
  std::string scans = path("scans");
  auto r = run_lodforge("mco scan " + mesh_ + " --views 6 --resolution 64 -o " + scans);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("6 scans of 64x64"));
  EXPECT_TRUE(fs::exists(fs::path(scans) / "scans.conf"));
  EXPECT_TRUE(fs::exists(fs::path(scans) / "scan005.ply"));
  std::string m = path("scanned.mco");
  r = run_lodforge("mco build " + scans + " -o " + m + " --resolution 20 --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("6 range scans"));
  // A single range-grid PLY is range input too; the .conf names the same set.
  r = run_lodforge("mco build " + (fs::path(scans) / "scans.conf").string() + " -o " + m +
                   " --resolution 20 --threads 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_lodforge("mco build " + (fs::path(scans) / "scan000.ply").string() + " -o " + m +
                   " --resolution 12 --threads 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 range scans"));
  // Bad scan input.
  EXPECT_EQ(run_lodforge("mco scan " + mesh_ + " --views 0 -o " + scans).exit_code, 2);
  EXPECT_EQ(run_lodforge("mco scan " + path("none.ply") + " -o " + scans).exit_code, 1);
}

}  // namespace
}  // namespace lodforge
