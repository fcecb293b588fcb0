// `lodforge report REPORT... [-o MERGED]`: the reports of the shards of a
// batch (`lod --report`) merged into the report of the whole, with a summary.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "lodforge/apps/batch.h"
#include "lodforge/apps/commands.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/core/output_path.h"

namespace lodforge::apps {
namespace {

struct Settings {
  std::vector<std::string> reports;
  std::string output;
  bool quiet = false;
};

nlohmann::ordered_json read_report(const std::string& path) {
  const FileBytes bytes(path);
  try {
    return nlohmann::ordered_json::parse(bytes.view());
  } catch (const nlohmann::json::parse_error& e) {
    throw DataError(fmt::format("{}: not JSON: {}", path, e.what()));
  }
}

void print_summary(const nlohmann::ordered_json& merged, std::size_t shards) {
  const auto& t = merged["totals"];
  const double in = t["bytes_in"].get<double>(), out = t["bytes_out"].get<double>();
  fmt::print("batch of {} scenes{}: {} written, {} failed\n", t["files"].get<std::size_t>(),
             shards > 1 ? fmt::format(" in {} shards", shards) : "",
             t["written"].get<std::size_t>(), t["failed"].get<std::size_t>());
  fmt::print(
      "  input {:.1f} MB -> output {:.1f} MB ({:.2f}x), {} triangles at distance 0, "
      "{:.1f} s of work\n",
      in / 1e6, out / 1e6, in > 0 ? out / in : 0.0, t["triangles"].get<std::size_t>(),
      t["seconds"].get<double>());
  for (const auto& f : merged["files"])
    if (f["status"] != "written")
      fmt::print("  failed: {}: {}\n", f["input"].get<std::string>(),
                 f.value("error", std::string()));
}

}  // namespace

void add_report_command(CLI::App& app, Runner& run) {
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "report", "Merge the reports of a batch's shards (lod --report) and summarise them");
  cmd->add_option("REPORT", s->reports, "Reports of `lodforge lod --report`, one per shard")
      ->required();
  cmd->add_option("-o,--output", s->output, "Write the merged report (JSON) to this file");
  cmd->add_flag("-q,--quiet", s->quiet, "No summary on standard output");
  cmd->callback([s, &run] {
    run = [s] {
      if (!s->output.empty())
        check_output_paths(std::array{OutputPath{s->output, "the merged report"}}, s->reports);
      std::vector<nlohmann::ordered_json> reports;
      for (const auto& r : s->reports) reports.push_back(read_report(r));
      const nlohmann::ordered_json merged = merge_batch_reports(reports, s->reports);
      if (!s->output.empty()) write_file_atomic(s->output, merged.dump(2) + "\n");
      if (!s->quiet) print_summary(merged, reports.size());
      return merged["totals"]["failed"].get<std::size_t>() == 0 ? 0 : 1;
    };
  });
}

}  // namespace lodforge::apps
