#pragma once
/// The marching-cube octree from a sign lattice: the surface points, the
/// leaves, the parents bottom-up, the holes of an open input, and the
/// priority numbering with its accumulation table (detail of
/// build_mc_octree; octree_builder.cpp builds, octree_numbering.cpp numbers).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "lodforge/core/progress.h"
#include "lodforge/core/quadric.h"
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/mc_octree.h"
#include "lodforge/mcoctree/sign_lattice.h"

namespace lodforge::detail {

/// How far a surface point is from the input: the distance, divided by the
/// rim gap fraction when the closest point is on an open rim (see
/// OctreeBuilder::mark_holes). {} for inputs without holes.
struct Gap {
  float gap = 0;
  bool rim = false;
};

/// attr(x, hint, near, normal, colour) sets the normal (and, when `colour` is
/// not null, the colour) of the surface point x and returns how far x is from
/// the input. `hint` is the calling thread's scratch (kNone at the start of
/// each run of nearby points), `near` the triangles closest to the ends of
/// x's lattice edge (or kNone); `normal` holds a fallback on entry. Called
/// from several threads at once.
using EdgePointAttributes =
    std::function<Gap(const Vec3& x, std::uint32_t& hint, const std::array<std::uint32_t, 2>& near,
                      Vec3& normal, Rgb8* colour)>;

/// Node by (level, coordinates), or a count by configuration: open
/// addressing, linear probing (std::unordered_map's chained buckets are
/// several times slower for the numbering's look-ups). Holds at most half
/// its capacity.
class NodeIndex {
 public:
  void reserve(std::size_t n) {
    std::size_t size = 16;
    shift_ = 60;
    while (size < 2 * n) size *= 2, --shift_;
    keys_.assign(size, kEmpty);
    values_.assign(size, McNode::kNone);
    mask_ = size - 1;
    size_ = 0;
  }
  void insert(std::uint64_t key, std::uint32_t value) {
    std::size_t i = slot(key);
    while (keys_[i] != kEmpty) i = (i + 1) & mask_;
    keys_[i] = key, values_[i] = value;
    ++size_;
  }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return keys_.size(); }
  std::uint32_t find(std::uint64_t key) const {
    for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == kEmpty) return McNode::kNone;
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t slot(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift_);
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t mask_ = 0, size_ = 0;
  int shift_ = 60;
};

/// Fills an McOctree in three steps: build_tree, then (open inputs)
/// mark_holes, then number. Each step's result depends neither on the
/// threads nor on how TBB splits the work.
class OctreeBuilder {
 public:
  OctreeBuilder(McOctree& t, McBuildStats& stats, bool place_coarse,
                const ProgressCallback& progress)
      : t_(t), stats_(stats), place_coarse_(place_coarse), progress_(progress) {}

  /// The tree of `lat`: a vertex per crossed lattice edge (its attributes
  /// from `attr`), leaves for the finest cells with a crossing, parents
  /// bottom-up by the four-case corner rule; with place_coarse, the coarse
  /// levels' own vertices. Throws DataError when no lattice edge is crossed.
  /// Reports "tree" (nodes made) to the progress callback.
  void build_tree(const Lattice& lat, bool colored, const EdgePointAttributes& attr);
  /// Clears the signs of the nodes over the input's holes; gap_at(x) is how
  /// far the point x is from the input (Gap::gap). After build_tree.
  void mark_holes(const std::function<float(const Vec3&)>& gap_at);
  /// The priority numbering by `which`, the LOD array, the accumulation
  /// table and the split priorities. After build_tree (and mark_holes).
  /// Reports "priorities" (expansions) to the progress callback.
  void number(McPriorityMetric which);

 private:
  // build_tree's steps (octree_builder.cpp).
  void place_edge_points(const Lattice& lat, const std::vector<std::int64_t>& edge_keys,
                         bool colored, const EdgePointAttributes& attr);
  void make_nodes(const Lattice& lat, const std::vector<std::int64_t>& edge_keys);
  void make_leaves(const Lattice& lat, const std::vector<std::int64_t>& edge_keys);
  void make_parents();
  void surface_quadrics(int D);
  void level_vertices(int l);
  void make_parent(McNode& node);

  // number's steps (octree_numbering.cpp).
  void make_near();
  std::uint32_t near(std::uint32_t i, int dx, int dy, int dz) const {
    if (i >= internal_) return McNode::kNone;
    return near_[27 * static_cast<std::size_t>(i) + (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1)];
  }
  std::pair<std::uint16_t, std::uint8_t> context(std::uint32_t i) const;
  int count_now(std::uint32_t i);
  double own_area(const McNode& n) const;
  std::uint32_t blocker(std::uint32_t i) const;
  std::vector<float> area_metric() const;
  std::vector<float> distance_metric() const;
  void expand_all(std::vector<float>& metric);
  void split_priorities();

  static std::uint64_t coord_key(int level, std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint64_t>(x) | static_cast<std::uint64_t>(y) << 20 |
           static_cast<std::uint64_t>(z) << 40 | static_cast<std::uint64_t>(level) << 60;
  }
  /// The node at (level, x, y, z), or kNone.
  std::uint32_t find(int level, std::int64_t x, std::int64_t y, std::int64_t z) const {
    std::int64_t size = std::int64_t{1} << level;
    if (x < 0 || y < 0 || z < 0 || x >= size || y >= size || z >= size) return McNode::kNone;
    return index_.find(coord_key(level, x, y, z));
  }
  std::uint32_t finest_of(std::uint32_t v) const {
    return v < finest_count_ ? v : finest_[v - finest_count_];
  }

  McOctree& t_;
  McBuildStats& stats_;
  bool place_coarse_;
  const ProgressCallback& progress_;
  std::vector<std::size_t>
      level_offset_;  // nodes [level_offset_[l], level_offset_[l + 1]) are level l's
  NodeIndex index_;
  std::vector<std::uint8_t> expanded_;
  NodeIndex counts_;  // see count_now
  std::vector<std::uint32_t> parent_;
  std::vector<Gap> gap_;               // per vertex
  std::vector<Quadric> node_q_;        // per internal node, while the tree is built
  std::size_t finest_count_ = 0;       // vertices [0, finest_count_) are finest crossings
  std::vector<std::uint32_t> finest_;  // per later (level) vertex: its finest crossing
  std::uint32_t internal_ = 0;         // nodes [0, internal_) are internal, the rest leaves
  std::vector<std::uint32_t> near_;    // 27 per internal node: its same-level neighbours
};

}  // namespace lodforge::detail
