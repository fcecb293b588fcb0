// The simplifiers' priority queue, plain and indexed, against sorting.
#include "lodforge/simplify/indexed_heap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace lodforge {
namespace {

struct Keyed {
  std::uint32_t key;
  std::uint32_t payload;
};
struct KeyedTraits {
  static constexpr bool kIndexed = false;
  static bool before(const Keyed& a, const Keyed& b) { return a.key < b.key; }
};
using PlainHeap = detail::IndexedHeap<Keyed, KeyedTraits>;

struct Item {
  float d;
  std::uint32_t id;
};
struct ItemTraits {
  static constexpr bool kIndexed = true;
  static bool before(const Item& a, const Item& b) { return a.d != b.d ? a.d < b.d : a.id < b.id; }
  static std::uint32_t id(const Item& e) { return e.id; }
};
using ItemHeap = detail::IndexedHeap<Item, ItemTraits>;

std::vector<std::uint32_t> drain_keys(PlainHeap& heap) {
  std::vector<std::uint32_t> keys;
  while (!heap.empty()) keys.push_back(heap.pop().key);
  return keys;
}

TEST(IndexedHeap, PopsInKeyOrderWithTiesAndAllFamilySizes) {
  // Sizes 0..40 cover every shape of the last family of a 4-ary heap.
  std::mt19937 rng(7);
  for (std::uint32_t n = 0; n <= 40; ++n) {
    PlainHeap heap;
    std::vector<std::uint32_t> keys;
    for (std::uint32_t i = 0; i < n; ++i) {
      keys.push_back(rng() % 8);  // many ties
      heap.push({keys.back(), i});
    }
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(drain_keys(heap), keys) << n << " entries";
  }
}

TEST(IndexedHeap, AppendThenMakeEqualsPushes) {
  std::mt19937 rng(11);
  PlainHeap appended;
  std::vector<std::uint32_t> keys;
  for (int i = 0; i < 1000; ++i) {
    keys.push_back(rng() % 100000);
    appended.append({keys.back(), 0});
  }
  appended.make();
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(drain_keys(appended), keys);
}

TEST(IndexedHeap, TakeAndDropIf) {
  std::vector<Keyed> from;
  for (std::uint32_t i = 0; i < 50; ++i) from.push_back({50 - i, i});
  PlainHeap heap;
  heap.take(from);
  EXPECT_TRUE(from.empty());
  EXPECT_EQ(heap.size(), 50u);
  heap.drop_if([](const Keyed& e) { return e.key % 2 == 1; });  // drop the odd keys
  EXPECT_EQ(heap.size(), 25u);
  std::vector<std::uint32_t> expected;
  for (std::uint32_t k = 2; k <= 50; k += 2) expected.push_back(k);
  EXPECT_EQ(drain_keys(heap), expected);
}

TEST(IndexedHeap, IndexedUpdateEraseAndPopKeepTheOrder) {
  // Random updates (up and down), erasures and pops, against a plain array.
  std::mt19937 rng(3);
  constexpr std::uint32_t kIds = 300;
  ItemHeap heap;
  heap.reset(kIds);
  std::vector<float> queued(kIds, -1.0f);  // -1: not queued
  for (int step = 0; step < 20000; ++step) {
    const std::uint32_t id = rng() % kIds;
    const int op = static_cast<int>(rng() % 4);
    if (op < 2) {
      const float d = static_cast<float>(rng() % 50);  // ties, broken by id
      heap.update({d, id});
      queued[id] = d;
    } else if (op == 2) {
      heap.erase(id);
      queued[id] = -1.0f;
    } else if (!heap.empty()) {
      // The smallest (d, id) queued.
      std::uint32_t best = kIds;
      for (std::uint32_t i = 0; i < kIds; ++i)
        if (queued[i] >= 0 && (best == kIds || queued[i] < queued[best])) best = i;
      const Item top = heap.pop();
      ASSERT_EQ(top.id, best);
      ASSERT_EQ(top.d, queued[best]);
      queued[best] = -1.0f;
    }
    ASSERT_EQ(heap.contains(id), queued[id] >= 0);
    if (queued[id] >= 0) ASSERT_EQ(heap.entry(id).d, queued[id]);
  }
  std::size_t left = 0;
  for (float d : queued) left += d >= 0;
  EXPECT_EQ(heap.size(), left);
}

TEST(IndexedHeap, ResetForgetsEverything) {
  ItemHeap heap;
  heap.reset(4);
  heap.update({1.0f, 2});
  heap.reset(4);
  EXPECT_TRUE(heap.empty());
  EXPECT_FALSE(heap.contains(2));
}

}  // namespace
}  // namespace lodforge
