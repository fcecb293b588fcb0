// The VRML 1.0 node catalogue (VRML 1.0 specification, 1995, "Nodes Reference"):
// every standard node with its fields, their types and default values; then
// the Open Inventor 2.1 nodes and fields that change what a scene draws (The
// Inventor Mentor and Coin's class documentation give their fields and
// defaults), marked as Inventor-only.
#include "lodforge/scene/schema.h"

#include <algorithm>
#include <initializer_list>

namespace lodforge::scene {
namespace {

using K = FieldKind;

FieldSpec sf(std::string name, K kind, std::vector<float> def) {
  return {std::move(name), {kind, false}, make_floats(kind, false, std::move(def)), {}};
}
FieldSpec mf(std::string name, K kind, std::vector<float> def) {
  return {std::move(name), {kind, true}, make_floats(kind, true, std::move(def)), {}};
}
FieldSpec sf_long(std::string name, std::int32_t def) {
  return {std::move(name), {K::kLong, false}, make_long(def), {}};
}
FieldSpec mf_long(std::string name, std::vector<std::int32_t> def) {
  return {std::move(name), {K::kLong, true}, make_longs(std::move(def)), {}};
}
FieldSpec sf_bool(std::string name, bool def) {
  return {std::move(name), {K::kBool, false}, make_bool(def), {}};
}
FieldSpec sf_string(std::string name, std::string def) {
  return {std::move(name), {K::kString, false}, make_string(std::move(def)), {}};
}
FieldSpec mf_string(std::string name, std::string def) {
  FieldSpec s{std::move(name), {K::kString, true}, make_string(std::move(def)), {}};
  s.default_value.type.multi = true;
  return s;
}
FieldSpec sf_enum(std::string name, std::string def, std::vector<std::string> names) {
  return {std::move(name), {K::kEnum, false}, make_enum(std::move(def)), std::move(names)};
}
FieldSpec sf_bitmask(std::string name, std::vector<std::string> def,
                     std::vector<std::string> names) {
  FieldValue v;
  v.type = {K::kBitMask, false};
  v.strings = std::move(def);
  return {std::move(name), {K::kBitMask, false}, std::move(v), std::move(names)};
}
FieldSpec sf_node(std::string name) {
  FieldValue v;
  v.type = {K::kNode, false};
  return {std::move(name), {K::kNode, false}, std::move(v), {}};
}
FieldSpec mf_uint32(std::string name, std::vector<std::uint32_t> def) {
  FieldValue v;
  v.type = {K::kUInt32, true};
  for (std::uint32_t x : def) v.ints.push_back(static_cast<std::int32_t>(x));
  return {std::move(name), {K::kUInt32, true}, std::move(v), {}};
}
FieldSpec sf_image(std::string name) {
  FieldValue v;
  v.type = {K::kImage, false};
  v.ints = {0, 0, 0};
  return {std::move(name), {K::kImage, false}, std::move(v), {}};
}

const std::vector<std::string> kBindings = {
    "DEFAULT",  "OVERALL",          "PER_PART",   "PER_PART_INDEXED",
    "PER_FACE", "PER_FACE_INDEXED", "PER_VERTEX", "PER_VERTEX_INDEXED"};

std::vector<FieldSpec> light_fields(std::initializer_list<FieldSpec> extra) {
  std::vector<FieldSpec> f = {sf_bool("on", true), sf("intensity", K::kFloat, {1}),
                              sf("color", K::kColor, {1, 1, 1})};
  f.insert(f.end(), extra.begin(), extra.end());
  return f;
}

std::vector<FieldSpec> indexed_set_fields() {
  return {mf_long("coordIndex", {0}), mf_long("materialIndex", {-1}), mf_long("normalIndex", {-1}),
          mf_long("textureCoordIndex", {-1})};
}

// Open Inventor 2.1: fields of the nodes VRML 1.0 shares with it, then the
// Inventor-only nodes that change the geometry a scene draws. Inventor nodes
// that do not (DrawStyle, LightModel, Font, Text2, Label, engines, ...) stay
// unknown nodes, kept verbatim.
void add_inventor(std::vector<NodeSpec>& s) {
  auto extend = [&](std::string_view type, std::vector<FieldSpec> fields) {
    for (auto& n : s)
      if (n.type == type)
        for (auto& f : fields) {
          f.inventor = true;
          n.fields.push_back(f);
        }
  };
  const std::vector<std::string> kCaching = {"ON", "OFF", "AUTO"};
  extend("Separator", {sf_enum("renderCaching", "AUTO", kCaching),
                       sf_enum("boundingBoxCaching", "AUTO", kCaching),
                       sf_enum("pickCulling", "AUTO", kCaching)});
  for (const char* t : {"IndexedFaceSet", "IndexedLineSet", "PointSet"})
    extend(t, {sf_node("vertexProperty")});
  extend("Texture2", {sf_enum("model", "MODULATE", {"MODULATE", "DECAL", "BLEND", "REPLACE"}),
                      sf("blendColor", K::kColor, {0, 0, 0})});

  auto inventor = [&](std::string type, bool group, bool separator, std::vector<FieldSpec> fields) {
    for (auto& f : fields) f.inventor = true;
    NodeSpec n{std::move(type), group, separator, std::move(fields)};
    n.inventor = true;
    s.push_back(std::move(n));
  };
  const std::vector<std::string> kVertexBindings = {
      "OVERALL",          "PER_PART",   "PER_PART_INDEXED",  "PER_FACE",
      "PER_FACE_INDEXED", "PER_VERTEX", "PER_VERTEX_INDEXED"};
  inventor("VertexProperty", false, false,
           {mf("vertex", K::kVec3f, {}), mf("normal", K::kVec3f, {}), mf("texCoord", K::kVec2f, {}),
            mf("texCoord3", K::kVec3f, {}), mf_uint32("orderedRGBA", {}),
            sf_enum("materialBinding", "OVERALL", kVertexBindings),
            sf_enum("normalBinding", "PER_VERTEX_INDEXED", kVertexBindings)});
  auto non_indexed = [&](std::vector<FieldSpec> extra) {
    std::vector<FieldSpec> f = {sf_node("vertexProperty"), sf_long("startIndex", 0)};
    f.insert(f.end(), extra.begin(), extra.end());
    return f;
  };
  inventor("FaceSet", false, false, non_indexed({mf_long("numVertices", {-1})}));
  inventor("TriangleStripSet", false, false, non_indexed({mf_long("numVertices", {-1})}));
  inventor("LineSet", false, false, non_indexed({mf_long("numVertices", {-1})}));
  inventor("QuadMesh", false, false,
           non_indexed({sf_long("verticesPerColumn", 1), sf_long("verticesPerRow", 1)}));
  {
    std::vector<FieldSpec> f = indexed_set_fields();
    f.insert(f.begin(), sf_node("vertexProperty"));
    inventor("IndexedTriangleStripSet", false, false, std::move(f));
  }
  inventor("Complexity", false, false,
           {sf_enum("type", "OBJECT_SPACE", {"OBJECT_SPACE", "SCREEN_SPACE", "BOUNDING_BOX"}),
            sf("value", K::kFloat, {0.5f}), sf("textureQuality", K::kFloat, {0.5f})});
  inventor("RotationXYZ", false, false,
           {sf_enum("axis", "X", {"X", "Y", "Z"}), sf("angle", K::kFloat, {0})});
  inventor("ResetTransform", false, false,
           {sf_bitmask("whatToReset", {"TRANSFORM"}, {"TRANSFORM", "BBOX"})});
  inventor("BaseColor", false, false, {mf("rgb", K::kColor, {0.8f, 0.8f, 0.8f})});
  inventor("PackedColor", false, false, {mf_uint32("orderedRGBA", {0xccccccffu})});
  inventor("Array", true, false,
           {sf_enum("origin", "FIRST", {"FIRST", "CENTER", "LAST"}), sf_long("numElements1", 1),
            sf_long("numElements2", 1), sf_long("numElements3", 1),
            sf("separation1", K::kVec3f, {1, 0, 0}), sf("separation2", K::kVec3f, {0, 1, 0}),
            sf("separation3", K::kVec3f, {0, 0, 1})});
  inventor("MultipleCopy", true, false,
           {mf("matrix", K::kMatrix, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1})});
  inventor("LevelOfDetail", true, false, {mf("screenArea", K::kFloat, {0})});
  inventor("Annotation", true, true, {});
  inventor(
      "Selection", true, true,
      {sf_enum("renderCaching", "AUTO", kCaching), sf_enum("boundingBoxCaching", "AUTO", kCaching),
       sf_enum("renderCulling", "AUTO", kCaching), sf_enum("pickCulling", "AUTO", kCaching),
       sf_enum("policy", "SHIFT", {"SINGLE", "TOGGLE", "SHIFT"})});
}

std::vector<NodeSpec> build() {
  const float kQuarterPi = 0.785398f;
  std::vector<NodeSpec> s;
  auto node = [&](std::string type, std::vector<FieldSpec> fields) {
    s.push_back({std::move(type), false, false, std::move(fields)});
  };
  auto group = [&](std::string type, bool separator, std::vector<FieldSpec> fields) {
    s.push_back({std::move(type), true, separator, std::move(fields)});
  };
  node("AsciiText", {mf_string("string", ""), sf("spacing", K::kFloat, {1}),
                     sf_enum("justification", "LEFT", {"LEFT", "CENTER", "RIGHT"}),
                     mf("width", K::kFloat, {0})});
  node("Cone", {sf_bitmask("parts", {"ALL"}, {"SIDES", "BOTTOM", "ALL"}),
                sf("bottomRadius", K::kFloat, {1}), sf("height", K::kFloat, {2})});
  node("Coordinate3", {mf("point", K::kVec3f, {0, 0, 0})});
  node("Cube",
       {sf("width", K::kFloat, {2}), sf("height", K::kFloat, {2}), sf("depth", K::kFloat, {2})});
  node("Cylinder", {sf_bitmask("parts", {"ALL"}, {"SIDES", "TOP", "BOTTOM", "ALL"}),
                    sf("radius", K::kFloat, {1}), sf("height", K::kFloat, {2})});
  node("DirectionalLight", light_fields({sf("direction", K::kVec3f, {0, 0, -1})}));
  node("FontStyle",
       {sf("size", K::kFloat, {10}), sf_enum("family", "SERIF", {"SERIF", "SANS", "TYPEWRITER"}),
        sf_bitmask("style", {"NONE"}, {"NONE", "BOLD", "ITALIC"})});
  group("Group", false, {});
  node("IndexedFaceSet", indexed_set_fields());
  node("IndexedLineSet", indexed_set_fields());
  node("Info", {sf_string("string", "<Undefined info>")});
  group("LOD", true, {mf("range", K::kFloat, {}), sf("center", K::kVec3f, {0, 0, 0})});
  node("Material",
       {mf("ambientColor", K::kColor, {0.2f, 0.2f, 0.2f}),
        mf("diffuseColor", K::kColor, {0.8f, 0.8f, 0.8f}),
        mf("specularColor", K::kColor, {0, 0, 0}), mf("emissiveColor", K::kColor, {0, 0, 0}),
        mf("shininess", K::kFloat, {0.2f}), mf("transparency", K::kFloat, {0})});
  node("MaterialBinding", {sf_enum("value", "DEFAULT", kBindings)});
  node("MatrixTransform",
       {sf("matrix", K::kMatrix, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1})});
  node("Normal", {mf("vector", K::kVec3f, {})});
  node("NormalBinding", {sf_enum("value", "DEFAULT", kBindings)});
  node("OrthographicCamera",
       {sf("position", K::kVec3f, {0, 0, 1}), sf("orientation", K::kRotation, {0, 0, 1, 0}),
        sf("focalDistance", K::kFloat, {5}), sf("height", K::kFloat, {2})});
  node("PerspectiveCamera",
       {sf("position", K::kVec3f, {0, 0, 1}), sf("orientation", K::kRotation, {0, 0, 1, 0}),
        sf("focalDistance", K::kFloat, {5}), sf("heightAngle", K::kFloat, {kQuarterPi})});
  node("PointLight", light_fields({sf("location", K::kVec3f, {0, 0, 1})}));
  node("PointSet", {sf_long("startIndex", 0), sf_long("numPoints", -1)});
  node("Rotation", {sf("rotation", K::kRotation, {0, 0, 1, 0})});
  node("Scale", {sf("scaleFactor", K::kVec3f, {1, 1, 1})});
  group("Separator", true, {sf_enum("renderCulling", "AUTO", {"ON", "OFF", "AUTO"})});
  node("ShapeHints", {sf_enum("vertexOrdering", "UNKNOWN_ORDERING",
                              {"UNKNOWN_ORDERING", "CLOCKWISE", "COUNTERCLOCKWISE"}),
                      sf_enum("shapeType", "UNKNOWN_SHAPE_TYPE", {"UNKNOWN_SHAPE_TYPE", "SOLID"}),
                      sf_enum("faceType", "CONVEX", {"UNKNOWN_FACE_TYPE", "CONVEX"}),
                      sf("creaseAngle", K::kFloat, {0.5f})});
  node("Sphere", {sf("radius", K::kFloat, {1})});
  node("SpotLight",
       light_fields({sf("location", K::kVec3f, {0, 0, 1}), sf("direction", K::kVec3f, {0, 0, -1}),
                     sf("dropOffRate", K::kFloat, {0}),
                     sf("cutOffAngle", K::kFloat, {kQuarterPi})}));
  group("Switch", false, {sf_long("whichChild", -1)});
  node("Texture2", {sf_string("filename", ""), sf_image("image"),
                    sf_enum("wrapS", "REPEAT", {"REPEAT", "CLAMP"}),
                    sf_enum("wrapT", "REPEAT", {"REPEAT", "CLAMP"})});
  node("Texture2Transform",
       {sf("translation", K::kVec2f, {0, 0}), sf("rotation", K::kFloat, {0}),
        sf("scaleFactor", K::kVec2f, {1, 1}), sf("center", K::kVec2f, {0, 0})});
  node("TextureCoordinate2", {mf("point", K::kVec2f, {0, 0})});
  node("Transform",
       {sf("translation", K::kVec3f, {0, 0, 0}), sf("rotation", K::kRotation, {0, 0, 1, 0}),
        sf("scaleFactor", K::kVec3f, {1, 1, 1}), sf("scaleOrientation", K::kRotation, {0, 0, 1, 0}),
        sf("center", K::kVec3f, {0, 0, 0})});
  group("TransformSeparator", false, {});
  node("Translation", {sf("translation", K::kVec3f, {0, 0, 0})});
  group("WWWAnchor", true,
        {sf_string("name", ""), sf_string("description", ""),
         sf_enum("map", "NONE", {"NONE", "POINT"})});
  node("WWWInline", {sf_string("name", ""), sf("bboxSize", K::kVec3f, {0, 0, 0}),
                     sf("bboxCenter", K::kVec3f, {0, 0, 0})});
  add_inventor(s);
  return s;
}

const std::vector<NodeSpec>& specs() {
  static const std::vector<NodeSpec> table = build();
  return table;
}

}  // namespace

const FieldSpec* NodeSpec::field(std::string_view name, bool with_inventor) const {
  for (const auto& f : fields)
    if (f.name == name && (with_inventor || !f.inventor)) return &f;
  return nullptr;
}

const NodeSpec* find_node_spec(std::string_view type, bool with_inventor) {
  const auto& t = specs();
  auto it = std::find_if(t.begin(), t.end(), [&](const NodeSpec& s) { return s.type == type; });
  return it == t.end() || (it->inventor && !with_inventor) ? nullptr : &*it;
}

std::span<const NodeSpec> node_specs() {
  return specs();
}

const FieldValue* field_or_default(const Node& node, std::string_view name) {
  if (const FieldValue* v = node.value(name)) return v;
  if (const NodeSpec* s = find_node_spec(node.type))
    if (const FieldSpec* f = s->field(name)) return &f->default_value;
  return nullptr;
}

}  // namespace lodforge::scene
