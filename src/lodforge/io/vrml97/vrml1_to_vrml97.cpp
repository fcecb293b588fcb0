// A VRML 1.0 / Inventor scene graph to VRML97 / X3D classic: the world-space
// shapes each LOD node's children draw (scene::collect_lod_shapes) become
// Shapes under a top-level LOD with the same ranges.
#include "lodforge/io/vrml97/vrml1_to_vrml97.h"

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <unordered_set>

#include "lodforge/scene/lod_shapes.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::vrml97 {
namespace {

using scene::DrawnShape;
using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

// VRML 1.0's ShapeHints creaseAngle default: the smoothing a VRML 1.0 viewer
// gives a shape without normals.
constexpr float kCreaseAngle = 0.5f;

FieldValue vec3s(const std::vector<Vec3>& values, FieldKind kind) {
  std::vector<float> flat;
  flat.reserve(3 * values.size());
  for (const Vec3& p : values) flat.insert(flat.end(), {p.x, p.y, p.z});
  return scene::make_floats(kind, true, std::move(flat));
}

FieldValue vec3(const Vec3& v, FieldKind kind) {
  return scene::make_floats(kind, false, {v.x, v.y, v.z});
}

// Builds the VRML97 nodes, sharing a texture node per Texture2 and a Material
// per colour.
class Converter {
 public:
  // The Shapes drawing `s` (faces, lines or points); empty when it has no
  // geometry.
  std::vector<NodePtr> shapes(const DrawnShape& d) {
    const scene::ShapeSurface& s = d.surface;
    std::vector<NodePtr> out;
    if (s.mesh.positions.empty()) {
      const std::string& t = d.node->type;
      if (t != "IndexedFaceSet" && t != "IndexedLineSet" && t != "PointSet") ++dropped_[t];
      return out;
    }
    if (!s.mesh.triangles.empty()) out.push_back(faces(s));
    if (!s.mesh.lines.empty()) out.push_back(lines(s));
    if (s.mesh.triangles.empty() && s.mesh.lines.empty()) out.push_back(points(s));
    return out;
  }

  const std::map<std::string, std::size_t>& dropped() const { return dropped_; }

 private:
  NodePtr coordinate(const scene::ShapeSurface& s) {
    auto c = scene::make_node("Coordinate");
    c->set("point", vec3s(s.mesh.positions, FieldKind::kVec3f));
    return c;
  }

  // True if every vertex has the first one's colour and opacity.
  static bool uniform(const scene::ShapeSurface& s) {
    return std::all_of(s.mesh.colors.begin(), s.mesh.colors.end(),
                       [&](const Vec3& c) { return c == s.mesh.colors[0]; }) &&
           std::all_of(s.opacity.begin(), s.opacity.end(),
                       [&](float o) { return o == s.opacity[0]; });
  }

  // The shape's Material: its one colour (diffuse, or emissive when unlit),
  // else white under a Color node; the mean opacity (VRML97 has one per
  // shape).
  NodePtr material(const scene::ShapeSurface& s, bool lit, bool one_colour) {
    Vec3 colour{0.8f, 0.8f, 0.8f};
    if (one_colour && s.mesh.has_colors()) colour = s.mesh.colors[0];
    double opacity = 0;
    for (float o : s.opacity) opacity += o;
    const float transparency =
        s.opacity.empty() ? 0.0f : std::clamp(1.0f - float(opacity / s.opacity.size()), 0.0f, 1.0f);
    const auto key = std::make_tuple(colour.x, colour.y, colour.z, transparency, lit);
    if (auto it = materials_.find(key); it != materials_.end()) return it->second;
    auto m = scene::make_node("Material");
    if (lit) {
      m->set("diffuseColor", vec3(colour, FieldKind::kColor));
    } else {
      m->set("diffuseColor", vec3({0, 0, 0}, FieldKind::kColor));
      m->set("emissiveColor", vec3(colour, FieldKind::kColor));
    }
    if (transparency > 0) m->set("transparency", scene::make_float(transparency));
    return materials_[key] = m;
  }

