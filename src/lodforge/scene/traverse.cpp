// The VRML 1.0 traversal state machine (VRML 1.0 specification, "Concepts:
// Scene graph, Transformations, Separator").
#include "lodforge/scene/traverse.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

// A Texture2Transform's matrix (VRML 1.0, Inventor's SoTexture2Transform):
// scale about the center, rotate about it, then translate.
Mat4 texture2_transform_matrix(const Node& n) {
  auto vec2 = [&](const char* field) {
    const FieldValue* v = field_or_default(n, field);
    return v && v->floats.size() >= 2 ? Vec3{v->floats[0], v->floats[1], 0} : Vec3{};
  };
  const FieldValue* r = field_or_default(n, "rotation");
  const float angle = r && !r->floats.empty() ? r->floats[0] : 0;
  Vec3 scale = vec2("scaleFactor");
  scale.z = 1;
  const Vec3 center = vec2("center");
  return Mat4::translation(vec2("translation") + center) * Mat4::rotation({0, 0, 1}, angle) *
         Mat4::scale(scale) * Mat4::translation(-1.0f * center);
}

constexpr std::array<std::string_view, 13> kShapes = {
    "IndexedFaceSet", "IndexedLineSet", "PointSet", "Cube", "Sphere", "Cone", "Cylinder",
    "AsciiText",
    // Open Inventor
    "FaceSet", "TriangleStripSet", "IndexedTriangleStripSet", "QuadMesh", "LineSet"};

// More instances than any real scene has: a bad number, not a scene to draw.
constexpr std::int64_t kMaxArrayInstances = 1'000'000;

// A field as a traversal applies it: the value given unless it carries the
// ignore flag, else the default.
const FieldValue* applied(const Node& n, std::string_view field) {
  if (const FieldValue* v = n.applied_value(field)) return v;
  if (const NodeSpec* s = find_node_spec(n.type))
    if (const FieldSpec* f = s->field(field)) return &f->default_value;
  return nullptr;
}

Vec3 vec3_of(const Node& n, std::string_view field) {
  const FieldValue* v = applied(n, field);
  if (!v || v->floats.size() < 3) return {};
  return {v->floats[0], v->floats[1], v->floats[2]};
}

Mat4 rotation_of(const Node& n, std::string_view field) {
  const FieldValue* v = applied(n, field);
  if (!v || v->floats.size() < 4) return {};
  return Mat4::rotation({v->floats[0], v->floats[1], v->floats[2]}, v->floats[3]);
}

std::int32_t long_of(const Node& n, std::string_view field, std::int32_t fallback) {
  const FieldValue* v = applied(n, field);
  return v && !v->ints.empty() ? v->ints[0] : fallback;
}

// Every field given is ignored ('~'): the node applies nothing.
bool all_ignored(const Node& n) {
  if (n.fields.empty()) return false;
  for (const auto& f : n.fields)
    if (!f.ignored) return false;
  return true;
}

// An Inventor packed colour 0xRRGGBBAA.
void unpack(std::int32_t packed, std::vector<float>& rgb, std::vector<float>& transparency) {
  const auto u = static_cast<std::uint32_t>(packed);
  for (int shift : {24, 16, 8}) rgb.push_back(float((u >> shift) & 0xffu) / 255.f);
  transparency.push_back(1.f - float(u & 0xffu) / 255.f);
}

// The VRML 1.0 property nodes made for one Inventor property node.
struct Derived {
  NodePtr coordinate3, normal, texture_coordinate2, material, material_binding, normal_binding;
};

// Owned by every state of one traversal (TraversalState::derived): the
// nodes made so far, one set per Inventor node, so a node met again (a USE,
// an Array instance) gives the same nodes.
struct DerivedArena {
  std::unordered_map<const Node*, Derived> made;
};

NodePtr derived_node(const char* type, const Node& from, std::string_view field, FieldValue v) {
  NodePtr n = make_node(type);
  n->first_line = from.first_line;
  n->last_line = from.last_line;
  n->set(field, std::move(v));
  return n;
}

NodePtr packed_material(const Node& from, const std::vector<std::int32_t>& packed) {
  std::vector<float> rgb, transparency;
  for (std::int32_t p : packed) unpack(p, rgb, transparency);
  NodePtr m = derived_node("Material", from, "diffuseColor",
                           make_floats(FieldKind::kColor, true, std::move(rgb)));
  m->set("transparency", make_floats(FieldKind::kFloat, true, std::move(transparency)));
  return m;
}

