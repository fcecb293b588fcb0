#include "lodforge/lod/flatten_vrml97.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/data_uri.h"
#include "lodforge/core/error.h"
#include "lodforge/core/math.h"
#include "lodforge/lod/vrml97_geometry.h"
#include "lodforge/scene/tessellate_primitive.h"

namespace lodforge {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;

// Deeper nesting than the reader allows cannot occur; this guards USE cycles.
constexpr int kMaxDepth = 512;
const Vec3 kDefaultGrey{0.8f, 0.8f, 0.8f};

Vec3 vec3_of(const Node& n, std::string_view field, Vec3 fallback) {
  const FieldValue* v = n.value(field);
  return v && v->floats.size() >= 3 ? Vec3{v->floats[0], v->floats[1], v->floats[2]} : fallback;
}

Mat4 rotation_of(const Node& n, std::string_view field, bool inverse = false) {
  const FieldValue* v = n.value(field);
  if (!v || v->floats.size() < 4) return {};
  return Mat4::rotation({v->floats[0], v->floats[1], v->floats[2]},
                        inverse ? -v->floats[3] : v->floats[3]);
}

// T * C * R * SR * S * SR^-1 * C^-1 (ISO/IEC 14772-1, 6.52 Transform).
Mat4 transform_of(const Node& n) {
  const Vec3 c = vec3_of(n, "center", {});
  return Mat4::translation(vec3_of(n, "translation", {})) * Mat4::translation(c) *
         rotation_of(n, "rotation") * rotation_of(n, "scaleOrientation") *
         Mat4::scale(vec3_of(n, "scale", {1, 1, 1})) * rotation_of(n, "scaleOrientation", true) *
         Mat4::translation(-c);
}

// A TextureTransform's matrix (ISO/IEC 14772-1, 6.49): Tc' = -C × S × R ×
// C × T × Tc, in x and y.
Mat4 texture_transform_of(const Node& t) {
  auto vec2 = [&](std::string_view field, Vec3 fallback) {
    const FieldValue* v = t.value(field);
    return v && v->floats.size() >= 2 ? Vec3{v->floats[0], v->floats[1], 0} : fallback;
  };
  Vec3 scale = vec2("scale", {1, 1, 0});
  scale.z = 1;
  const Vec3 c = vec2("center", {});
  const FieldValue* r = t.value("rotation");
  return Mat4::translation(-c) * Mat4::scale(scale) *
         Mat4::rotation({0, 0, 1}, r && !r->floats.empty() ? r->floats[0] : 0) *
         Mat4::translation(c) * Mat4::translation(vec2("translation", {}));
}

std::vector<NodePtr> nodes_of(const Node& n, std::string_view field) {
  const FieldValue* v = n.value(field);
  return v && v->type.kind == FieldKind::kNode ? v->nodes : std::vector<NodePtr>{};
}

int int_of(const Node& n, std::string_view field, int fallback) {
  const FieldValue* v = n.value(field);
  return v && !v->ints.empty() ? v->ints[0] : fallback;
}

float float_of(const Node& n, std::string_view field, float fallback) {
  const FieldValue* v = n.value(field);
  return v && !v->floats.empty() ? v->floats[0] : fallback;
}

bool is_primitive(const std::string& type) {
  return type == "Box" || type == "Sphere" || type == "Cone" || type == "Cylinder";
}

// A VRML97 primitive as the VRML 1.0 node tessellate_primitive knows (the
// same defaults; Box's size is Cube's width, height and depth; side, top and
// bottom are Cone's and Cylinder's parts).
NodePtr as_vrml1_primitive(const Node& g) {
  if (g.type == "Box") {
    NodePtr cube = scene::make_node("Cube");
    cube->first_line = g.first_line;
    const Vec3 size = vec3_of(g, "size", {2, 2, 2});
    cube->set("width", scene::make_float(size.x));
    cube->set("height", scene::make_float(size.y));
    cube->set("depth", scene::make_float(size.z));
    return cube;
  }
  NodePtr n = scene::make_node(g.type);
  n->first_line = g.first_line;
  for (const char* f : {"radius", "bottomRadius", "height"})
    if (const FieldValue* v = g.value(f)) n->set(f, *v);
  if (g.type == "Sphere") return n;
  FieldValue parts = scene::make_enum("SIDES");
  parts.strings.clear();
  auto part = [&](const char* field, const char* name) {
    const FieldValue* v = g.value(field);
    if (!v || v->ints.empty() || v->ints[0]) parts.strings.push_back(name);
  };
  part("side", "SIDES");
  part("bottom", "BOTTOM");
  if (g.type == "Cylinder") part("top", "TOP");
  n->set("parts", std::move(parts));
  return n;
}

// A shape coloured per face: every triangle gets vertices of its own whose
// colour slot holds its polygon's colour index.
vrml97_geometry::ShapeMesh unshared_by_face(const vrml97_geometry::ShapeMesh& in,
                                            const std::vector<std::uint32_t>& face_color) {
  vrml97_geometry::ShapeMesh out;
  for (std::size_t t = 0; t < in.mesh.triangles.size(); ++t) {
    const std::uint32_t polygon = in.triangle_polygon[t];
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = in.mesh.triangles[t][k];
      tri[k] = std::uint32_t(out.mesh.positions.size());
      out.mesh.positions.push_back(in.mesh.positions[v]);
      vrml97_geometry::Corner c = in.vertex_corner[v];
      c[3] = polygon < face_color.size() ? face_color[polygon] : kNone;
      out.vertex_corner.push_back(c);
    }
    out.mesh.triangles.push_back(tri);
    out.triangle_polygon.push_back(polygon);
  }
  return out;
}

