// VRML 1.0 attribute bindings: which binding a node asks for, and which
// value each corner of a face set takes under it.
#include "lodforge/scene/attribute_binding.h"

#include <gtest/gtest.h>

#include <vector>

namespace lodforge::scene {
namespace {

NodePtr binding_node(const char* value) {
  NodePtr n = make_node("MaterialBinding");
  n->set("value", make_enum(value));
  return n;
}

TEST(AttributeBinding, BindingOfEachValueAndTheDefault) {
  EXPECT_EQ(binding_of(nullptr, Binding::kPerVertexIndexed), Binding::kPerVertexIndexed);
  EXPECT_EQ(binding_of(binding_node("OVERALL").get(), Binding::kPerFace), Binding::kOverall);
  EXPECT_EQ(binding_of(binding_node("PER_PART").get(), Binding::kOverall), Binding::kPerFace);
  EXPECT_EQ(binding_of(binding_node("PER_FACE").get(), Binding::kOverall), Binding::kPerFace);
  EXPECT_EQ(binding_of(binding_node("PER_PART_INDEXED").get(), Binding::kOverall),
            Binding::kPerFaceIndexed);
  EXPECT_EQ(binding_of(binding_node("PER_FACE_INDEXED").get(), Binding::kOverall),
            Binding::kPerFaceIndexed);
  EXPECT_EQ(binding_of(binding_node("PER_VERTEX").get(), Binding::kOverall), Binding::kPerVertex);
  EXPECT_EQ(binding_of(binding_node("PER_VERTEX_INDEXED").get(), Binding::kOverall),
            Binding::kPerVertexIndexed);
  // DEFAULT and an unknown value: the caller's default.
  EXPECT_EQ(binding_of(binding_node("DEFAULT").get(), Binding::kPerFace), Binding::kPerFace);
  EXPECT_EQ(binding_of(binding_node("SIDEWAYS").get(), Binding::kOverall), Binding::kOverall);
  EXPECT_TRUE(is_per_vertex(Binding::kPerVertex));
  EXPECT_TRUE(is_per_vertex(Binding::kPerVertexIndexed));
  EXPECT_FALSE(is_per_vertex(Binding::kPerFaceIndexed));
}

TEST(AttributeBinding, IndexerFollowsTheTableAndMarksShortIndexFields) {
  const std::vector<std::int32_t> ci{3, 4, 5, -1, 6, 7, 8, -1};
  const std::vector<std::int32_t> per_face{9, 8};
  const std::vector<std::int32_t> per_vertex{1, 2, 3, -1, 4};
  // Face 1, its corner 1 (corner 4 of the shape), at coordIndex position 5.
  auto at = [&](Binding b, const std::vector<std::int32_t>* index) {
    return AttributeIndexer{b, index, &ci}.at(1, 4, 5);
  };
  EXPECT_EQ(at(Binding::kOverall, &per_face), -1);
  EXPECT_EQ(at(Binding::kPerFace, nullptr), 1);
  EXPECT_EQ(at(Binding::kPerFaceIndexed, &per_face), 8);
  EXPECT_EQ(at(Binding::kPerVertex, nullptr), 4);
  EXPECT_EQ(at(Binding::kPerVertexIndexed, &ci), 7);
  // Too short an index field: -2.
  EXPECT_EQ(at(Binding::kPerVertexIndexed, &per_vertex), -2);
  const std::vector<std::int32_t> one{5};
  EXPECT_EQ(at(Binding::kPerFaceIndexed, &one), -2);
  EXPECT_EQ(at(Binding::kPerFaceIndexed, nullptr), -2);
  // [] and [-1] are the default index field: coordIndex is read instead.
  const std::vector<std::int32_t> empty, minus_one{-1};
  EXPECT_EQ(at(Binding::kPerVertexIndexed, &empty), 7);
  EXPECT_EQ(at(Binding::kPerVertexIndexed, &minus_one), 7);
  EXPECT_TRUE((AttributeIndexer{Binding::kPerVertexIndexed, &minus_one, &ci}.index_is_default()));
  EXPECT_FALSE((AttributeIndexer{Binding::kPerVertexIndexed, &one, &ci}.index_is_default()));
}

}  // namespace
}  // namespace lodforge::scene
