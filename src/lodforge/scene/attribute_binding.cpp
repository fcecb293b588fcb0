#include "lodforge/scene/attribute_binding.h"

#include <string>

#include "lodforge/scene/schema.h"

namespace lodforge::scene {

Binding binding_of(const Node* binding_node, Binding default_binding) {
  if (!binding_node) return default_binding;
  const FieldValue* v = field_or_default(*binding_node, "value");
  const std::string s = !v || v->strings.empty() ? std::string("DEFAULT") : v->strings[0];
  if (s == "OVERALL") return Binding::kOverall;
  if (s == "PER_PART" || s == "PER_FACE") return Binding::kPerFace;
  if (s == "PER_PART_INDEXED" || s == "PER_FACE_INDEXED") return Binding::kPerFaceIndexed;
  if (s == "PER_VERTEX") return Binding::kPerVertex;
  if (s == "PER_VERTEX_INDEXED") return Binding::kPerVertexIndexed;
  return default_binding;
}

std::int64_t AttributeIndexer::at(std::size_t face, std::size_t corner_seq, std::size_t pos) const {
  switch (bind) {
    case Binding::kOverall:
      return -1;
    case Binding::kPerFace:
      return std::int64_t(face);
    case Binding::kPerFaceIndexed:
      return index && face < index->size() ? (*index)[face] : std::int64_t(-2);
    case Binding::kPerVertex:
      return std::int64_t(corner_seq);
    case Binding::kPerVertexIndexed: {
      const std::vector<std::int32_t>* idx = index_is_default() ? coord_index : index;
      return idx && pos < idx->size() ? (*idx)[pos] : std::int64_t(-2);
    }
  }
  return -1;
}

bool AttributeIndexer::index_is_default() const {
  return !index || index->empty() || (index->size() == 1 && (*index)[0] == -1);
}

}  // namespace lodforge::scene
