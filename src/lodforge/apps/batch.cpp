#include "lodforge/apps/batch.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge::apps {
namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// The name under --out-dir of a manifest line: the relative path as
/// written when it stays inside its folder, else the file name.
std::string output_name_of(const std::string& line) {
  const fs::path p = fs::path(line).lexically_normal();
  if (p.is_relative() && !p.empty() && *p.begin() != "..") return p.string();
  return fs::path(line).filename().string();
}

std::size_t parse_count(const std::string& text, const std::string& whole) {
  std::size_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    throw std::invalid_argument("expected I/N with whole numbers, got '" + whole + "'");
  return v;
}

nlohmann::ordered_json outcome_json(const BatchOutcome& o) {
  nlohmann::ordered_json j;
  j["index"] = o.index;
  j["input"] = o.input;
  j["output"] = o.output;
  j["status"] = o.written ? "written" : "failed";
  if (!o.written) j["error"] = o.error;
  j["bytes_in"] = o.bytes_in;
  j["bytes_out"] = o.bytes_out;
  j["shapes"] = o.shapes;
  j["shapes_with_lod"] = o.shapes_with_lod;
  j["levels"] = o.levels;
  j["triangles"] = o.triangles;
  j["seconds"] = o.seconds;
  return j;
}

nlohmann::ordered_json totals_of(const nlohmann::ordered_json& files) {
  std::size_t written = 0, bytes_in = 0, bytes_out = 0, triangles = 0;
  double seconds = 0;
  for (const auto& f : files) {
    written += f["status"] == "written";
    bytes_in += f["bytes_in"].get<std::size_t>();
    bytes_out += f["bytes_out"].get<std::size_t>();
    triangles += f["triangles"].get<std::size_t>();
    seconds += f["seconds"].get<double>();
  }
  return {{"files", files.size()}, {"written", written},     {"failed", files.size() - written},
          {"bytes_in", bytes_in},  {"bytes_out", bytes_out}, {"triangles", triangles},
          {"seconds", seconds}};
}

}  // namespace

std::vector<BatchItem> read_manifest(const std::string& path) {
  std::istringstream text{std::string(FileBytes(path).view())};
  const fs::path folder = fs::path(path).parent_path();
  std::vector<BatchItem> items;
  std::string line;
  for (std::size_t number = 1; std::getline(text, line); ++number) {
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    if (line == "-")
      throw DataError(fmt::format("{}:{}: a manifest cannot name standard input", path, number));
    const fs::path p(line);
    items.push_back({.index = items.size(),
                     .input = p.is_absolute() ? line : (folder / p).lexically_normal().string(),
                     .output_name = output_name_of(line)});
  }
  return items;
}

std::vector<BatchItem> command_line_items(const std::vector<std::string>& inputs,
                                          std::size_t first) {
  std::vector<BatchItem> items;
  for (const auto& in : inputs)
    items.push_back({.index = first + items.size(),
                     .input = in,
                     .output_name = in == "-" ? "stdin.wrl" : fs::path(in).filename().string()});
  return items;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  if (slash == std::string::npos)
    throw std::invalid_argument("expected I/N (shard I of N, from 0), got '" + text + "'");
  const Shard s{.index = parse_count(text.substr(0, slash), text),
                .count = parse_count(text.substr(slash + 1), text)};
  if (s.count == 0 || s.index >= s.count)
    throw std::invalid_argument("shard I/N needs 0 <= I < N, got '" + text + "'");
  return s;
}

std::vector<BatchItem> select_shard(const std::vector<BatchItem>& items, Shard shard) {
  std::vector<BatchItem> mine;
  for (const auto& item : items)
    if (item.index % shard.count == shard.index) mine.push_back(item);
  return mine;
}

nlohmann::ordered_json batch_report(const std::string& manifest, std::size_t items, Shard shard,
                                    const std::vector<BatchOutcome>& outcomes) {
  nlohmann::ordered_json j;
  j["lodforge_batch_report"] = 1;
  j["manifest"] = manifest;
  j["items"] = items;
  j["shard"] = fmt::format("{}/{}", shard.index, shard.count);
  j["files"] = nlohmann::ordered_json::array();
  for (const auto& o : outcomes) j["files"].push_back(outcome_json(o));
  j["totals"] = totals_of(j["files"]);
  return j;
}

nlohmann::ordered_json merge_batch_reports(const std::vector<nlohmann::ordered_json>& reports,
                                           const std::vector<std::string>& names) {
  if (reports.empty()) throw DataError("no reports to merge");
  std::map<std::size_t, std::string> shards;  // shard index -> report name
  std::size_t count = 0;
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < reports.size(); ++r) {
    const auto& j = reports[r];
    if (!j.is_object() || !j.contains("lodforge_batch_report") || !j.contains("shard"))
      throw DataError(fmt::format("{}: not a report of lodforge lod --report", names[r]));
    const Shard s = [&] {
      try {
        if (!j["shard"].is_string()) throw std::invalid_argument("not text");
        return parse_shard(j["shard"].get<std::string>());
      } catch (const std::invalid_argument& e) {
        throw DataError(fmt::format("{}: bad shard: {}", names[r], e.what()));
      }
    }();
    if (r == 0) count = s.count;
    // Shards may name the manifest by other paths (other folders, other
    // machines): its file name, the batch's size and the shard count must agree.
    const auto manifest_name = [&](const nlohmann::ordered_json& report) {
      if (!report.contains("manifest") || !report["manifest"].is_string() ||
          !report.contains("items") || !report["items"].is_number_unsigned())
        throw DataError(fmt::format("{}: not a complete batch report (manifest, items)", names[r]));
      return fs::path(report["manifest"].get<std::string>()).filename().string();
    };
    if (manifest_name(j) != manifest_name(reports[0]) || j["items"] != reports[0]["items"] ||
        s.count != count)
      throw DataError(fmt::format("{}: is of another batch than {} (manifest, size or shards)",
                                  names[r], names[0]));
    if (auto [at, inserted] = shards.emplace(s.index, names[r]); !inserted)
      throw DataError(
          fmt::format("{} and {}: both are shard {}/{}", at->second, names[r], s.index, s.count));
    try {  // the fields the merge reads, with their types
      for (const auto& f : j.at("files")) {
        f.at("index").get<std::size_t>();
        f.at("status").get<std::string>();
        f.at("input").get<std::string>();
        for (const char* key : {"bytes_in", "bytes_out", "triangles"}) f.at(key).get<std::size_t>();
        f.at("seconds").get<double>();
        files.push_back(f);
      }
    } catch (const nlohmann::json::exception& e) {
      throw DataError(fmt::format("{}: not a complete batch report: {}", names[r], e.what()));
    }
  }
  std::string missing;
  for (std::size_t i = 0; i < count; ++i)
    if (!shards.count(i)) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", i, count);
  if (!missing.empty()) throw DataError("shards missing: " + missing);
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) {
    return a["index"].template get<std::size_t>() < b["index"].template get<std::size_t>();
  });
  nlohmann::ordered_json merged = reports[0];
  merged["shard"] = "0/1";
  merged["files"] = files;
  merged["totals"] = totals_of(files);
  return merged;
}

}  // namespace lodforge::apps
