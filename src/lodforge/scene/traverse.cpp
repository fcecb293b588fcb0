// The VRML 1.0 traversal state machine (VRML 1.0 specification, "Concepts:
// Scene graph, Transformations, Separator").
#include "lodforge/scene/traverse.h"

#include <algorithm>
#include <array>

#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

constexpr std::array<std::string_view, 8> kShapes = {"IndexedFaceSet", "IndexedLineSet", "PointSet",
                                                     "Cube",           "Sphere",         "Cone",
                                                     "Cylinder",       "AsciiText"};

Vec3 vec3_of(const Node& n, std::string_view field) {
  const FieldValue* v = field_or_default(n, field);
  if (!v || v->floats.size() < 3) return {};
  return {v->floats[0], v->floats[1], v->floats[2]};
}

Mat4 rotation_of(const Node& n, std::string_view field) {
  const FieldValue* v = field_or_default(n, field);
  if (!v || v->floats.size() < 4) return {};
  return Mat4::rotation({v->floats[0], v->floats[1], v->floats[2]}, v->floats[3]);
}

class Walker {
 public:
  Walker(const std::function<void(const ShapeVisit&)>& visit, const TraverseOptions& options)
      : visit_(visit), options_(options) {}

  void node(const Node& n, TraversalState& state, std::size_t index) {
    const std::string& t = n.type;
    if (is_shape_type(t)) {
      visit_(ShapeVisit{n, state, camera_, path_, index, path_index_});
      return;
    }
    if (t == "Coordinate3")
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
    else if (t == "FontStyle")
      state.font_style = &n;
    else if (t == "PerspectiveCamera") {
      if (!camera_) camera_ = &n;
    } else if (t == "Transform" || t == "MatrixTransform" || t == "Translation" ||
               t == "Rotation" || t == "Scale") {
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
    auto children = [&](TraversalState& s) {
      if (n.type == "Switch") {
        const FieldValue* w = field_or_default(n, "whichChild");
        int which = (w && !w->ints.empty()) ? w->ints[0] : -1;
        if (which == -3) {
          for (std::size_t i = 0; i < n.children.size(); ++i) node(*n.children[i], s, i);
        } else if (which >= 0 && std::size_t(which) < n.children.size()) {
          node(*n.children[std::size_t(which)], s, std::size_t(which));
        }
      } else if (n.type == "LOD") {
        const std::size_t k = lod_child(n, state);
        node(*n.children[k], s, k);
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
  const Node* camera_ = nullptr;
  std::vector<const Node*> path_;
  std::vector<std::size_t> path_index_;
};

}  // namespace

bool is_shape_type(std::string_view type) {
  return std::find(kShapes.begin(), kShapes.end(), type) != kShapes.end();
}

Mat4 local_transform(const Node& n) {
  const std::string& t = n.type;
  if (t == "Translation") return Mat4::translation(vec3_of(n, "translation"));
  if (t == "Rotation") return rotation_of(n, "rotation");
  if (t == "Scale") return Mat4::scale(vec3_of(n, "scaleFactor"));
  if (t == "MatrixTransform") {
    const FieldValue* v = field_or_default(n, "matrix");
    return (v && v->floats.size() == 16) ? Mat4::from_vrml(v->floats.data()) : Mat4{};
  }
  if (t == "Transform") {
    // T * C * R * SR * S * SR^-1 * C^-1 (VRML 1.0 Transform node).
    Vec3 c = vec3_of(n, "center");
    Mat4 sr = rotation_of(n, "scaleOrientation");
    const FieldValue* so = field_or_default(n, "scaleOrientation");
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
  for (std::size_t i = 0; i < scene.roots.size(); ++i) w.node(*scene.roots[i], state, i);
}

}  // namespace lodforge::scene