Derived make_derived(const Node& n) {
  Derived d;
  const std::string& t = n.type;
  auto given = [&](std::string_view field) -> const FieldValue* {
    const FieldValue* v = n.applied_value(field);
    return v && v->count() > 0 ? v : nullptr;
  };
  if (t == "BaseColor") {
    if (const FieldValue* rgb = applied(n, "rgb"))
      d.material = derived_node("Material", n, "diffuseColor",
                                make_floats(FieldKind::kColor, true, rgb->floats));
  } else if (t == "PackedColor") {
    if (const FieldValue* c = applied(n, "orderedRGBA")) d.material = packed_material(n, c->ints);
  } else if (t == "VertexProperty") {
    // As SoVertexProperty::doAction: what has values is set, the bindings
    // with the normals and colours they bind.
    if (const FieldValue* v = given("vertex"))
      d.coordinate3 = derived_node("Coordinate3", n, "point", *v);
    if (const FieldValue* v = given("texCoord"))
      d.texture_coordinate2 = derived_node("TextureCoordinate2", n, "point", *v);
    if (const FieldValue* v = given("normal")) {
      d.normal = derived_node("Normal", n, "vector", *v);
      d.normal_binding = derived_node("NormalBinding", n, "value", *applied(n, "normalBinding"));
    }
    if (const FieldValue* v = given("orderedRGBA")) {
      d.material = packed_material(n, v->ints);
      d.material_binding =
          derived_node("MaterialBinding", n, "value", *applied(n, "materialBinding"));
    }
  }
  return d;
}

void apply(const Derived& d, TraversalState& state) {
  if (d.coordinate3) state.coordinate3 = d.coordinate3.get();
  if (d.normal) state.normal = d.normal.get();
  if (d.texture_coordinate2) state.texture_coordinate2 = d.texture_coordinate2.get();
  if (d.material) state.material = d.material.get();
  if (d.material_binding) state.material_binding = d.material_binding.get();
  if (d.normal_binding) state.normal_binding = d.normal_binding.get();
}

// The vertexProperty node of an Inventor shape, or nullptr.
const Node* vertex_property_of(const Node& shape) {
  const FieldValue* v = shape.value("vertexProperty");
  return v && v->type.kind == FieldKind::kNode && !v->nodes.empty() ? v->nodes[0].get() : nullptr;
}

class Walker {
 public:
  Walker(const std::function<void(const ShapeVisit&)>& visit, const TraverseOptions& options)
      : visit_(visit), options_(options), arena_(std::make_shared<DerivedArena>()) {}

  std::shared_ptr<const void> arena() const { return arena_; }

  void node(const Node& n, TraversalState& state, std::size_t index) {
    const std::string& t = n.type;
    // An unknown node kept verbatim has no fields or children to apply.
    if (n.is_raw) return;
    if (is_shape_type(t)) {
      if (const Node* vp = vertex_property_of(n)) {
        // The shape's own vertex data, for this shape only (Inventor pushes
        // the state around it).
        TraversalState with = state;
        apply(derived_of(*vp), with);
        visit_(ShapeVisit{n, with, camera_, path_, index, path_index_, path_transform_});
        return;
      }
      visit_(ShapeVisit{n, state, camera_, path_, index, path_index_, path_transform_});
      return;
    }
    if (n.children.empty() && all_ignored(n)) return;
    if (t == "BaseColor" || t == "PackedColor" || t == "VertexProperty") {
      apply(derived_of(n), state);
    } else if (t == "Complexity") {
      state.complexity = &n;
    } else if (t == "ResetTransform") {
      const FieldValue* what = applied(n, "whatToReset");
      if (what &&
          std::find(what->strings.begin(), what->strings.end(), "TRANSFORM") != what->strings.end())
        state.transform = Mat4{};
    } else if (t == "Coordinate3")
      state.coordinate3 = &n;
    else if (t == "Normal")
      state.normal = &n;
    else if (t == "TextureCoordinate2")
      state.texture_coordinate2 = &n;
    else if (t == "Material")
      state.material = &n;
    else if (t == "MaterialBinding")
      state.material_binding = &n;
    else if (t == "NormalBinding")
      state.normal_binding = &n;
    else if (t == "ShapeHints")
      state.shape_hints = &n;
    else if (t == "Texture2")
      state.texture2 = &n;
    else if (t == "Texture2Transform")
      state.texture_transform = state.texture_transform * texture2_transform_matrix(n);
    else if (t == "FontStyle")
      state.font_style = &n;
    else if (t == "PerspectiveCamera") {
      if (!camera_) camera_ = &n;
    } else if (t == "Transform" || t == "MatrixTransform" || t == "Translation" ||
               t == "Rotation" || t == "Scale" || t == "RotationXYZ") {
      state.transform = state.transform * local_transform(n);
    } else if (!n.children.empty()) {
      group(n, state, index);
    }
  }

