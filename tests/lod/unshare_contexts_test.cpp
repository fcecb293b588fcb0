#include "lodforge/lod/unshare_contexts.h"

#include <gtest/gtest.h>

#include "lodforge/io/vrml1/read_vrml1.h"

namespace lodforge {
namespace {

bool is_face_set(const scene::Node& n) {
  return n.type == "IndexedFaceSet";
}

// The place of every IndexedFaceSet drawn, and the context it is drawn in.
std::vector<std::pair<const scene::Node*, PropertyContext>> uses(const scene::Scene& s) {
  std::vector<std::pair<const scene::Node*, PropertyContext>> out;
  scene::traverse(s, [&](const scene::ShapeVisit& v) {
    if (is_face_set(v.shape)) out.emplace_back(&v.shape, PropertyContext::of(v.state));
  });
  return out;
}

constexpr const char* kTwoContexts = R"(#VRML V1.0 ascii
Separator {
  Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] }
  DEF G Separator { IndexedFaceSet { coordIndex [0, 1, 2, -1] } }
  Coordinate3 { point [0 0 0, 2 0 0, 0 2 0] }
  USE G
  USE G
})";

TEST(UnsharePropertyContexts, EachFurtherContextGetsItsOwnCopy) {
  scene::Scene s = vrml1::read_vrml1(kTwoContexts).scene;
  auto before = uses(s);
  ASSERT_EQ(before.size(), 3u);
  EXPECT_EQ(before[0].first, before[1].first);  // one node in two contexts
  EXPECT_EQ(unshare_property_contexts(s, is_face_set), 1u);
  auto after = uses(s);
  ASSERT_EQ(after.size(), 3u);
  EXPECT_NE(after[0].first, after[1].first);
  // The two uses in the second context share the one copy.
  EXPECT_EQ(after[1].first, after[2].first);
  // What is drawn is unchanged: the same contexts, in the same order.
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(after[i].second.coordinate3, before[i].second.coordinate3);
}

TEST(UnsharePropertyContexts, SharingInOneContextIsKept) {
  scene::Scene s = vrml1::read_vrml1(R"(#VRML V1.0 ascii
Separator {
  Coordinate3 { point [0 0 0, 1 0 0, 0 1 0] }
  DEF G Separator { IndexedFaceSet { coordIndex [0, 1, 2, -1] } }
  Translation { translation 3 0 0 }
  USE G
})")
                       .scene;
  EXPECT_EQ(unshare_property_contexts(s, is_face_set), 0u);
  auto after = uses(s);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0].first, after[1].first);
}

TEST(UnsharePropertyContexts, ShapesTheCallerDoesNotAskForAreLeftShared) {
  scene::Scene s = vrml1::read_vrml1(kTwoContexts).scene;
  EXPECT_EQ(unshare_property_contexts(s, [](const scene::Node&) { return false; }), 0u);
  auto after = uses(s);
  EXPECT_EQ(after[0].first, after[1].first);
}

}  // namespace
}  // namespace lodforge
