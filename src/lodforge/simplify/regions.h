#pragma once
/// Shared by the simplifiers whose main loop is one priority queue (quadric
/// collapse, vertex decimation): the regional first phase of a large
/// reduction. The mesh is cut into a few kd regions; each region works on the
/// vertices it owns (all their triangles lie in it) with its own queue, on
/// TBB's threads, while the vertices on the cuts (seams) wait; the regions
/// advance together in rounds up to a common priority limit, so that the
/// order stays close to one queue's; then the whole mesh goes on from one
/// queue. The regions and rounds depend on the mesh and target only, so the
/// result does not depend on the thread count.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/parallel_for.h>

namespace lodforge::regions {

/// The phase runs from this many triangles on ...
inline constexpr std::size_t kMinTriangles = 32768;
/// ... in regions of about this many triangles, at most kMaxParts (every cut
/// leaves a seam that waits for the second phase, so more regions cost
/// quality).
inline constexpr std::size_t kTrianglesPerPart = 16384;
inline constexpr int kMaxParts = 4;
/// Region id of a vertex that is on a seam.
inline constexpr std::uint8_t kSeam = 0xff;

/// How many regions for `triangles` live triangles (a power of two, >= 2).
int part_count(std::size_t triangles);

/// Where the first phase stops for `target` of `live` triangles: at `slack`
/// times the target, but leaving at least a tenth of the collapses to the
/// second phase.
inline std::size_t goal(std::size_t target, std::size_t live, std::size_t slack = 2) {
  const std::size_t rest = target + (live - target) / 10;
  return slack * target < rest ? slack * target : rest;
}

/// Whether the phase runs for a reduction of `live` triangles to `target`:
/// from kMinTriangles on, when it removes at least a quarter of them (with
/// the default slack: when the target keeps at most 72 %).
inline bool worthwhile(std::size_t target, std::size_t live, std::size_t slack = 2) {
  return live >= kMinTriangles && target < live && 4 * goal(target, live, slack) <= 3 * live;
}

/// Cuts the triangles with use[t] != 0 into `parts` (a power of two, <= 64)
/// regions of about equal count by a kd-tree on their centroids `centre`
/// (3 floats per triangle): each cell is cut across its longest side at the
/// median, found with a histogram of 1024 bins. Returns the region of every
/// triangle (0 where use[t] == 0).
std::vector<std::uint8_t> kd_partition(const std::vector<float>& centre,
                                       const std::vector<std::uint8_t>& use, int parts);

/// The priority limit of the next round, in the bit patterns of non-negative
/// floats (which order like the floats), shifted left by `shift` bits (1 for
/// quadric collapse's keys, 0 for plain floats): x16 in priority while
/// `remaining` is above 8x `goal`, x4 above 2x, x2 near it; saturates at the
/// largest key.
std::uint32_t next_limit(std::uint32_t limit, std::size_t remaining, std::size_t goal, int shift);

/// The rounds of the phase. `lanes` are the regions' states, each with
/// `inner` (its triangles without a seam corner) and `done`; `limit` starts
/// at the smallest queued priority (as a key, see next_limit). While the
/// inner triangles add up to more than `goal` and some region is not done,
/// the limit grows and `step(lane, limit)` runs for every region not done,
/// side by side on TBB's threads; it works up to the limit and returns
/// whether the region is done.
template <class Lane, class Step>
void run_rounds(std::vector<std::unique_ptr<Lane>>& lanes, std::size_t goal, std::uint32_t limit,
                int shift, Step step) {
  for (;;) {
    std::size_t remaining = 0;
    bool all_done = true;
    for (auto& lane : lanes) {
      remaining += lane->inner;
      all_done &= lane->done;
    }
    if (remaining <= goal || all_done || limit == 0xffffffffu) return;
    limit = next_limit(limit, remaining, goal, shift);
    tbb::parallel_for(std::size_t{0}, lanes.size(), [&](std::size_t r) {
      if (!lanes[r]->done) lanes[r]->done = step(*lanes[r], limit);
    });
  }
}

}  // namespace lodforge::regions
