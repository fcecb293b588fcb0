#pragma once
/// The .mco model file: the run-time model of a marching-cube octree
/// (mc_lod_model.h), to extract levels from later without rebuilding.
/// Progressive: the data come in priority order, so that a reader can stop
/// after priority N (a prefix of the file, e.g. a partial download) and still
/// extract any level up to N.
///
/// Layout (little-endian):
///
///   offset  size  field
///   0       8     magic "LFMCO\r\n\x1a" (catches text-mode mangling)
///   8       4     version (4; version 3 is read too)
///   12      4     flags: bit 0 = colours present
///   16      4     depth
///   20      12    origin (3 x f32)
///   32      4     cell size (f32)
///   36      4     triangles at full resolution (version 4; 0 in version 3)
///   40      8     vertex count V
///   48      8     cell count C
///   56      8     interval count I
///   64      8     triangle count T (over all cells and intervals)
///   72      8     priorities L
///   80      8     FNV-1a 64 of bytes 0..79
///   88      ...   chunks 0..L, chunk k holding the cells whose parent has
///                 priority k (k = 0: the root) and the vertices they use
///                 first:
///                   u32 cells, u32 intervals, u32 triangles, u32 vertices,
///                   u32 centroid vertices, u32 0, u64 accumulated[k],
///                   vertices (position 3 x f32, octahedral normal u32,
///                   colour 3 x u8 if coloured) padded to 8,
///                   cells (u32 until, u32 interval count),
///                   intervals (u32 from, u32 triangle count),
///                   triangles (3 x u32 vertex index),
///                   centroid vertex indices (u32) padded to 8,
///                   u64 FNV-1a 64 of the chunk's bytes before it
///
/// Version 2 stored the build-time tree; version 3 stores what extraction
/// reads, so reading does no triangulation; version 4 records the
/// full-resolution triangle count in the header, so that a prefix of the
/// file knows what a percentage of the whole model is.
#include <string>
#include <string_view>

#include "lodforge/mcoctree/mc_lod_model.h"

namespace lodforge {

inline constexpr std::uint32_t kMcoVersion = 4;

/// The file's bytes. Never throws except std::bad_alloc.
std::string write_mco_data(const McLodModel& model);
/// Writes atomically. Throws DataError when the file cannot be written.
void write_mco_file(const McLodModel& model, const std::string& path);

struct McoReadOptions {
  /// Read only what priorities 0..N need (the accumulation table ends at N);
  /// -1 = everything. The rest of the file is not looked at.
  std::int64_t max_priority = -1;
  /// false: skip the checksum comparisons, so that a fuzzer reaches the
  /// structural checks behind them (which still reject any inconsistent
  /// data). Never for real files.
  bool verify_checksums = true;
  /// true: data that end early (a partial download, a cut file) are read up
  /// to the last priority they hold in full, instead of being an error; data
  /// without even priority 0 are still an error.
  bool prefix = false;
};

/// What the header and the complete chunks of a .mco file say, without
/// reading the model: for a file that may be cut short.
struct McoFileSummary {
  std::uint32_t version = 0;
  std::uint64_t priorities = 0;      ///< L, the model's priorities
  std::uint64_t full_triangles = 0;  ///< at priority L; 0: not recorded (version 3)
  /// Chunks the data hold in full: priorities 0 .. complete_priorities - 1
  /// can be read (L + 1 for a whole file).
  std::uint64_t complete_priorities = 0;
  bool truncated() const { return complete_priorities < priorities + 1; }
};

/// Reads the header and walks the chunks (sizes and checksums). Throws
/// DataError as read_mco_data for a bad header or a corrupted chunk, but not
/// for data that end early.
McoFileSummary summarize_mco_data(std::string_view data, const std::string& name);

/// Parses a model (or its first priorities); `name` is used in messages.
/// Throws DataError ("name: ...") for a wrong magic, an unknown version, a
/// file truncated before the data asked for, a checksum mismatch, indices out
/// of range, a vertex position or lattice origin that is not finite,
/// intervals out of order, or triangle counts that disagree with
/// the accumulation table (so extraction can trust it). A model read up to N
/// extracts exactly the meshes of the whole model at priorities 0..N.
McLodModel read_mco_data(std::string_view data, const std::string& name,
                         const McoReadOptions& options = {});
McLodModel read_mco_file(const std::string& path, const McoReadOptions& options = {});

/// Bytes of `data` (a whole .mco file) that priorities 0..N need: the prefix
/// to send or keep. Throws DataError as read_mco_data.
std::uint64_t mco_prefix_size(std::string_view data, std::uint32_t priority,
                              const std::string& name);

}  // namespace lodforge