class Flattener {
 public:
  Flattener(const FlattenVrml97Options& options, Log& log) : options_(options), log_(log) {}

  /// Collects each Shape drawn as a shape of its own into `shapes` (by the
  /// LOD node it is drawn under, every level of it) instead of the one mesh.
  void collect(Vrml97LodShapes& shapes) {
    collect_ = &shapes;
    sink_ = &shapes.shapes.plain;
  }

  void node(const NodePtr& n, const Mat4& m, int depth) {
    if (!n) return;
    if (depth > kMaxDepth)
      throw DataError(fmt::format("line {}: nodes nested deeper than {} (a USE inside itself?)",
                                  n->first_line, kMaxDepth));
    const std::string& t = n->type;
    if (n->statement) return;  // PROTO, ROUTE, ... (their bodies are not drawn)
    if (t == "Shape") return shape(*n, m);
    if (t == "Transform") return children(nodes_of(*n, "children"), m * transform_of(*n), depth);
    if (t == "LOD") return lod(*n, m, depth);
    if (t == "Switch") return choice(*n, m, depth);
    if (t == "Inline") {
      ++out_.skipped[t];
      return;
    }
    // A skinned mesh (Castle's Skin, an HAnimHumanoid's skin) is drawn in the
    // pose its coordinates hold, in the humanoid's own transform.
    if (t == "Skin") return children(nodes_of(*n, "shapes"), m, depth);
    if (t == "HAnimHumanoid") return children(nodes_of(*n, "skin"), m * transform_of(*n), depth);
    children(nodes_of(*n, "children"), m, depth);
  }

  FlatVrml97 result() {
    if (!has_color_ && out_.flat.textures.empty()) {  // a plain mesh
      out_.flat.mesh.colors.clear();
      out_.flat.mesh.texcoords.clear();
      out_.flat.mesh.materials.clear();
      out_.flat.opacity.clear();
    }
    return std::move(out_);
  }

 private:
  void children(const std::vector<NodePtr>& list, const Mat4& m, int depth) {
    for (const NodePtr& c : list) node(c, m, depth + 1);
  }

  void lod(const Node& n, const Mat4& m, int depth) {
    std::vector<NodePtr> levels = nodes_of(n, "level");
    if (levels.empty()) levels = nodes_of(n, "children");  // X3D
    if (levels.empty()) return;
    if (collect_ && sink_ == &collect_->shapes.plain) {  // every level, each a group of shapes
      scene::LodGroup group{.lod = &n, .transform = m};
      group.levels.resize(levels.size());
      for (std::size_t k = 0; k < levels.size(); ++k) {
        sink_ = &group.levels[k];
        node(levels[k], m, depth + 1);
      }
      sink_ = &collect_->shapes.plain;
      collect_->shapes.lods[{collect_->shapes.lods.size()}] = std::move(group);
      return;
    }
    std::size_t k = std::size_t(std::max(options_.lod_level, 0));
    if (options_.viewpoint) {
      // `range` ascends: the level is the number of ranges <= the distance.
      const float d = length(m.transform_point(vec3_of(n, "center", {})) - *options_.viewpoint);
      const FieldValue* range = n.value("range");
      k = range ? std::size_t(std::upper_bound(range->floats.begin(), range->floats.end(), d) -
                              range->floats.begin())
                : 0;
    }
    node(levels[std::min(k, levels.size() - 1)], m, depth + 1);
  }

