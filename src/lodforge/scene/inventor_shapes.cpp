// Inventor's non-VRML vertex shapes as indexed sets (see inventor_shapes.h).
#include "lodforge/scene/inventor_shapes.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>

#include "lodforge/core/error.h"
#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

// A field's values, or none when the node's type has no such field.
const std::vector<std::int32_t>& ints_of(const Node& node, std::string_view field) {
  static const std::vector<std::int32_t> kNone;
  const FieldValue* v = field_or_default(node, field);
  return v ? v->ints : kNone;
}

const std::vector<float>& floats_of(const Node& node, std::string_view field) {
  static const std::vector<float> kNone;
  const FieldValue* v = field_or_default(node, field);
  return v ? v->floats : kNone;
}

constexpr std::array<std::string_view, 5> kTypes = {
    "FaceSet", "TriangleStripSet", "IndexedTriangleStripSet", "QuadMesh", "LineSet"};

// What a binding node asks of an Inventor vertex shape.
enum class Per { kOverall, kPart, kFace, kVertex };

Per per_of(const Node* binding, Per fallback, bool& indexed) {
  indexed = false;
  if (!binding) return fallback;
  const FieldValue* v = field_or_default(*binding, "value");
  const std::string s = v && !v->strings.empty() ? v->strings[0] : "DEFAULT";
  indexed = s.ends_with("_INDEXED");
  if (s == "OVERALL") return Per::kOverall;
  if (s.starts_with("PER_PART")) return Per::kPart;
  if (s.starts_with("PER_FACE")) return Per::kFace;
  if (s.starts_with("PER_VERTEX")) return Per::kVertex;
  return fallback;
}

struct Corner {
  std::int32_t coord;  // coordinate index
  std::int32_t seq;    // the shape's vertex number, from 0
  std::int64_t pos;    // position in the input's coordIndex (indexed strips), else -1
};

struct Face {
  std::vector<Corner> corners;
  std::int32_t part = 0;
  std::int32_t face = 0;
};

// The index list of an indexed input field at `i`, or a value out of any
// range when the list is too short (the reader of the result reports it).
std::int32_t at(const std::vector<std::int32_t>& v, std::int64_t i) {
  return i >= 0 && std::size_t(i) < v.size() ? v[std::size_t(i)]
                                             : std::numeric_limits<std::int32_t>::max();
}

bool is_default_index(const std::vector<std::int32_t>& v) {
  return v.empty() || (v.size() == 1 && v[0] == -1);
}

class Converter {
 public:
  explicit Converter(const ShapeVisit& visit) : shape_(visit.shape), state_(visit.state) {
    static const Node kDefaultCoords{.type = "Coordinate3"};
    const Node& c = state_.coordinate3 ? *state_.coordinate3 : kDefaultCoords;
    coords_ = std::int64_t(floats_of(c, "point").size() / 3);
  }

  IndexedEquivalent run() {
    const std::string& t = shape_.type;
    if (t == "FaceSet" || t == "LineSet")
      runs();
    else if (t == "TriangleStripSet")
      strips();
    else if (t == "IndexedTriangleStripSet")
      indexed_strips();
    else if (t == "QuadMesh")
      quad_mesh();
    return build();
  }

 private:
  std::int32_t long_field(std::string_view f) const {
    const FieldValue* v = field_or_default(shape_, f);
    return v && !v->ints.empty() ? v->ints[0] : 0;
  }

  // Coordinates [first, first + count) must exist.
  void need(std::int64_t first, std::int64_t count) const {
    if (first < 0 || first + count > coords_)
      throw DataError(
          fmt::format("line {}: {} uses coordinates {}..{}, but the current coordinates have {}",
                      shape_.first_line, shape_.type, first, first + count - 1, coords_));
  }

  // numVertices: one count per part; -1 takes all coordinates that are left.
  std::vector<std::int64_t> counts(std::int64_t start) const {
    std::vector<std::int64_t> out;
    std::int64_t used = 0;
    for (std::int32_t n : ints_of(shape_, "numVertices")) {
      std::int64_t k = n < 0 ? std::max<std::int64_t>(0, coords_ - start - used) : n;
      out.push_back(k);
      used += k;
    }
    need(start, used);
    return out;
  }

  void runs() {
    const std::int64_t start = long_field("startIndex");
    std::int64_t next = start;
    std::int32_t seq = 0, part = 0;
    for (std::int64_t n : counts(start)) {
      Face f;
      f.part = f.face = part++;
      for (std::int64_t i = 0; i < n; ++i) f.corners.push_back({std::int32_t(next++), seq++, -1});
      faces_.push_back(std::move(f));
    }
  }

  // The triangles of one strip of corners.
  void strip(const std::vector<Corner>& v, std::int32_t part) {
    for (std::size_t i = 0; i + 2 < v.size(); ++i) {
      Face f;
      f.part = part;
      f.face = triangle_++;
      if (i % 2 == 0)
        f.corners = {v[i], v[i + 1], v[i + 2]};
      else
        f.corners = {v[i + 1], v[i], v[i + 2]};
      faces_.push_back(std::move(f));
    }
  }

  void strips() {
    const std::int64_t start = long_field("startIndex");
    std::int64_t next = start;
    std::int32_t seq = 0, part = 0;
    for (std::int64_t n : counts(start)) {
      std::vector<Corner> v;
      for (std::int64_t i = 0; i < n; ++i) v.push_back({std::int32_t(next++), seq++, -1});
      strip(v, part++);
    }
  }

