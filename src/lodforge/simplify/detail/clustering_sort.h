#pragma once
/// The octree order of vertex_clustering's level 0 (see vertex_clustering.h):
/// the used vertices sorted by Morton code. Internal to simplify/.
#include <cstdint>
#include <span>

#include "lodforge/core/math.h"
#include "lodforge/simplify/detail/clustering_cut.h"

namespace lodforge::detail::clustering {

/// Sorts vertices into octree order: by Morton code, then by position (so
/// that equal coordinates are neighbours), then by index; unused ones (code
/// kUnused) last, by index, their positions unread. `keys[i]` is a vertex's
/// top 32 code bits above its index (8 bytes an item: what is moved),
/// `code[v]` its whole code.
///
/// The top 32 bits are the octree down to depth 10 and a bit; runs of equal
/// top bits are vertices in one cell of side 1/1024 of the bounding cube's
/// or less, rarely more than one, so a radix sort of 32 bits (core
/// radix_sort) and a comparison sort of those runs give the order of a sort
/// by the whole code at half the passes. Large arrays are first split
/// stably by their top 10 bits (blocks of keys counted and scattered in
/// parallel, each block into slots of its own), and the groups of
/// consecutive buckets are then sorted in parallel, each in its own memory.
/// The result does not depend on the thread count.
void sort_octree_order(Buffer<std::uint64_t>& keys, std::span<const std::uint64_t> code,
                       std::span<const Vec3> positions);

}  // namespace lodforge::detail::clustering