  void choice(const Node& n, const Mat4& m, int depth) {
    std::vector<NodePtr> choices = nodes_of(n, "choice");
    if (choices.empty()) choices = nodes_of(n, "children");  // X3D
    const int k = int_of(n, "whichChoice", -1);
    if (k >= 0 && std::size_t(k) < choices.size()) node(choices[std::size_t(k)], m, depth + 1);
  }

  void shape(const Node& s, const Mat4& m) {
    const NodePtr g = vrml97_geometry::node_of(s, "geometry");
    if (!g) return;
    const Node& geometry = *g;
    if (geometry.type == "IndexedLineSet") {
      ++out_.shapes;
      scene::DrawnShape lines = line_shape(s, geometry, m);
      if (collect_) {
        if (sink_) sink_->push_back(std::move(lines));
      } else {
        const NodePtr a = vrml97_geometry::node_of(s, "appearance");
        append_lines(lines.surface, vrml97_geometry::node_of(geometry, "color") ||
                                        (a && vrml97_geometry::node_of(*a, "material")));
      }
      return;
    }
    vrml97_geometry::ShapeMesh piece;
    Attributes from;
    if (is_primitive(geometry.type)) {
      piece.mesh = scene::tessellate_primitive(*as_vrml1_primitive(geometry));
    } else if (vrml97_geometry::is_supported_geometry(geometry.type)) {
      // The reader's warnings speak of levels (an attribute dropped from
      // them, a shape left without LOD): here only an undrawn shape matters.
      Log reader_log;
      vrml97_geometry::GeometryReader reader(geometry, reader_log,
                                             fmt::format("line {}", geometry.first_line));
      vrml97_geometry::Polygons polygons;
      if (!reader.read(polygons)) {
        ++out_.skipped[geometry.type];
        for (const auto& d : reader_log.entries())
          log_.warn(LogCategory::kParse, fmt::format("{} (not drawn)", d.text));
        return;
      }
      vrml97_geometry::build_mesh(polygons, reader, options_.triangulation, piece);
      if (const NodePtr& c = reader.color().node) {
        from.color_node = c;
        from.colors = c->value("color");
        from.stride = c->type == "ColorRGBA" ? 4 : 3;
        if (!reader.color().per_vertex) piece = unshared_by_face(piece, polygons.face_color);
      }
      // The first 2D coordinate list (of a MultiTextureCoordinate: its
      // first texture's); computed ones get VRML97's default mapping.
      if (NodePtr t = vrml97_geometry::first_texture_coordinates(reader.tex().node)) {
        from.texcoord_node = t;
        from.texcoords = t->value("point");
      }
    } else {
      ++out_.skipped[geometry.type];
      return;
    }
    ++out_.shapes;
    const std::size_t vertices = out_.flat.mesh.positions.size();
    const std::size_t triangles = out_.flat.mesh.triangles.size();
    const Look look = appearance_of(s);
    append(piece, m, look, from);
    if (sink_) sink_->push_back(take_shape(s, vertices, triangles, look.texture));
  }

