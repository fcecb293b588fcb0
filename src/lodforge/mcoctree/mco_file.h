#pragma once
/// The .mco model file: a marching-cube octree as built, to extract levels
/// from later without rebuilding. Progressive: the data come in priority
/// order, so that a reader can stop after priority N (a prefix of the file,
/// e.g. a partial download) and still extract any level up to N.
///
/// Layout (little-endian):
///
///   offset  size  field
///   0       8     magic "LFMCO\r\n\x1a" (catches text-mode mangling)
///   8       4     version (2)
///   12      4     flags: bit 0 = colours present
///   16      4     depth
///   20      12    origin (3 x f32)
///   32      4     cell size (f32)
///   36      4     sizeof(McNode) (the node record, checked on reading)
///   40      8     vertex count V
///   48      8     node count
///   56      8     LOD array length L
///   64      8     FNV-1a 64 of bytes 0..63
///   72      ...   chunks 0..L, chunk k holding what extraction at priority k
///                 needs beyond chunk k-1:
///                   u32 nodes, u32 vertices, u32 LOD entry k (0 for k = 0),
///                   u32 0, u64 accumulated[k],
///                   vertices (position, normal: 6 x f32, colour 3 x u8 if
///                   coloured) padded to 8, node records padded to 8,
///                   u64 FNV-1a 64 of the chunk's bytes before it
///
/// Nodes and vertices are numbered in the order they are stored. A node is
/// needed from the priority at which its parent is expanded or, earlier, at
/// which its parent is a cell with a split face or edge (whose vertices are
/// its children's); a vertex from the first needed node that uses it.
#include <string>
#include <string_view>

#include "lodforge/mcoctree/mc_octree.h"

namespace lodforge {

inline constexpr std::uint32_t kMcoVersion = 2;

/// The file's bytes. Never throws except std::bad_alloc.
std::string write_mco_data(const McOctree& tree);
/// Writes atomically. Throws DataError when the file cannot be written.
void write_mco_file(const McOctree& tree, const std::string& path);

struct McoReadOptions {
  /// Read only what priorities 0..N need (the LOD array and accumulation
  /// table end at N); -1 = everything. The rest of the file is not looked at.
  std::int64_t max_priority = -1;
};

/// Parses a model (or its first priorities); `name` is used in messages.
/// Throws DataError ("name: ...") for a wrong magic, an unknown version, a
/// file truncated before the data asked for, a checksum mismatch, or
/// indices out of range (vertex, child, LOD entry). A tree read up to N
/// extracts exactly the meshes of the whole tree at priorities 0..N.
McOctree read_mco_data(std::string_view data, const std::string& name,
                       const McoReadOptions& options = {});
McOctree read_mco_file(const std::string& path, const McoReadOptions& options = {});

/// Bytes of `data` (a whole .mco file) that priorities 0..N need: the prefix
/// to send or keep. Throws DataError as read_mco_data.
std::uint64_t mco_prefix_size(std::string_view data, std::uint32_t priority,
                              const std::string& name);

}  // namespace lodforge
