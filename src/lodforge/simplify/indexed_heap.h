#pragma once
/// The priority queue of the simplifiers: a 4-ary min-heap, optionally
/// indexed (each entry's position is kept per id, so that an entry can be
/// re-keyed or erased in place).
///
/// A 4-ary heap has half the depth of a binary one, and a node's children lie
/// side by side in memory (four 16-byte entries span at most two cache lines).
/// A pop moves the hole down to a leaf along the smallest children and then
/// sifts the last entry up from there (Floyd's variant): the last entry
/// usually belongs near the bottom, which saves a comparison per level.
///
/// `Traits` describes the entries:
///   static bool before(const Entry& a, const Entry& b);  // strict weak order
///   static constexpr bool kIndexed;                        // keep positions?
///   static std::uint32_t id(const Entry& e);               // only if kIndexed
/// With an index, ids are in [0, ids) (see reset()) and each id is queued at
/// most once.
///
/// Determinism: the heap is a function of the sequence of calls, so the pop
/// order is the same on every run; when `before` is a total order, it is
/// also the order of the entries alone, whatever the sequence.
/// Complexity: push, pop, update and erase O(log n); make() O(n).
#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lodforge/core/math.h"

namespace lodforge::detail {

template <class Entry, class Traits>
class IndexedHeap {
 public:
  static constexpr bool kIndexed = Traits::kIndexed;

  bool empty() const { return v_.empty(); }
  std::size_t size() const { return v_.size(); }
  /// The smallest entry (the heap must not be empty).
  const Entry& top() const { return v_[0]; }
  void clear() {
    if constexpr (kIndexed)
      for (const Entry& e : v_) pos_[Traits::id(e)] = kNone;
    v_.clear();
  }

  /// Empties the heap and makes room for the ids [0, ids).
  void reset(std::size_t ids) requires kIndexed {
    v_.clear();
    pos_.assign(ids, kNone);
  }
  bool contains(std::uint32_t id) const requires kIndexed { return pos_[id] != kNone; }
  /// The entry queued for `id` (which must be queued).
  const Entry& entry(std::uint32_t id) const requires kIndexed { return v_[pos_[id]]; }
  /// Starts fetching what update() or erase() of `id` reads first.
  void prefetch(std::uint32_t id) const requires kIndexed { __builtin_prefetch(&pos_[id]); }
  /// Queues `e`, or re-keys the entry of its id if that is queued.
  void update(const Entry& e) requires kIndexed {
    const std::uint32_t i = pos_[Traits::id(e)];
    if (i == kNone) {
      push(e);
    } else if (Traits::before(e, v_[i])) {
      sift_up(i, e);
    } else {
      v_[i] = e;
      sift_down(i);
    }
  }
  /// Removes the entry of `id`, if queued.
  void erase(std::uint32_t id) requires kIndexed {
    const std::uint32_t i = pos_[id];
    if (i == kNone) return;
    pos_[id] = kNone;
    const Entry last = v_.back();
    v_.pop_back();
    if (i == v_.size()) return;
    if (i > 0 && Traits::before(last, v_[(i - 1) / 4])) {
      sift_up(i, last);
    } else {
      place(i, last);
      sift_down(i);
    }
  }

  /// Drops the entries for which `stale` holds and re-orders the rest.
  template <class Stale>
  void drop_if(Stale stale) requires(!kIndexed) {
    std::erase_if(v_, stale);
    make();
  }
  /// Becomes the entries of `from` (this heap must be empty); `from` is left
  /// empty, with this heap's old storage.
  void take(std::vector<Entry>& from) requires(!kIndexed) {
    assert(v_.empty());
    v_.swap(from);
    make();
  }
  /// Appends without ordering; call make() before the next push or pop.
  void append(const Entry& e) requires(!kIndexed) { v_.push_back(e); }
  /// Restores the heap order after append(), O(n).
  void make() {
    if (v_.size() < 2) return;
    for (std::size_t i = (v_.size() - 2) / 4 + 1; i-- > 0;) sift_down(i);
  }

  /// Queues `e` (with an index: its id must not be queued).
  void push(const Entry& e) {
    if constexpr (kIndexed) assert(!contains(Traits::id(e)));
    v_.push_back(e);
    sift_up(v_.size() - 1, e);
  }
  /// Removes and returns the smallest entry (the heap must not be empty).
  Entry pop() {
    const Entry top = v_[0];
    if constexpr (kIndexed) pos_[Traits::id(top)] = kNone;
    const Entry last = v_.back();
    v_.pop_back();
    const std::size_t n = v_.size();
    if (n == 0) return top;
    std::size_t i = 0;
    Entry* h = v_.data();
    // Full families first, the smallest of four chosen by arithmetic: which
    // child is smallest depends on the data, so branches would mispredict.
    for (std::size_t c = 1; c + 4 <= n; c = 4 * i + 1) {
      const std::size_t b01 = c + std::size_t{Traits::before(h[c + 1], h[c])};
      const std::size_t b23 = c + 2 + std::size_t{Traits::before(h[c + 3], h[c + 2])};
      const std::size_t best = b01 + (b23 - b01) * std::size_t{Traits::before(h[b23], h[b01])};
      place(i, h[best]);
      i = best;
    }
    if (std::size_t c = 4 * i + 1; c < n) {
      std::size_t best = c;
      for (std::size_t j = c + 1; j < n; ++j)
        if (Traits::before(h[j], h[best])) best = j;
      place(i, h[best]);
      i = best;
    }
    sift_up(i, last);
    return top;
  }

 private:
  void place(std::size_t i, const Entry& e) {
    v_[i] = e;
    if constexpr (kIndexed) pos_[Traits::id(e)] = static_cast<std::uint32_t>(i);
  }
  /// Moves `x` from the hole at i up to its place.
  void sift_up(std::size_t i, const Entry& x) {
    while (i > 0) {
      const std::size_t p = (i - 1) / 4;
      if (!Traits::before(x, v_[p])) break;
      place(i, v_[p]);
      i = p;
    }
    place(i, x);
  }
  /// Moves the entry at i down to its place.
  void sift_down(std::size_t i) {
    const Entry x = v_[i];
    const std::size_t n = v_.size();
    for (;;) {
      const std::size_t c = 4 * i + 1;
      if (c >= n) break;
      const std::size_t end = std::min(c + 4, n);
      std::size_t best = c;
      for (std::size_t j = c + 1; j < end; ++j)
        if (Traits::before(v_[j], v_[best])) best = j;
      if (!Traits::before(v_[best], x)) break;
      place(i, v_[best]);
      i = best;
    }
    place(i, x);
  }

  std::vector<Entry> v_;
  std::vector<std::uint32_t> pos_;  // with an index: position in v_ per id, kNone if not queued
};

}  // namespace lodforge::detail