  // An IndexedLineSet as line segments in world space, coloured by its Color
  // node (per vertex or per polyline) or else its Material's emissiveColor
  // (white without a Material: VRML97 lines are not lit).
  scene::DrawnShape line_shape(const Node& s, const Node& set, const Mat4& m) {
    scene::DrawnShape d{.node = &s};
    TriangleMesh& mesh = d.surface.mesh;
    const NodePtr coord = vrml97_geometry::node_of(set, "coord");
    const FieldValue* points = coord ? coord->value("point") : nullptr;
    const FieldValue* index = set.value("coordIndex");
    if (!points || !index) return d;
    const NodePtr color = vrml97_geometry::node_of(set, "color");
    const FieldValue* colors = color ? color->value("color") : nullptr;
    const std::size_t stride = color && color->type == "ColorRGBA" ? 4 : 3;
    const FieldValue* color_index = set.value("colorIndex");
    const bool per_vertex = int_of(set, "colorPerVertex", 1) != 0;
    Vec3 plain{1, 1, 1};
    float opacity = 1;
    if (const NodePtr a = vrml97_geometry::node_of(s, "appearance"))
      if (const NodePtr mat = vrml97_geometry::node_of(*a, "material")) {
        plain = vec3_of(*mat, "emissiveColor", {});
        opacity = 1 - std::clamp(float_of(*mat, "transparency", 0), 0.f, 1.f);
      }
    const std::size_t n = points->floats.size() / 3;
    auto color_at = [&](std::size_t i) {
      const std::size_t at = stride * i;
      return colors && at + 2 < colors->floats.size()
                 ? Vec3{colors->floats[at], colors->floats[at + 1], colors->floats[at + 2]}
                 : plain;
    };
    std::size_t polyline = 0;
    bool open = false;
    for (std::size_t k = 0; k < index->ints.size(); ++k) {
      const std::int32_t i = index->ints[k];
      if (i < 0 || std::size_t(i) >= n) {  // -1 ends a polyline; a bad index too
        polyline += open;
        open = false;
        continue;
      }
      const Vec3 p = m.transform_point({points->floats[3 * std::size_t(i)],
                                        points->floats[3 * std::size_t(i) + 1],
                                        points->floats[3 * std::size_t(i) + 2]});
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw DataError("a coordinate is not finite (after its transforms)");
      const bool indexed = color_index && k < color_index->ints.size();
      const std::size_t c =
          per_vertex ? (indexed ? std::size_t(std::max(color_index->ints[k], 0)) : std::size_t(i))
                     : (color_index && polyline < color_index->ints.size()
                            ? std::size_t(std::max(color_index->ints[polyline], 0))
                            : polyline);
      if (open)
        mesh.lines.push_back(
            {std::uint32_t(mesh.positions.size() - 1), std::uint32_t(mesh.positions.size())});
      mesh.positions.push_back(p);
      mesh.colors.push_back(color_at(c));
      d.surface.opacity.push_back(opacity);
      open = true;
    }
    return d;
  }

  // The shape appended last (from `vertices`, `triangles` on) taken out of
  // the mesh as a shape of its own, its texture as a Texture2 node.
  scene::DrawnShape take_shape(const Node& s, std::size_t vertices, std::size_t triangles,
                               std::uint32_t texture) {
    auto& flat = out_.flat;
    scene::DrawnShape d{.node = &s};
    TriangleMesh& mesh = d.surface.mesh;
    auto tail = [](auto& from, std::size_t at, auto& to) {
      to.assign(from.begin() + std::ptrdiff_t(at), from.end());
      from.resize(at);
    };
    tail(flat.mesh.positions, vertices, mesh.positions);
    tail(flat.mesh.colors, vertices, mesh.colors);
    tail(flat.mesh.texcoords, vertices, mesh.texcoords);
    tail(flat.opacity, vertices, d.surface.opacity);
    tail(flat.mesh.triangles, triangles, mesh.triangles);
    flat.mesh.materials.resize(triangles);
    const auto base = std::uint32_t(vertices);
    for (Triangle& t : mesh.triangles) t = {t[0] - base, t[1] - base, t[2] - base};
    if (texture == scene::kUntextured) {
      mesh.texcoords.clear();
    } else {
      auto& nodes = collect_->textures;
      if (nodes.size() <= texture) nodes.resize(flat.textures.size());
      NodePtr& t = nodes[texture];
      if (!t) {
        const scene::SceneTexture& from = flat.textures[texture];
        t = scene::make_node("Texture2");
        t->set("filename", scene::make_string(from.filename));
        t->set("wrapS", scene::make_enum(from.repeat_s ? "REPEAT" : "CLAMP"));
        t->set("wrapT", scene::make_enum(from.repeat_t ? "REPEAT" : "CLAMP"));
      }
      d.surface.texture = t.get();
    }
    return d;
  }

