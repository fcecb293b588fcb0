#pragma once
/// The collapse queue of quadric_collapse: queued edge collapses with lazy
/// deletion, in a bucket queue in front of a small exact heap. Internal to
/// simplify/ (quadric_collapse.cpp and its collapser_*.cpp parts).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "lodforge/simplify/indexed_heap.h"

namespace lodforge::detail::qem {

/// A queued collapse of edge {a, b}: 16 bytes, so that the four children of a
/// node of the 4-ary heap below span at most two cache lines. `key` orders
/// entries (see heap_key()). `stamp` is the sum of the versions of a and b
/// when it was pushed; versions only grow, so the sum is unchanged exactly
/// when neither end changed.
struct HeapEntry {
  std::uint32_t key;
  std::uint32_t a, b;
  std::uint32_t stamp;
};

/// The heap key of a cost: the bits of the float cost (non-negative floats
/// order like their bit patterns, and their sign bit is free), shifted up to
/// make room for the deferred flag, so that a deferred sliver goes after an
/// ordinary collapse of the same cost.
inline std::uint32_t heap_key(double cost, bool deferred) {
  float f = static_cast<float>(cost);
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u << 1 | std::uint32_t{deferred};
}
inline bool is_deferred(const HeapEntry& e) {
  return (e.key & 1) != 0;
}

struct HeapEntryTraits {
  static constexpr bool kIndexed = false;
  static bool before(const HeapEntry& a, const HeapEntry& b) { return a.key < b.key; }
};
/// Min-heap of HeapEntry by (cost, deferred last). Entries are deleted lazily
/// (see Collapser::drain), so pops dominate.
using EdgeHeap = IndexedHeap<HeapEntry, HeapEntryTraits>;

/// The queue of collapses: a bucket queue in front of a small exact heap.
/// Keys are bucketed by their top bits (the float exponent and a few mantissa
/// bits, so a bucket spans a few percent of cost); a push beyond the current
/// bucket is an append, and only the current bucket is kept in heap order,
/// so the heap holds a few hundred entries instead of all of them and stale
/// entries (see Collapser::drain) cost an append and a pop in that small heap. The order
/// stays exact: a push into the current bucket or below goes into the heap.
class CollapseQueue {
 public:
  /// `shift`: key bits below the bucket index (18 for a whole mesh; the
  /// small queues of the regions use fewer, wider buckets).
  explicit CollapseQueue(int shift = 18)
      : shift_(shift), buckets_(std::size_t{1} << (32 - shift)), used_(buckets_.size() / 64) {}
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  void clear() {
    for (std::size_t w = 0; w < used_.size(); ++w)
      for (std::uint64_t bits = used_[w]; bits != 0; bits &= bits - 1)
        buckets_[64 * w + static_cast<std::size_t>(std::countr_zero(bits))].clear();
    std::fill(used_.begin(), used_.end(), 0);
    heap_.clear();
    current_ = 0;
    size_ = 0;
  }
  void push(const HeapEntry& e) {
    ++size_;
    std::size_t b = e.key >> shift_;
    if (b <= current_) {
      heap_.push(e);
    } else {
      buckets_[b].push_back(e);
      used_[b / 64] |= std::uint64_t{1} << (b % 64);
    }
  }
  /// Removes the smallest entry into `out`; false if there is none or its key
  /// is above `limit` (then it stays). Entries
  /// for which `stale` holds are dropped in bulk when their bucket becomes
  /// the heap (most entries are stale by then: they were pushed long before
  /// their cost came up, and their vertices changed since), so they cost a
  /// scan instead of a pop.
  template <class Stale>
  bool pop(HeapEntry& out, Stale stale, std::uint32_t limit = 0xffffffffu) {
    while (heap_.empty()) {
      if (size_ == 0) return false;
      // The next bucket in use becomes the heap.
      std::size_t w = (current_ + 1) / 64;
      std::uint64_t bits = used_[w] & (~std::uint64_t{0} << ((current_ + 1) % 64));
      while (bits == 0) bits = used_[++w];
      const std::size_t next = 64 * w + static_cast<std::size_t>(std::countr_zero(bits));
      if (next > limit >> shift_) return false;
      current_ = next;
      used_[w] &= ~(std::uint64_t{1} << (current_ % 64));
      std::vector<HeapEntry>& bucket = buckets_[current_];
      const std::size_t before = bucket.size();
      std::erase_if(bucket, stale);
      size_ -= before - bucket.size();
      heap_.take(bucket);
    }
    if (heap_.top().key > limit) return false;
    --size_;
    out = heap_.pop();
    return true;
  }
  /// The next entry of the current bucket, if any (for prefetching).
  const HeapEntry* peek() const { return heap_.empty() ? nullptr : &heap_.top(); }
  /// Drops the entries for which `stale` holds.
  template <class Stale>
  void drop_if(Stale stale) {
    heap_.drop_if(stale);
    size_ = heap_.size();
    for (std::size_t w = 0; w < used_.size(); ++w)
      for (std::uint64_t bits = used_[w]; bits != 0; bits &= bits - 1) {
        std::size_t b = 64 * w + static_cast<std::size_t>(std::countr_zero(bits));
        std::erase_if(buckets_[b], stale);
        size_ += buckets_[b].size();
        if (buckets_[b].empty()) used_[w] &= ~(std::uint64_t{1} << (b % 64));
      }
  }

 private:
  int shift_;
  std::vector<std::vector<HeapEntry>> buckets_;
  std::vector<std::uint64_t> used_;  // bit b: bucket b is not empty
  EdgeHeap heap_;                    // the current bucket and anything below it
  std::size_t current_ = 0;
  std::size_t size_ = 0;
};

}  // namespace lodforge::detail::qem
