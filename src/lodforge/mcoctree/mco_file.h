#pragma once
/// The .mco model file: a marching-cube octree as built, to extract levels
/// from later without rebuilding.
///
/// Layout (little-endian, every section 8-byte aligned, so that a reader can
/// map the file and use the arrays in place):
///
///   offset  size  field
///   0       8     magic "LFMCO\r\n\x1a" (catches text-mode mangling)
///   8       4     version (1)
///   12      4     flags: bit 0 = colours present
///   16      4     depth
///   20      12    origin (3 x f32)
///   32      4     cell size (f32)
///   36      4     sizeof(McNode) (the node record, checked on reading)
///   40      8     vertex count V
///   48      8     node count
///   56      8     LOD array length L
///   64      8     FNV-1a 64 of every byte after the header
///   72      ...   positions V x 3 f32, normals V x 3 f32, colours V x 3 u8
///                 (padded to 8), nodes (McNode records), LOD array L x u32
///                 (padded to 8), accumulation table (L + 1) x u64
#include <string>
#include <string_view>

#include "lodforge/mcoctree/mc_octree.h"

namespace lodforge {

inline constexpr std::uint32_t kMcoVersion = 1;

/// The file's bytes. Never throws except std::bad_alloc.
std::string write_mco_data(const McOctree& tree);
/// Writes atomically. Throws DataError when the file cannot be written.
void write_mco_file(const McOctree& tree, const std::string& path);

/// Parses a model; `name` is used in messages. Throws DataError ("name: ...")
/// for a wrong magic, an unknown version, a truncated file, a checksum
/// mismatch, or indices out of range (vertex, child, LOD entry).
McOctree read_mco_data(std::string_view data, const std::string& name);
McOctree read_mco_file(const std::string& path);

}  // namespace lodforge
