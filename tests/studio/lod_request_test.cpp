#include "lodforge/studio/lod_request.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>

#include "lodforge/core/error.h"

namespace lodforge::studio {
namespace {

using nlohmann::json;

TEST(LodRequest, OptionsBecomeLodOptionsAndTheirCommandLine) {
  const LodRequest r = lod_request(json{{"method", "cluster"},
                                        {"error-range", 10},
                                        {"quality", {"polygon=3"}},
                                        {"ranges", {"sphere=5,10"}},
                                        {"join", true},
                                        {"no-lines", false}},
                                   "/data/my scene.wrl", "/data/out.wrl");
  EXPECT_EQ(r.options.method, SimplifyMethod::kCluster);
  EXPECT_FLOAT_EQ(r.options.range.error_range, 0.1f);
  EXPECT_EQ(r.options.manual.at("polygon").quality, 3);
  EXPECT_EQ(r.options.manual.at("sphere").ranges, (std::vector<float>{5, 10}));
  EXPECT_TRUE(r.options.join);
  EXPECT_FALSE(r.options.no_lines);
  EXPECT_EQ(r.command_line,
            "lodforge lod '/data/my scene.wrl' -o /data/out.wrl --error-range 10 --join "
            "--method cluster --quality polygon=3 --ranges sphere=5,10");
}

TEST(LodRequest, NoOptionsAreTheDefaults) {
  const LodRequest r = lod_request(json::object(), "a.wrl", "b.wrl");
  EXPECT_EQ(r.command_line, "lodforge lod a.wrl -o b.wrl");
  EXPECT_EQ(r.options.method, LodOptions{}.method);
  EXPECT_EQ(r.options.range.error_range, LodOptions{}.range.error_range);
  EXPECT_FALSE(r.options.camera_angle_given);
}

TEST(LodRequest, BadValuesNameTheOption) {
  const auto message = [](const json& o) {
    try {
      lod_request(o, "a.wrl", "b.wrl");
    } catch (const DataError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{"error-range", 0}}).find("error-range"), std::string::npos);
  EXPECT_NE(message({{"method", "fast"}}).find("fast"), std::string::npos);
  EXPECT_NE(message({{"quality", {"torus=2"}}}).find("torus"), std::string::npos);
  EXPECT_NE(message({{"ranges", {"5,3"}}}).find("increase"), std::string::npos);
  EXPECT_NE(message({{"join", 1}}).find("join"), std::string::npos);
  EXPECT_NE(message({{"output", "x"}}).find("unknown option 'output'"), std::string::npos);
  EXPECT_NE(message(json::array()).find("object"), std::string::npos);
}

// What lod_request says to `options`: "accepted" or the DataError's text.
std::string message_of(const json& options) {
  try {
    lod_request(options, "a.wrl", "b.wrl");
  } catch (const DataError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LodRequest, ReadingWritingAndMessageOptionsAreTheCommandLines) {
  const LodRequest r = lod_request(json{{"format", "x3dv"},
                                        {"inline", true},
                                        {"max-instances", 500},
                                        {"max-triangles", 0},
                                        {"floats-per-line", 3},
                                        {"ints-per-line", 4},
                                        {"no-tabs", true},
                                        {"minimize", true},
                                        {"verbose", {"join", "coord,face"}}},
                                   "a.wrl", "b.wrl");
  EXPECT_EQ(r.format, "x3dv");
  EXPECT_TRUE(r.reread);
  EXPECT_TRUE(r.read.read_inlines);
  EXPECT_EQ(r.read.max_instances, 500u);
  EXPECT_EQ(r.read.max_triangles, 0u);
  EXPECT_EQ(r.write.floats_per_line, 3);
  EXPECT_EQ(r.write.ints_per_line, 4);
  EXPECT_TRUE(r.write.no_tabs);
  EXPECT_TRUE(r.write.minimize);
  EXPECT_TRUE(r.verbose_given);
  EXPECT_EQ(r.verbose, (std::vector<LogCategory>{LogCategory::kJoin, LogCategory::kCoord,
                                                 LogCategory::kFace}));
  EXPECT_EQ(r.command_line,
            "lodforge lod a.wrl -o b.wrl --floats-per-line 3 --format x3dv --inline "
            "--ints-per-line 4 --max-instances 500 --max-triangles 0 --minimize --no-tabs "
            "--verbose join --verbose coord,face");
  // Flags set to false and no reading option leave the scene as loaded.
  const LodRequest d = lod_request(
      json{{"inline", false}, {"minimize", false}, {"verbose", json::array()}}, "a.wrl", "b.wrl");
  EXPECT_FALSE(d.reread);
  EXPECT_FALSE(d.write.minimize);
  EXPECT_FALSE(d.verbose_given);
  EXPECT_EQ(d.format, "");
  EXPECT_EQ(d.command_line, "lodforge lod a.wrl -o b.wrl");
}

TEST(LodRequest, BadReadingWritingAndMessageValuesNameTheOption) {
  EXPECT_EQ(message_of({{"format", "obj"}}), "option format: unknown value 'obj'");
  EXPECT_EQ(message_of({{"format", 1}}), "option format: expected a string, got 1");
  EXPECT_EQ(message_of({{"inline", "yes"}}), "option inline: expected true or false");
  EXPECT_NE(message_of({{"max-instances", -1}}).find("option max-instances: -1 is outside [0, "),
            std::string::npos);
  EXPECT_EQ(message_of({{"max-triangles", 1.5}}),
            "option max-triangles: expected a whole number, got 1.5");
  EXPECT_NE(message_of({{"floats-per-line", 0}}).find("option floats-per-line: 0 is outside [1, "),
            std::string::npos);
  EXPECT_EQ(message_of({{"ints-per-line", "8"}}),
            "option ints-per-line: expected a number, got \"8\"");
  EXPECT_EQ(message_of({{"no-tabs", 1}}), "option no-tabs: expected true or false");
  EXPECT_EQ(message_of({{"minimize", nullptr}}), "option minimize: expected true or false");
  EXPECT_NE(message_of({{"verbose", {"colour"}}}).find("option verbose: unknown category 'colour'"),
            std::string::npos);
  EXPECT_NE(message_of({{"verbose", "coord,,face"}}).find("unknown category ''"),
            std::string::npos);
  EXPECT_EQ(message_of({{"verbose", 3}}), "option verbose: expected a list of strings");
}

// ---- every option of `lodforge lod` has a place in the studio ----

// The options `lodforge lod` takes that make no sense in the studio, and why.
const std::map<std::string, std::string> kNotInTheStudio = {
    {"SCENE", "the scene is the one selected in the Files list"},
    {"help", "prints the CLI's help"},
    {"output", "the Save field names the output"},
    {"out-dir", "batch: the studio runs one scene at a time"},
    {"manifest", "batch"},
    {"shard", "batch"},
    {"report", "batch report"},
    {"stats", "the page shows the statistics (Statistics panel)"},
    {"quiet", "what the CLI prints on stderr; the page has its own message filter"},
    {"threads", "set for the whole server by `lodforge studio --threads`"},
};

// The long options (and positionals) `lodforge lod --help` lists.
std::set<std::string> lod_options_from_help() {
  const std::string command = std::string(LODFORGE_EXE) + " lod --help";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  EXPECT_TRUE(pipe) << command;
  std::string help;
  char buffer[4096];
  while (pipe && std::fgets(buffer, sizeof buffer, pipe.get())) help += buffer;
  // CLI11 lists an option as "  -o,--output TEXT ..." (a default as
  // "-q{warnings},--quiet{warnings}"), a positional as "  SCENE TEXT ...";
  // description lines are indented further.
  std::set<std::string> names;
  std::istringstream lines(help);
  std::string line, section;
  const std::regex entry("^  ([^ ]+)");
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != ' ') section = line;
    std::smatch m;
    if (!std::regex_search(line, m, entry)) continue;
    if (section.starts_with("Positionals")) {
      names.insert(m[1]);
      continue;
    }
    std::stringstream parts(std::regex_replace(m[1].str(), std::regex("\\{[^}]*\\}"), ""));
    for (std::string part; std::getline(parts, part, ',');)
      if (part.starts_with("--")) names.insert(part.substr(2));
  }
  return names;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(LodRequest, EveryLodOptionHasAPanelEntryOrIsListedAsNotForTheStudio) {
  const std::set<std::string> options = lod_options_from_help();
  // The help was read: it lists the options every version has.
  for (const char* known : {"method", "error-range", "output", "SCENE"})
    ASSERT_TRUE(options.count(known)) << known << " not found in `lodforge lod --help`";
  // The page names each control after its option: name="error-range" in
  // index.html, or a family of per-type / per-category controls named
  // OPTION-X (name="verbose-coord", and studio.js's `quality-${t}`).
  const std::string page = read_text(std::string(LODFORGE_STUDIO_WEB) + "/index.html");
  const std::string script = read_text(std::string(LODFORGE_STUDIO_WEB) + "/studio.js");
  for (const auto& option : options) {
    if (kNotInTheStudio.count(option)) continue;
    const bool on_page = page.find("name=\"" + option + "\"") != std::string::npos ||
                         page.find("name=\"" + option + "-") != std::string::npos ||
                         script.find("name: `" + option + "-") != std::string::npos;
    EXPECT_TRUE(on_page) << "--" << option
                         << " of `lodforge lod` has no control on the studio's LOD options "
                            "panel (src/lodforge/studio/web/index.html) and is not in "
                            "kNotInTheStudio";
    // And the server takes it (any error but an unknown key is about the value).
    EXPECT_EQ(message_of({{option, true}}).find("unknown option"), std::string::npos)
        << "--" << option << ": lod_request does not know the option";
  }
  // The list stays short and true: each entry is an option `lod` has.
  for (const auto& [option, why] : kNotInTheStudio)
    EXPECT_TRUE(options.count(option)) << option << " (" << why << ") is no option of lod any more";
}

}  // namespace
}  // namespace lodforge::studio