  struct Look {
    Vec3 diffuse = kDefaultGrey;
    float opacity = 1;
    bool material = false;
    std::uint32_t texture = scene::kUntextured;  ///< index into FlatScene::textures
    Mat4 texture_transform;                      ///< the Appearance's TextureTransform
  };

  Look appearance_of(const Node& s) {
    Look look;
    const NodePtr a = vrml97_geometry::node_of(s, "appearance");
    if (!a) return look;
    const NodePtr tex = vrml97_geometry::node_of(*a, "texture");
    if (tex && tex->type == "ImageTexture") look.texture = texture(*tex);
    if (const NodePtr tt = vrml97_geometry::node_of(*a, "textureTransform"))
      if (tt->type == "TextureTransform") look.texture_transform = texture_transform_of(*tt);
    const NodePtr mat = vrml97_geometry::node_of(*a, "material");
    if (!mat) return look;
    look.material = true;
    look.diffuse = vec3_of(*mat, "diffuseColor", look.diffuse);
    look.opacity = 1 - std::clamp(float_of(*mat, "transparency", 0), 0.f, 1.f);
    return look;
  }

  // An ImageTexture's first URL (a file relative to the scene's folder, or
  // a data: URI), once per node.
  std::uint32_t texture(const Node& t) {
    auto [it, fresh] = texture_of_.try_emplace(&t, scene::kUntextured);
    if (!fresh) return it->second;
    const scene::Field* url = t.find("url");
    std::string file;
    if (url && !url->is_raw && !url->value.strings.empty()) file = url->value.strings[0];
    if (file.empty()) return it->second;
    auto repeat = [&](const char* field) {
      const scene::Field* f = t.find(field);
      return !f || (f->is_raw ? f->raw.find("FALSE") == std::string::npos
                              : f->value.ints.empty() || f->value.ints[0]);
    };
    it->second = std::uint32_t(out_.flat.textures.size());
    scene::SceneTexture texture{
        .repeat_s = repeat("repeatS"), .repeat_t = repeat("repeatT"), .line = t.first_line};
    // An image in a data: URI comes as its bytes (as a glTF file's embedded one).
    if (auto bytes = decode_data_uri(file))
      texture.encoded = std::move(*bytes);
    else
      texture.filename = file;
    out_.flat.textures.push_back(std::move(texture));
    return it->second;
  }

  // Where a shape's per-vertex colours and texture coordinates come from.
  struct Attributes {
    const FieldValue* colors = nullptr;  ///< the Color / ColorRGBA node's
    std::size_t stride = 3;              ///< floats a colour
    const FieldValue* texcoords = nullptr;
    /// The nodes they are held by: an ElevationGrid's texture coordinates
    /// are made by the reader, which is gone when they are used.
    NodePtr color_node, texcoord_node;
  };

  // Appends a shape's mesh in world space, with its colours (the Color
  // node's where the corner has one, else the material's) and, when it is
  // textured, its texture coordinates.
  void append(const vrml97_geometry::ShapeMesh& piece, const Mat4& m, const Look& look,
              const Attributes& from) {
    auto& mesh = out_.flat.mesh;
    const auto base = std::uint32_t(mesh.positions.size());
    for (const Vec3& p : piece.mesh.positions) {
      const Vec3 q = m.transform_point(p);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        throw DataError("a coordinate is not finite (after its transforms)");
      mesh.positions.push_back(q);
    }
    for (const Triangle& t : piece.mesh.triangles) {
      mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
      mesh.materials.push_back(look.texture);
    }
    has_color_ = has_color_ || look.material || from.colors;
    const std::vector<Vec2> uv = texture_coordinates(piece, from.texcoords);
    for (std::size_t v = 0; v < piece.mesh.positions.size(); ++v) {
      Vec3 c = look.diffuse;
      if (from.colors && v < piece.vertex_corner.size()) {
        const std::uint32_t i = piece.vertex_corner[v][3];
        const std::size_t at = from.stride * std::size_t(i);
        if (i != kNone && at + 2 < from.colors->floats.size())
          c = {from.colors->floats[at], from.colors->floats[at + 1], from.colors->floats[at + 2]};
      }
      mesh.colors.push_back(c);
      Vec2 t = look.texture == scene::kUntextured ? Vec2{} : uv[v];
      if (!(look.texture_transform == Mat4{})) {
        const Vec3 q = look.texture_transform.transform_point({t.x, t.y, 0});
        t = {q.x, q.y};
      }
      mesh.texcoords.push_back(t);
      out_.flat.opacity.push_back(look.opacity);
    }
  }