 private:
  void group(const Node& n, TraversalState& state, std::size_t index) {
    const NodeSpec* spec = find_node_spec(n.type);
    bool separator = n.type == "WWWInline" || (spec && spec->separator);
    if (!spec && !n.is_a.empty()) {
      const NodeSpec* base = find_node_spec(n.is_a.front());
      separator = base && base->separator;
    }
    path_.push_back(&n);
    path_index_.push_back(index);
    path_transform_.push_back(state.transform);
    auto all = [&](TraversalState& s) {
      for (std::size_t i = 0; i < n.children.size(); ++i) node(*n.children[i], s, i);
    };
    auto children = [&](TraversalState& s) {
      if (n.type == "Switch") {
        const FieldValue* w = field_or_default(n, "whichChild");
        int which = (w && !w->ints.empty()) ? w->ints[0] : -1;
        if (which == -2) which = s.switch_choice;  // Inventor's SO_SWITCH_INHERIT
        s.switch_choice = which;
        if (which == -3) {
          all(s);
        } else if (which >= 0 && std::size_t(which) < n.children.size()) {
          node(*n.children[std::size_t(which)], s, std::size_t(which));
        }
      } else if (n.type == "LOD") {
        const std::size_t k = lod_child(n, state);
        node(*n.children[k], s, k);
      } else if (n.type == "LevelOfDetail") {
        // Inventor's LOD by screen area: the child TraverseOptions::lod_level
        // asks for (no screen to measure areas on; child 0 with a viewpoint).
        const std::size_t k = options_.viewpoint ? 0 : std::size_t(std::max(options_.lod_level, 0));
        const std::size_t c = std::min(k, n.children.size() - 1);
        node(*n.children[c], s, c);
      } else if (n.type == "Array") {
        array_instances(n, s, all);
      } else if (n.type == "MultipleCopy") {
        const FieldValue* m = applied(n, "matrix");
        for (std::size_t k = 0; m && 16 * (k + 1) <= m->floats.size(); ++k) {
          TraversalState copy = s;
          copy.transform = s.transform * Mat4::from_vrml(m->floats.data() + 16 * k);
          all(copy);
        }
      } else {
        for (std::size_t i = 0; i < n.children.size(); ++i) node(*n.children[i], s, i);
      }
    };
    if (separator) {
      TraversalState saved = state;
      children(saved);
    } else if (n.type == "TransformSeparator") {
      Mat4 saved = state.transform;
      children(state);
      state.transform = saved;
    } else {
      children(state);
    }
    path_.pop_back();
    path_index_.pop_back();
    path_transform_.pop_back();
  }

  // Inventor's Array: numElements1 x 2 x 3 instances, instance (i, j, k) at
  // i * separation1 + j * separation2 + k * separation3, moved so that the
  // first, the centre or the last instance is at the origin. Each instance is
  // traversed with the state saved around it.
  template <typename Children>
  void array_instances(const Node& n, TraversalState& s, Children& all) {
    const std::int64_t n1 = std::max<std::int32_t>(0, long_of(n, "numElements1", 1));
    const std::int64_t n2 = std::max<std::int32_t>(0, long_of(n, "numElements2", 1));
    const std::int64_t n3 = std::max<std::int32_t>(0, long_of(n, "numElements3", 1));
    if (n1 > kMaxArrayInstances || n2 > kMaxArrayInstances || n3 > kMaxArrayInstances ||
        n1 * n2 > kMaxArrayInstances || n1 * n2 * n3 > kMaxArrayInstances)
      throw DataError(fmt::format("line {}: Array of {} x {} x {} instances; at most {} are drawn",
                                  n.first_line, n1, n2, n3, kMaxArrayInstances));
    const Vec3 d1 = vec3_of(n, "separation1"), d2 = vec3_of(n, "separation2"),
               d3 = vec3_of(n, "separation3");
    const FieldValue* origin = applied(n, "origin");
    const std::string o = origin && !origin->strings.empty() ? origin->strings[0] : "FIRST";
    Vec3 start{};
    if (o != "FIRST") {
      start = -(d1 * float(n1 - 1) + d2 * float(n2 - 1) + d3 * float(n3 - 1));
      if (o == "CENTER") start = start * 0.5f;
    }
    for (std::int64_t k = 0; k < n3; ++k)
      for (std::int64_t j = 0; j < n2; ++j)
        for (std::int64_t i = 0; i < n1; ++i) {
          TraversalState copy = s;
          copy.transform = s.transform *
                           Mat4::translation(start + d1 * float(i) + d2 * float(j) + d3 * float(k));
          all(copy);
        }
  }

  const Derived& derived_of(const Node& n) {
    auto it = arena_->made.find(&n);
    if (it == arena_->made.end()) it = arena_->made.emplace(&n, make_derived(n)).first;
    return it->second;
  }

