#pragma once
/// The attribute bindings of VRML 1.0 (MaterialBinding, NormalBinding) on an
/// IndexedFaceSet or IndexedLineSet: which value of an attribute list each
/// corner of each face takes.
///
///  | binding                    | value of corner c of face f (position p in coordIndex)   |
///  |----------------------------|-----------------------------------------------------------|
///  | DEFAULT, OVERALL           | none (value 0 for the whole shape)                        |
///  | PER_PART, PER_FACE         | f-th value                                                |
///  | *_PART/FACE_INDEXED        | index[f]                                                  |
///  | PER_VERTEX                 | c-th value counting all corners of the shape in order     |
///  | PER_VERTEX_INDEXED         | index[p], or coordIndex[p] if the index field is [-1]     |
///
/// PER_PART is per face on an IndexedFaceSet (the specification's parts of a
/// face set are its faces) and per polyline on an IndexedLineSet.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lodforge/scene/node.h"

namespace lodforge::scene {

enum class Binding { kOverall, kPerFace, kPerFaceIndexed, kPerVertex, kPerVertexIndexed };

/// The binding a MaterialBinding or NormalBinding node asks for;
/// `default_binding` for nullptr, DEFAULT and values it does not know.
Binding binding_of(const Node* binding_node, Binding default_binding);

/// True for the two per-vertex bindings.
inline bool is_per_vertex(Binding b) {
  return b == Binding::kPerVertex || b == Binding::kPerVertexIndexed;
}

/// The attribute index of a corner under a binding, before range checking.
struct AttributeIndexer {
  Binding bind = Binding::kOverall;
  const std::vector<std::int32_t>* index = nullptr;  ///< materialIndex / normalIndex / ...
  const std::vector<std::int32_t>* coord_index = nullptr;

  /// Corner `corner_seq` (counted over the whole shape) of face `face`, at
  /// position `pos` of coordIndex: the value's index; -1 under OVERALL; -2
  /// when the index field is too short.
  std::int64_t at(std::size_t face, std::size_t corner_seq, std::size_t pos) const;
  /// True when the index field is left at its default ([] or [-1]), so
  /// PER_VERTEX_INDEXED reads coordIndex.
  bool index_is_default() const;
};

}  // namespace lodforge::scene