  // The texture node of a Texture2: ImageTexture for a file, PixelTexture for
  // an inline image; nullptr for neither.
  NodePtr texture(const Node* texture2) {
    if (!texture2) return nullptr;
    if (auto it = textures_.find(texture2); it != textures_.end()) return it->second;
    NodePtr t;
    const FieldValue* file = scene::field_or_default(*texture2, "filename");
    const FieldValue* image = scene::field_or_default(*texture2, "image");
    if (file && !file->strings.empty() && !file->strings[0].empty()) {
      t = scene::make_node("ImageTexture");
      FieldValue url = scene::make_string(file->strings[0]);
      url.type.multi = true;
      t->set("url", std::move(url));
    } else if (image && image->ints.size() >= 3 && image->ints[0] > 0) {
      t = scene::make_node("PixelTexture");
      t->set("image", *image);
    }
    if (t)
      for (const auto& [from, to] :
           {std::pair{"wrapS", "repeatS"}, std::pair{"wrapT", "repeatT"}}) {
        const FieldValue* w = scene::field_or_default(*texture2, from);
        if (w && !w->strings.empty() && w->strings[0] == "CLAMP")
          t->set(to, scene::make_bool(false));
      }
    return textures_[texture2] = t;
  }

  // A Color node on `geometry` when the shape has several colours; true when
  // it has one (or none), which its Material then holds.
  static bool colours(Node& geometry, const scene::ShapeSurface& s) {
    if (!s.mesh.has_colors() || uniform(s)) return true;
    auto c = scene::make_node("Color");
    c->set("color", vec3s(s.mesh.colors, FieldKind::kColor));
    geometry.set("color", scene::make_node_value(std::move(c)));
    return false;
  }

  NodePtr shape(NodePtr geometry, NodePtr appearance) {
    auto shape = scene::make_node("Shape");
    shape->set("appearance", scene::make_node_value(std::move(appearance)));
    shape->set("geometry", scene::make_node_value(std::move(geometry)));
    return shape;
  }

  NodePtr appearance(const scene::ShapeSurface& s, bool lit, bool one_colour, NodePtr tex) {
    auto a = scene::make_node("Appearance");
    a->set("material", scene::make_node_value(material(s, lit, one_colour)));
    if (tex) a->set("texture", scene::make_node_value(std::move(tex)));
    return a;
  }

  NodePtr faces(const scene::ShapeSurface& s) {
    auto ifs = scene::make_node("IndexedFaceSet");
    ifs->set("coord", scene::make_node_value(coordinate(s)));
    std::vector<std::int32_t> index;
    index.reserve(4 * s.mesh.triangles.size());
    for (const auto& t : s.mesh.triangles)
      index.insert(index.end(), {std::int32_t(t[0]), std::int32_t(t[1]), std::int32_t(t[2]), -1});
    ifs->set("coordIndex", scene::make_longs(std::move(index)));
    const bool one_colour = colours(*ifs, s);
    if (s.mesh.has_normals()) {
      auto n = scene::make_node("Normal");
      n->set("vector", vec3s(s.mesh.normals, FieldKind::kVec3f));
      ifs->set("normal", scene::make_node_value(std::move(n)));
    }
    NodePtr tex = s.mesh.has_texcoords() ? texture(s.texture) : nullptr;
    if (tex) {
      std::vector<float> flat;
      for (const Vec2& t : s.mesh.texcoords) flat.insert(flat.end(), {t.x, t.y});
      auto tc = scene::make_node("TextureCoordinate");
      tc->set("point", scene::make_floats(FieldKind::kVec2f, true, std::move(flat)));
      ifs->set("texCoord", scene::make_node_value(std::move(tc)));
    }
    ifs->set("solid", scene::make_bool(false));
    ifs->set("creaseAngle", scene::make_float(kCreaseAngle));
    return shape(ifs, appearance(s, true, one_colour, tex));
  }

  NodePtr lines(const scene::ShapeSurface& s) {
    auto ils = scene::make_node("IndexedLineSet");
    ils->set("coord", scene::make_node_value(coordinate(s)));
    std::vector<std::int32_t> index;
    for (const auto& l : s.mesh.lines)
      index.insert(index.end(), {std::int32_t(l[0]), std::int32_t(l[1]), -1});
    ils->set("coordIndex", scene::make_longs(std::move(index)));
    const bool one_colour = colours(*ils, s);
    return shape(ils, appearance(s, false, one_colour, nullptr));
  }

  NodePtr points(const scene::ShapeSurface& s) {
    auto ps = scene::make_node("PointSet");
    ps->set("coord", scene::make_node_value(coordinate(s)));
    const bool one_colour = colours(*ps, s);
    return shape(ps, appearance(s, false, one_colour, nullptr));
  }