  // The child a LOD node shows (see TraverseOptions::viewpoint). `range` is
  // ascending by the specification, so the child is the number of ranges <= d.
  std::size_t lod_child(const Node& n, const TraversalState& state) const {
    std::size_t k = std::size_t(std::max(options_.lod_level, 0));
    if (options_.viewpoint) {
      const float d =
          length(state.transform.transform_point(vec3_of(n, "center")) - *options_.viewpoint);
      const FieldValue* range = field_or_default(n, "range");
      k = range ? std::size_t(std::upper_bound(range->floats.begin(), range->floats.end(), d) -
                              range->floats.begin())
                : 0;
    }
    return std::min(k, n.children.size() - 1);
  }

  const std::function<void(const ShapeVisit&)>& visit_;
  const TraverseOptions& options_;
  std::shared_ptr<DerivedArena> arena_;
  const Node* camera_ = nullptr;
  std::vector<const Node*> path_;
  std::vector<std::size_t> path_index_;
  std::vector<Mat4> path_transform_;
};

}  // namespace

bool is_shape_type(std::string_view type) {
  return std::find(kShapes.begin(), kShapes.end(), type) != kShapes.end();
}

float complexity_value(const TraversalState& state) {
  if (!state.complexity) return 0.5f;
  const FieldValue* v = applied(*state.complexity, "value");
  const float c = v && !v->floats.empty() ? v->floats[0] : 0.5f;
  return std::isfinite(c) ? std::clamp(c, 0.f, 1.f) : 0.5f;
}

Mat4 local_transform(const Node& n) {
  const std::string& t = n.type;
  if (t == "Translation") return Mat4::translation(vec3_of(n, "translation"));
  if (t == "Rotation") return rotation_of(n, "rotation");
  if (t == "Scale") return Mat4::scale(vec3_of(n, "scaleFactor"));
  if (t == "RotationXYZ") {
    const FieldValue* axis = applied(n, "axis");
    const FieldValue* angle = applied(n, "angle");
    const std::string a = axis && !axis->strings.empty() ? axis->strings[0] : "X";
    const float r = angle && !angle->floats.empty() ? angle->floats[0] : 0.f;
    return Mat4::rotation({a == "X" ? 1.f : 0.f, a == "Y" ? 1.f : 0.f, a == "Z" ? 1.f : 0.f}, r);
  }
  if (t == "MatrixTransform") {
    const FieldValue* v = applied(n, "matrix");
    return (v && v->floats.size() == 16) ? Mat4::from_vrml(v->floats.data()) : Mat4{};
  }
  if (t == "Transform") {
    // T * C * R * SR * S * SR^-1 * C^-1 (VRML 1.0 Transform node).
    Vec3 c = vec3_of(n, "center");
    Mat4 sr = rotation_of(n, "scaleOrientation");
    const FieldValue* so = applied(n, "scaleOrientation");
    Mat4 sr_inv =
        so && so->floats.size() >= 4
            ? Mat4::rotation({so->floats[0], so->floats[1], so->floats[2]}, -so->floats[3])
            : Mat4{};
    return Mat4::translation(vec3_of(n, "translation")) * Mat4::translation(c) *
           rotation_of(n, "rotation") * sr * Mat4::scale(vec3_of(n, "scaleFactor")) * sr_inv *
           Mat4::translation(-c);
  }
  return {};
}

void traverse(const Scene& scene, const std::function<void(const ShapeVisit&)>& visit,
              const TraverseOptions& options) {
  Walker w(visit, options);
  TraversalState state;
  state.derived = w.arena();
  for (std::size_t i = 0; i < scene.roots.size(); ++i) w.node(*scene.roots[i], state, i);
}

void for_each_node(const Scene& scene, const std::function<void(const Node&)>& visit,
                   const NodeWalkOptions& options) {
  std::unordered_set<const Node*> seen;
  std::vector<const Node*> stack;
  for (const auto& r : scene.roots) stack.push_back(r.get());
  while (!stack.empty()) {
    const Node* n = stack.back();
    stack.pop_back();
    if (!n || !seen.insert(n).second) continue;
    visit(*n);
    for (const auto& c : n->children) stack.push_back(c.get());
    if (options.field_nodes)
      for (const auto& c : field_nodes(*n)) stack.push_back(c.get());
  }
}

std::size_t lod_level_count(const Scene& scene) {
  std::size_t count = 1;
  for_each_node(scene, [&](const Node& n) {
    if (n.type == "LOD" || n.type == "LevelOfDetail") count = std::max(count, n.children.size());
  });
  return count;
}

}  // namespace lodforge::scene