  // Line segments (line_shape's) into the one mesh; `coloured`: by a Color
  // node or a Material (else the scene's colours may be left out).
  void append_lines(const scene::ShapeSurface& lines, bool coloured) {
    auto& mesh = out_.flat.mesh;
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), lines.mesh.positions.begin(),
                          lines.mesh.positions.end());
    mesh.colors.insert(mesh.colors.end(), lines.mesh.colors.begin(), lines.mesh.colors.end());
    mesh.texcoords.resize(mesh.positions.size());
    out_.flat.opacity.insert(out_.flat.opacity.end(), lines.opacity.begin(), lines.opacity.end());
    for (const Segment& l : lines.mesh.lines) mesh.lines.push_back({l[0] + base, l[1] + base});
    has_color_ = has_color_ || coloured;
  }

  // A shape's texture coordinates: its TextureCoordinate node's, a
  // primitive's own, or else VRML97's default mapping (s along the bounding
  // box's longest side, t along the second, both in units of the longest).
  static std::vector<Vec2> texture_coordinates(const vrml97_geometry::ShapeMesh& piece,
                                               const FieldValue* points) {
    const std::size_t n = piece.mesh.positions.size();
    if (piece.mesh.texcoords.size() == n) return piece.mesh.texcoords;
    std::vector<Vec2> uv(n);
    if (points) {
      for (std::size_t v = 0; v < n && v < piece.vertex_corner.size(); ++v) {
        const std::uint32_t i = piece.vertex_corner[v][2];
        if (i != kNone && 2 * std::size_t(i) + 1 < points->floats.size())
          uv[v] = {points->floats[2 * i], points->floats[2 * i + 1]};
      }
      return uv;
    }
    const Box3 box = piece.mesh.bounds();
    const Vec3 size = box.size();
    int axis[3] = {0, 1, 2};
    std::sort(axis, axis + 3, [&](int a, int b) { return size[a] > size[b]; });
    const float longest = size[axis[0]] > 0 ? size[axis[0]] : 1;
    for (std::size_t v = 0; v < n; ++v) {
      const Vec3 p = piece.mesh.positions[v] - box.lo;
      uv[v] = {p[axis[0]] / longest, p[axis[1]] / longest};
    }
    return uv;
  }

  const FlattenVrml97Options& options_;
  Log& log_;
  Vrml97LodShapes* collect_ = nullptr;
  std::vector<scene::DrawnShape>* sink_ = nullptr;  ///< where a collected shape goes
  FlatVrml97 out_;
  bool has_color_ = false;
  std::unordered_map<const Node*, std::uint32_t> texture_of_;
};

}  // namespace

std::optional<float> viewpoint_field_of_view(const scene::Scene& scene) {
  std::unordered_set<const Node*> seen;
  std::function<const Node*(const NodePtr&)> first = [&](const NodePtr& n) -> const Node* {
    if (!n || n->statement || !seen.insert(n.get()).second) return nullptr;
    if (n->type == "Viewpoint") return n.get();
    for (const auto& f : n->fields)
      for (const auto& c : f.value.nodes)
        if (const Node* v = first(c)) return v;
    return nullptr;
  };
  for (const NodePtr& r : scene.roots)
    if (const Node* v = first(r)) {
      const float fov = float_of(*v, "fieldOfView", 0);
      return fov > 0 && fov < 3.1f ? fov : kDefaultFieldOfView;
    }
  return std::nullopt;
}

FlatVrml97 flatten_vrml97(const scene::Scene& scene, const FlattenVrml97Options& options,
                          Log& log) {
  Flattener f(options, log);
  for (const NodePtr& root : scene.roots) f.node(root, Mat4{}, 0);
  return f.result();
}

Vrml97LodShapes vrml97_lod_shapes(const scene::Scene& scene, Log& log) {
  Vrml97LodShapes out;
  const FlattenVrml97Options options;
  Flattener f(options, log);
  f.collect(out);
  for (const NodePtr& root : scene.roots) f.node(root, Mat4{}, 0);
  out.skipped = f.result().skipped;
  return out;
}

}  // namespace lodforge
