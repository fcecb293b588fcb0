#include "lodforge/mcoctree/sign_lattice.h"

#include <gtest/gtest.h>

#include "lodforge/core/error.h"

namespace lodforge::detail {
namespace {

// 10 cells across a box 1 x 0.5 x 0.2: a root cube of 16 cells a side
// (the power of two above 10 + 2), the box and a cell to spare inside it.
TEST(EmptyLattice, HoldsTheBoxWithACellToSpare) {
  Box3 box;
  box.add(Vec3{0, 0, 0});
  box.add(Vec3{1, 0.5f, 0.2f});
  const Lattice lat = empty_lattice(box, 10);
  EXPECT_EQ(lat.depth, 4);
  EXPECT_FLOAT_EQ(lat.h, 0.1f);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(lat.origin[a], box.lo[a] - lat.h * 0.99f);
    EXPECT_GE(lat.origin[a] + static_cast<float>(lat.dim[a] - 1) * lat.h,
              box.hi[a] + lat.h * 0.99f);
  }
  EXPECT_EQ(lat.state.size(), static_cast<std::size_t>(lat.dim[0] * lat.dim[1] * lat.dim[2]));
  EXPECT_TRUE(lat.on_border(0));
  EXPECT_EQ(lat.coords(lat.index(1, 2, 3)), (std::array<std::int64_t, 3>{1, 2, 3}));
}

TEST(EmptyLattice, OnePointIsADataError) {
  Box3 box;
  box.add(Vec3{1, 2, 3});
  EXPECT_THROW(empty_lattice(box, 10), DataError);
}

// What the layers append comes back in layer order, whatever ran first.
TEST(CollectByLayer, KeepsLayerOrder) {
  const auto out = collect_by_layer(2, 40, [](std::int64_t k, std::vector<std::int64_t>& o) {
    for (int i = 0; i < k % 3; ++i) o.push_back(k);
  });
  EXPECT_TRUE(std::is_sorted(out.begin(), out.end()));
  EXPECT_EQ(out.size(), 38u);
}

}  // namespace
}  // namespace lodforge::detail
