#pragma once
/// The data of vertex_clustering (see vertex_clustering.h for the contract):
/// the working arrays' allocator, the implicit octree of Morton codes and one
/// cut of it (a level). Internal to simplify/.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/scalable_allocator.h>

#include "lodforge/core/math.h"
#include "lodforge/core/quadric.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge::detail::clustering {

/// The allocator of the call's working arrays: TBB's scalable allocator,
/// which keeps freed large blocks for the next call where glibc's malloc
/// hands them back to the system, so that every call faulted their pages in
/// again; and resize() leaves elements without a default member initialiser
/// (indices, codes, quadrics) uninitialised: every array resized here is
/// written in full before it is read, and zeroing it first would be a serial
/// pass over memory.
template <class T>
struct BufferAllocator : tbb::scalable_allocator<T> {
  using value_type = T;
  // The name the standard gives it; it hides the base's, which would rebind
  // to tbb::scalable_allocator and lose construct() below.
  template <class U>
  struct rebind {  // NOLINT(readability-identifier-naming)
    using other = BufferAllocator<U>;
  };
  BufferAllocator() = default;
  template <class U>
  BufferAllocator(const BufferAllocator<U>& /*other*/) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const BufferAllocator<U>& /*other*/) const noexcept {
    return true;
  }
};
template <class T>
using Buffer = std::vector<T, BufferAllocator<T>>;

constexpr int kMaxDepth = 21;  ///< bits per axis of the Morton code (3 x 21 = 63)

/// An unused vertex's code: above every 63-bit code, so it sorts last.
constexpr std::uint64_t kUnused = ~std::uint64_t(0);

/// Depth of the deepest octree cell two codes share (kMaxDepth if equal).
inline int common_depth(std::uint64_t a, std::uint64_t b) {
  const std::uint64_t x = a ^ b;
  if (x == 0) return kMaxDepth;
  const int highest = 63 - std::countl_zero(x);
  return kMaxDepth - 1 - highest / 3;
}

/// The bounding cube of the used vertices, the root of the octree.
struct Octree {
  Vec3 lo;          ///< corner of the bounding cube
  double side = 1;  ///< its side

  /// Corner of the depth-`depth` cell holding `code`.
  Vec3 cell_lo(std::uint64_t code, int depth) const {
    const int shift = kMaxDepth - depth;
    const double unit = side / double(1u << kMaxDepth);
    auto axis = [&](int a) {
      const std::uint32_t q = compact_bits(code >> (2 - a)) >> shift << shift;
      return static_cast<float>(lo[a] + q * unit);
    };
    return {axis(0), axis(1), axis(2)};
  }
  double cell_side(int depth) const { return side / double(1u << depth); }

 private:
  /// The inverse of morton_spread: every third bit, packed.
  static std::uint32_t compact_bits(std::uint64_t x) {
    x &= 0x1249249249249249ull;
    x = (x ^ (x >> 2)) & 0x10c30c30c30c30c3ull;
    x = (x ^ (x >> 4)) & 0x100f00f00f00f00full;
    x = (x ^ (x >> 8)) & 0x1f0000ff0000ffull;
    x = (x ^ (x >> 16)) & 0x1f00000000ffffull;
    x = (x ^ (x >> 32)) & 0x1fffffull;
    return static_cast<std::uint32_t>(x);
  }
};

/// One cut of the octree: the vertices of a level (in Morton order) and the
/// triangles and lines over them.
struct Cut {
  Buffer<Vec3> pos;
  Buffer<std::uint32_t> weight;  ///< distinct input coordinates represented
  Buffer<std::uint32_t> orig;    ///< input vertex giving attributes / vertex_map
  Buffer<std::uint64_t> code;    ///< Morton code of an input coordinate in the cell
  Buffer<Quadric> quadric;       ///< empty unless the quadric heuristic is on
  Buffer<Triangle> tris;
  Buffer<std::uint32_t> tri_origin;  ///< input triangle of each triangle
  Buffer<Segment> lines;
  int depth = kMaxDepth + 1;  ///< cut depth (level 0: below the finest cell)

  std::size_t size() const { return pos.size(); }
};

/// Runs body(lo, hi) over [0, n) in TBB's parallel_for with grain kGrain
/// (on the calling thread when n is within one grain): coarse enough that a
/// task's work outweighs its cost (an item of a pass over an array costs
/// nanoseconds; choosing a cell's representative, up to microseconds).
template <std::size_t kGrain = 2048, class Body>
void for_chunks(std::size_t n, const Body& body) {
  if (n <= kGrain) {
    body(std::size_t(0), n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

}  // namespace lodforge::detail::clustering