  void indexed_strips() {
    const std::vector<std::int32_t>& ci = ints_of(shape_, "coordIndex");
    std::vector<Corner> v;
    std::int32_t seq = 0, part = 0;
    auto flush = [&] {
      if (!v.empty()) strip(v, part++);
      v.clear();
    };
    for (std::size_t p = 0; p < ci.size(); ++p) {
      if (ci[p] < 0) {
        flush();
        continue;
      }
      if (ci[p] >= coords_)
        throw DataError(fmt::format(
            "line {}: {} coordIndex[{}] = {} is out of range (the current coordinates have {})",
            shape_.first_line, shape_.type, p, ci[p], coords_));
      v.push_back({ci[p], seq++, std::int64_t(p)});
    }
    flush();
  }

  void quad_mesh() {
    const std::int64_t start = long_field("startIndex");
    const std::int64_t row = std::max(0, long_field("verticesPerRow"));
    const std::int64_t rows = std::max(0, long_field("verticesPerColumn"));
    if (row < 2 || rows < 2) return;
    need(start, row * rows);
    auto corner = [&](std::int64_t r, std::int64_t c) {
      const std::int32_t i = std::int32_t(r * row + c);
      return Corner{std::int32_t(start + i), i, -1};
    };
    std::int32_t face = 0;
    for (std::int64_t r = 0; r + 1 < rows; ++r)
      for (std::int64_t c = 0; c + 1 < row; ++c) {
        Face f;
        f.part = std::int32_t(r);
        f.face = face++;
        f.corners = {corner(r, c), corner(r, c + 1), corner(r + 1, c + 1), corner(r + 1, c)};
        faces_.push_back(std::move(f));
      }
  }

  NodePtr binding(const char* type, const char* value) {
    NodePtr n = make_node(type);
    n->first_line = shape_.first_line;
    n->set("value", make_enum(value));
    owned_.push_back(n);
    return n;
  }

  // The index list of one attribute (material or normal) and the binding node
  // that reads it; nullptr when the state's binding stays as it is.
  const Node* attribute(const Node* binding_node, Per fallback, const char* binding_type,
                        const char* index_field, Node& out) {
    bool indexed_binding = false;
    const Per per = per_of(binding_node, fallback, indexed_binding);
    if (per == Per::kOverall) return binding_node;
    const bool indexed_shape = shape_.type == "IndexedTriangleStripSet";
    const std::vector<std::int32_t>& given = ints_of(shape_, index_field);
    const std::vector<std::int32_t>& ci = ints_of(shape_, "coordIndex");
    // An indexed shape under an *_INDEXED binding reads its index field.
    const bool reads_index = indexed_shape && indexed_binding;
    std::vector<std::int32_t> idx;
    if (per == Per::kVertex) {
      for (const Face& f : faces_) {
        for (const Corner& c : f.corners)
          idx.push_back(!reads_index              ? c.seq
                        : is_default_index(given) ? at(ci, c.pos)
                                                  : at(given, c.pos));
        idx.push_back(-1);
      }
    } else {
      for (const Face& f : faces_) {
        const std::int32_t k = per == Per::kPart ? f.part : f.face;
        idx.push_back(reads_index ? at(given, k) : k);
      }
    }
    out.set(index_field, make_longs(std::move(idx)));
    return binding(binding_type, per == Per::kVertex ? "PER_VERTEX_INDEXED" : "PER_FACE_INDEXED")
        .get();
  }

  IndexedEquivalent build() {
    IndexedEquivalent r;
    const bool lines = shape_.type == "LineSet";
    NodePtr out = make_node(lines ? "IndexedLineSet" : "IndexedFaceSet");
    out->first_line = shape_.first_line;
    out->last_line = shape_.last_line;
    std::vector<std::int32_t> ci;
    for (const Face& f : faces_) {
      for (const Corner& c : f.corners) ci.push_back(c.coord);
      ci.push_back(-1);
    }
    out->set("coordIndex", make_longs(std::move(ci)));
    r.state = state_;
    r.state.material_binding =
        attribute(state_.material_binding, Per::kOverall, "MaterialBinding", "materialIndex", *out);
    const FieldValue* normals =
        state_.normal ? field_or_default(*state_.normal, "vector") : nullptr;
    if (normals && !normals->floats.empty() && !lines)
      r.state.normal_binding =
          attribute(state_.normal_binding, Per::kVertex, "NormalBinding", "normalIndex", *out);
    const FieldValue* tex = state_.texture_coordinate2
                                ? field_or_default(*state_.texture_coordinate2, "point")
                                : nullptr;
    if (tex && !tex->floats.empty() && !lines) {
      // Texture coordinates follow the vertices (the indexed strip set: its
      // textureCoordIndex, or coordIndex).
      const bool indexed_shape = shape_.type == "IndexedTriangleStripSet";
      const std::vector<std::int32_t>& given = ints_of(shape_, "textureCoordIndex");
      const std::vector<std::int32_t>& input_ci = ints_of(shape_, "coordIndex");
      std::vector<std::int32_t> idx;
      for (const Face& f : faces_) {
        for (const Corner& c : f.corners)
          idx.push_back(!indexed_shape            ? c.seq
                        : is_default_index(given) ? at(input_ci, c.pos)
                                                  : at(given, c.pos));
        idx.push_back(-1);
      }
      out->set("textureCoordIndex", make_longs(std::move(idx)));
    }
    r.shape = out;
    r.owned = std::move(owned_);
    return r;
  }

  const Node& shape_;
  const TraversalState& state_;
  std::int64_t coords_ = 0;
  std::vector<Face> faces_;
  std::int32_t triangle_ = 0;
  std::vector<NodePtr> owned_;
};

}  // namespace

bool has_indexed_equivalent(std::string_view type) {
  return std::find(kTypes.begin(), kTypes.end(), type) != kTypes.end();
}

IndexedEquivalent to_indexed_shape(const ShapeVisit& visit) {
  return Converter(visit).run();
}

}  // namespace lodforge::scene