  std::map<std::tuple<float, float, float, float, bool>, NodePtr> materials_;
  std::map<const Node*, NodePtr> textures_;
  std::map<std::string, std::size_t> dropped_;
};

// The shapes of one list, each named by its node's DEF name the first time
// that node is met.
std::vector<NodePtr> convert_all(Converter& c, const std::vector<DrawnShape>& drawn,
                                 std::unordered_set<const Node*>& named) {
  std::vector<NodePtr> out;
  for (const DrawnShape& d : drawn) {
    std::vector<NodePtr> made = c.shapes(d);
    if (!made.empty() && !d.node->name.empty() && named.insert(d.node).second)
      made[0]->name = d.node->name;
    out.insert(out.end(), made.begin(), made.end());
  }
  return out;
}

NodePtr convert_lod(Converter& c, const scene::LodGroup& g, bool x3d,
                    std::unordered_set<const Node*>& named) {
  auto lod = scene::make_node("LOD");
  if (!g.lod->name.empty() && named.insert(g.lod).second) lod->name = g.lod->name;
  const FieldValue* range = scene::field_or_default(*g.lod, "range");
  if (range && !range->floats.empty())
    lod->set("range", scene::make_floats(FieldKind::kFloat, true, range->floats));
  const FieldValue* center = scene::field_or_default(*g.lod, "center");
  Vec3 local{};
  if (center && center->floats.size() >= 3)
    local = {center->floats[0], center->floats[1], center->floats[2]};
  lod->set("center", vec3(g.transform.transform_point(local), FieldKind::kVec3f));
  std::vector<NodePtr> levels;
  for (const auto& child : g.levels) {
    auto group = scene::make_node("Group");
    std::vector<NodePtr> shapes = convert_all(c, child, named);
    if (!shapes.empty()) group->set("children", scene::make_nodes_value(std::move(shapes)));
    levels.push_back(std::move(group));
  }
  lod->set(x3d ? "children" : "level", scene::make_nodes_value(std::move(levels)));
  return lod;
}

// Nodes the conversion does not carry, counted by type.
std::map<std::string, std::size_t> not_carried(const scene::Scene& s) {
  static const std::unordered_set<std::string_view> kTypes = {"WWWInline",
                                                              "PerspectiveCamera",
                                                              "OrthographicCamera",
                                                              "PointLight",
                                                              "SpotLight",
                                                              "DirectionalLight",
                                                              "Text2",
                                                              "Text3"};
  std::map<std::string, std::size_t> count;
  scene::for_each_node(s,
                       [&](const Node& n) {
                         if (kTypes.count(n.type)) ++count[n.type];
                       },
                       {.field_nodes = true});
  return count;
}

std::string counted(const std::map<std::string, std::size_t>& m) {
  std::string text;
  for (const auto& [type, n] : m) text += fmt::format("{}{} {}", text.empty() ? "" : ", ", n, type);
  return text;
}

}  // namespace

scene::Scene vrml1_to_vrml97(const scene::Scene& in, const Vrml1ToVrml97Options& options,
                             Log& log) {
  const scene::LodShapes drawn = scene::collect_lod_shapes(in, log);
  Converter c;
  std::unordered_set<const Node*> named;
  scene::Scene out;
  out.header = options.x3d ? "#X3D V3.0 utf8" : "#VRML V2.0 utf8";
  if (options.x3d) {
    auto profile = scene::make_node("PROFILE");
    profile->statement = true;
    profile->raw_body = "Immersive";
    out.roots.push_back(std::move(profile));
  }
  for (NodePtr& s : convert_all(c, drawn.plain, named)) out.roots.push_back(std::move(s));
  for (const auto& [key, group] : drawn.lods)
    out.roots.push_back(convert_lod(c, group, options.x3d, named));
  if (!c.dropped().empty())
    log.warn(LogCategory::kGeneral,
             fmt::format(
                 "{} shapes without geometry here are left out of the {} output: {}",
                 [&] {
                   std::size_t n = 0;
                   for (const auto& [t, k] : c.dropped()) n += k;
                   return n;
                 }(),
                 options.x3d ? "X3D" : "VRML97", counted(c.dropped())));
  if (const auto skipped = not_carried(in); !skipped.empty())
    log.warn(LogCategory::kGeneral,
             fmt::format("not carried into the {} output (the browser supplies its own camera and "
                         "lights; inlined files are not converted): {}",
                         options.x3d ? "X3D" : "VRML97", counted(skipped)));
  return out;
}

}  // namespace lodforge::vrml97
