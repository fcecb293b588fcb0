#pragma once
/// Batches of scenes for `lodforge lod`: a manifest lists them, a shard
/// takes a deterministic slice of the list (so that N processes, on one
/// machine or many, split a library without talking to each other), each run
/// writes a report, and `lodforge report` merges the shards' reports into the
/// report of the whole batch.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lodforge::apps {

/// One scene of a batch.
struct BatchItem {
  std::size_t index = 0;  ///< position in the whole list (manifest order)
  std::string input;      ///< the path to read
  /// Where its output goes under --out-dir: a manifest's relative path as
  /// written (folders kept, so a library's tree is mirrored), otherwise the
  /// file's name.
  std::string output_name;
};

/// Reads a manifest: one scene path per line; leading and trailing blanks are
/// trimmed, empty lines and lines starting with '#' skipped. A relative path
/// is relative to the manifest's folder. Throws DataError if the file cannot
/// be read or a line names standard input ("-").
std::vector<BatchItem> read_manifest(const std::string& path);

/// The items of scenes given on the command line, numbered after `first`
/// items, each written under its file name.
std::vector<BatchItem> command_line_items(const std::vector<std::string>& inputs,
                                          std::size_t first);

/// Shard I of N: the items whose index is I modulo N (round robin, so shards
/// of a sorted library get alike mixes of files).
struct Shard {
  std::size_t index = 0;
  std::size_t count = 1;
};

/// Parses "I/N" (0 <= I < N). Throws std::invalid_argument with the reason.
Shard parse_shard(const std::string& text);

/// The items of `shard`, in order.
std::vector<BatchItem> select_shard(const std::vector<BatchItem>& items, Shard shard);

/// What became of one scene of a batch.
struct BatchOutcome {
  std::size_t index = 0;
  std::string input, output;
  bool written = false;
  std::string error;  ///< why not, when not written
  std::size_t bytes_in = 0, bytes_out = 0;
  std::size_t shapes = 0, shapes_with_lod = 0, levels = 0;
  std::size_t triangles = 0;  ///< drawn at distance 0, every instance counted
  double seconds = 0;         ///< wall time of this scene
};

/// The report of one run: the batch's size (`items`), the shard, and one
/// entry per scene with totals. `manifest` may be empty.
nlohmann::ordered_json batch_report(const std::string& manifest, std::size_t items, Shard shard,
                                    const std::vector<BatchOutcome>& outcomes);

/// Merges the reports of the shards of one batch into the report of the
/// whole (files in manifest order, totals recomputed, "shard" 0/1). Throws
/// DataError naming the file when a report is not a lodforge batch report,
/// when reports disagree on the batch (manifest, size, shard count), when a
/// shard comes twice, or when shards are missing (listed).
nlohmann::ordered_json merge_batch_reports(const std::vector<nlohmann::ordered_json>& reports,
                                           const std::vector<std::string>& names);

}  // namespace lodforge::apps
