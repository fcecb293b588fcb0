#include "lodforge/io/gltf/gltf_to_vrml97.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "lodforge/core/data_uri.h"
#include "lodforge/core/error.h"
#include "lodforge/io/gltf/accessor_data.h"
#include "lodforge/io/gltf/node_matrices.h"
#include "lodforge/io/gltf/primitive_mesh.h"
#include "lodforge/io/gltf/scene_mesh.h"
#include "lodforge/scene/flatten_scene.h"

namespace lodforge::gltf {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::make_node;
using scene::make_node_value;
using scene::NodePtr;

// Deeper Transforms than this would not read back: VRML readers (ours
// included) stop at 256 levels of nesting.
constexpr std::size_t kMaxDepth = 200;

// The classic encoding's keywords (VRML97's and X3D's), which a DEF name
// must not be.
const std::set<std::string, std::less<>> kKeywords = {
    "AS",        "COMPONENT",    "DEF",   "EXPORT",         "EXTERNPROTO", "FALSE",
    "IMPORT",    "IS",           "META",  "NULL",           "PROFILE",     "PROTO",
    "ROUTE",     "TO",           "TRUE",  "UNIT",           "USE",         "eventIn",
    "eventOut",  "exposedField", "field", "initializeOnly", "inputOnly",   "inputOutput",
    "outputOnly"};

FieldValue points(FieldKind kind, const std::vector<Vec3>& values) {
  std::vector<float> flat;
  flat.reserve(3 * values.size());
  for (const Vec3& p : values) flat.insert(flat.end(), {p.x, p.y, p.z});
  return scene::make_floats(kind, true, std::move(flat));
}

FieldValue colour(double r, double g, double b) {
  return scene::make_floats(FieldKind::kColor, false, {float(r), float(g), float(b)});
}

// glTF's TRS of a node: translation, rotation (quaternion x, y, z, w) and
// scale; a matrix decomposed (`sheared` when its axes are not orthogonal).
struct Trs {
  std::array<double, 3> t{0, 0, 0};
  std::array<double, 4> q{0, 0, 0, 1};
  std::array<double, 3> s{1, 1, 1};
  bool sheared = false;
};

// The unit quaternion of rotation matrix `r` (r[row][col]).
std::array<double, 4> quaternion(const std::array<std::array<double, 3>, 3>& r) {
  const double trace = r[0][0] + r[1][1] + r[2][2];
  std::array<double, 4> q;
  if (trace > 0) {
    const double k = 0.5 / std::sqrt(trace + 1);
    q = {(r[2][1] - r[1][2]) * k, (r[0][2] - r[2][0]) * k, (r[1][0] - r[0][1]) * k, 0.25 / k};
  } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
    const double k = 2 * std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]);
    q = {0.25 * k, (r[0][1] + r[1][0]) / k, (r[0][2] + r[2][0]) / k, (r[2][1] - r[1][2]) / k};
  } else if (r[1][1] > r[2][2]) {
    const double k = 2 * std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]);
    q = {(r[0][1] + r[1][0]) / k, 0.25 * k, (r[1][2] + r[2][1]) / k, (r[0][2] - r[2][0]) / k};
  } else {
    const double k = 2 * std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]);
    q = {(r[0][2] + r[2][0]) / k, (r[1][2] + r[2][1]) / k, 0.25 * k, (r[1][0] - r[0][1]) / k};
  }
  return q;
}

// A column-major matrix as translation, rotation and scale (a mirroring
// matrix gets a negative x scale).
Trs decompose(const std::vector<double>& m) {
  Trs out;
  out.t = {m[12], m[13], m[14]};
  std::array<std::array<double, 3>, 3> axis;  // axis[c] = column c
  for (int c = 0; c < 3; ++c) {
    axis[std::size_t(c)] = {m[std::size_t(4 * c)], m[std::size_t(4 * c + 1)],
                            m[std::size_t(4 * c + 2)]};
    const auto& a = axis[std::size_t(c)];
    out.s[std::size_t(c)] = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  const auto& [x, y, z] = axis;
  const double det = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
                     x[2] * (y[0] * z[1] - y[1] * z[0]);
  if (det < 0) out.s[0] = -out.s[0];
  if (out.s[0] == 0 || out.s[1] == 0 || out.s[2] == 0) return out;  // no rotation to find
  std::array<std::array<double, 3>, 3> r;
  for (std::size_t row = 0; row < 3; ++row)
    for (std::size_t c = 0; c < 3; ++c) r[row][c] = axis[c][row] / out.s[c];
  auto dot = [&](std::size_t a, std::size_t b) {
    return r[0][a] * r[0][b] + r[1][a] * r[1][b] + r[2][a] * r[2][b];
  };
  out.sheared =
      std::abs(dot(0, 1)) > 1e-3 || std::abs(dot(0, 2)) > 1e-3 || std::abs(dot(1, 2)) > 1e-3;
  out.q = quaternion(r);
  return out;
}

Trs trs_of(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return decompose(n.matrix);
  Trs out;
  if (n.translation.size() == 3) std::copy_n(n.translation.begin(), 3, out.t.begin());
  if (n.rotation.size() == 4) std::copy_n(n.rotation.begin(), 4, out.q.begin());
  if (n.scale.size() == 3) std::copy_n(n.scale.begin(), 3, out.s.begin());
  return out;
}

// VRML's axis-angle rotation of quaternion `q`; the angle in [0, pi].
std::array<float, 4> axis_angle(std::array<double, 4> q) {
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(norm > 0)) return {0, 0, 1, 0};
  for (double& v : q) v /= norm * (q[3] < 0 ? -1 : 1);
  const double sine = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  if (sine < 1e-12) return {0, 0, 1, 0};
  return {float(q[0] / sine), float(q[1] / sine), float(q[2] / sine),
          float(2 * std::atan2(sine, q[3]))};
}

const tinygltf::Material* material_of(const tinygltf::Model& model, int m) {
  return m >= 0 && std::size_t(m) < model.materials.size() ? &model.materials[std::size_t(m)]
                                                           : nullptr;
}

// Builds the VRML97 nodes, one Appearance per glTF material (and kind of
// geometry), one ImageTexture per glTF texture, the Shapes of a mesh once.
class Converter {
 public:
  Converter(const tinygltf::Model& model, Log& log) : model_(model), log_(log) {}

  scene::Scene run() {
    scene::Scene out;
    out.header = "#VRML V2.0 utf8";
    // Nodes form trees (read_gltf checks it): an explicit stack visits each
    // once, from the roots down.
    std::vector<NodePtr> made(model_.nodes.size());
    const std::vector<int> roots = shown_roots(model_);
    std::vector<std::pair<int, std::size_t>> stack;  // node, depth
    for (int r : roots) stack.emplace_back(r, 1);
    std::vector<int> order;
    while (!stack.empty()) {
      const auto [i, depth] = stack.back();
      stack.pop_back();
      if (made[std::size_t(i)]) continue;  // a root listed twice
      if (depth > kMaxDepth)
        throw DataError(fmt::format(
            "node {}: the node hierarchy is deeper than {} levels, more than a VRML97 / X3D "
            "reader accepts",
            i, kMaxDepth));
      made[std::size_t(i)] = transform(model_.nodes[std::size_t(i)]);
      order.push_back(i);
      for (int c : model_.nodes[std::size_t(i)].children) stack.emplace_back(c, depth + 1);
    }
    for (int i : order) {
      const tinygltf::Node& n = model_.nodes[std::size_t(i)];
      std::vector<NodePtr> children = contents(n);
      for (int c : n.children) children.push_back(made[std::size_t(c)]);
      if (!children.empty())
        made[std::size_t(i)]->set("children", scene::make_nodes_value(std::move(children)));
    }
    for (int r : roots)
      if (std::find(out.roots.begin(), out.roots.end(), made[std::size_t(r)]) == out.roots.end())
        out.roots.push_back(made[std::size_t(r)]);
    warn_left_out();
    return out;
  }

 private:
  // A node's Transform, without its children.
  NodePtr transform(const tinygltf::Node& n) {
    auto t = make_node("Transform");
    t->name = def_name(n.name);
    const Trs trs = trs_of(n);
    if (trs.sheared) ++left_out_["the shear of node matrices (nearest rotation and scale kept)"];
    if (trs.t != std::array<double, 3>{0, 0, 0})
      t->set("translation",
             scene::make_floats(FieldKind::kVec3f, false,
                                {float(trs.t[0]), float(trs.t[1]), float(trs.t[2])}));
    const auto r = axis_angle(trs.q);
    if (r[3] != 0)
      t->set("rotation", scene::make_floats(FieldKind::kRotation, false, {r[0], r[1], r[2], r[3]}));
    if (trs.s != std::array<double, 3>{1, 1, 1})
      t->set("scale", scene::make_floats(FieldKind::kVec3f, false,
                                         {float(trs.s[0]), float(trs.s[1]), float(trs.s[2])}));
    return t;
  }

  // What a node holds besides its child nodes: its mesh's Shapes and its
  // camera's Viewpoint.
  std::vector<NodePtr> contents(const tinygltf::Node& n) {
    if (n.skin >= 0) ++left_out_["skins (their meshes written in the bind pose)"];
    if (n.extensions.count("MSFT_lod")) ++left_out_["MSFT_lod levels (level 0 written)"];
    if (n.extensions.count("KHR_lights_punctual")) ++left_out_["lights (KHR_lights_punctual)"];
    std::vector<NodePtr> out;
    if (n.mesh >= 0 && std::size_t(n.mesh) < model_.meshes.size()) out = shapes(n.mesh);
    if (n.camera >= 0 && std::size_t(n.camera) < model_.cameras.size()) {
      const tinygltf::Camera& c = model_.cameras[std::size_t(n.camera)];
      if (c.type == "perspective") {
        auto v = make_node("Viewpoint");
        v->set("position", scene::make_floats(FieldKind::kVec3f, false, {0, 0, 0}));
        v->set("fieldOfView", scene::make_float(float(c.perspective.yfov)));
        if (!c.name.empty()) v->set("description", scene::make_string(c.name));
        out.push_back(std::move(v));
      } else {
        ++left_out_["orthographic cameras"];
      }
    }
    return out;
  }

  // The Shapes of mesh `m`, made once.
  const std::vector<NodePtr>& shapes(int m) {
    auto [it, added] = meshes_.try_emplace(m);
    if (!added) return it->second;
    for (const tinygltf::Primitive& p : model_.meshes[std::size_t(m)].primitives) {
      if (!p.targets.empty()) ++left_out_["morph targets (the base shape written)"];
      if (NodePtr s = shape(p, m)) it->second.push_back(std::move(s));
    }
    return it->second;
  }

  NodePtr shape(const tinygltf::Primitive& p, int mesh) {
    TriangleMesh part = primitive_mesh(model_, p, mesh);
    if (part.positions.empty()) return nullptr;
    const bool faces = !part.triangles.empty();
    const bool lines = !faces && !part.lines.empty();
    auto coord = make_node("Coordinate");
    coord->set("point", points(FieldKind::kVec3f, part.positions));
    NodePtr g = make_node(faces ? "IndexedFaceSet" : lines ? "IndexedLineSet" : "PointSet");
    g->set("coord", make_node_value(std::move(coord)));
    std::vector<std::int32_t> index;
    for (const Triangle& t : part.triangles)
      index.insert(index.end(), {std::int32_t(t[0]), std::int32_t(t[1]), std::int32_t(t[2]), -1});
    if (lines)
      for (const Segment& s : part.lines)
        index.insert(index.end(), {std::int32_t(s[0]), std::int32_t(s[1]), -1});
    if (!index.empty()) g->set("coordIndex", scene::make_longs(std::move(index)));
    if (p.attributes.count("COLOR_0")) {
      add_colors(model_, p, part);
      auto c = make_node("Color");
      c->set("color", points(FieldKind::kColor, part.colors));
      g->set("color", make_node_value(std::move(c)));
    }
    bool textured = false;
    if (faces) {
      add_normals(p, part.positions.size(), *g);
      add_texture(model_, p, part);
      textured = part.materials.front() != scene::kUntextured;
      if (textured) {
        std::vector<float> flat;
        for (const Vec2& uv : part.texcoords) flat.insert(flat.end(), {uv.x, uv.y});
        auto tc = make_node("TextureCoordinate");
        tc->set("point", scene::make_floats(FieldKind::kVec2f, true, std::move(flat)));
        g->set("texCoord", make_node_value(std::move(tc)));
      }
      const tinygltf::Material* m = material_of(model_, p.material);
      if (m && m->doubleSided) g->set("solid", scene::make_bool(false));
    }
    auto s = make_node("Shape");
    s->set("appearance", make_node_value(appearance(p.material, textured, !faces)));
    s->set("geometry", make_node_value(std::move(g)));
    return s;
  }

  // The primitive's NORMALs as the face set's Normal node (none without
  // them: the face set is then drawn flat, as glTF says).
  void add_normals(const tinygltf::Primitive& p, std::size_t vertices, scene::Node& g) {
    const auto n = p.attributes.find("NORMAL");
    if (n == p.attributes.end()) return;
    const AccessorValues v = read_accessor(model_, n->second);
    if (v.components != 3 || v.count != vertices) return;
    std::vector<float> flat(v.values.begin(), v.values.end());
    auto normal = make_node("Normal");
    normal->set("vector", scene::make_floats(FieldKind::kVec3f, true, std::move(flat)));
    g.set("normal", make_node_value(std::move(normal)));
  }

  // The Appearance of material `m` (-1: glTF's default, white) for faces
  // (lit) or for lines and points (`unlit`: drawn in the emissive colour).
  NodePtr appearance(int m, bool textured, bool unlit) {
    const auto key = std::make_tuple(m, textured, unlit);
    if (auto it = appearances_.find(key); it != appearances_.end()) return it->second;
    const tinygltf::Material* material = material_of(model_, m);
    std::vector<double> base{1, 1, 1, 1};
    if (material && material->pbrMetallicRoughness.baseColorFactor.size() == 4)
      base = material->pbrMetallicRoughness.baseColorFactor;
    if (material && material->extensions.count("KHR_materials_unlit")) unlit = true;
    auto mat = make_node("Material");
    if (unlit) {
      mat->set("diffuseColor", colour(0, 0, 0));
      mat->set("emissiveColor", colour(base[0], base[1], base[2]));
    } else {
      mat->set("diffuseColor", colour(base[0], base[1], base[2]));
      if (material && material->emissiveFactor.size() == 3 &&
          material->emissiveFactor != std::vector<double>{0, 0, 0})
        mat->set("emissiveColor", colour(material->emissiveFactor[0], material->emissiveFactor[1],
                                         material->emissiveFactor[2]));
    }
    if (material && material->alphaMode == "BLEND" && base[3] < 1)
      mat->set("transparency", scene::make_float(float(1 - std::clamp(base[3], 0.0, 1.0))));
    if (material && (material->normalTexture.index >= 0 || material->occlusionTexture.index >= 0 ||
                     material->emissiveTexture.index >= 0 ||
                     material->pbrMetallicRoughness.metallicRoughnessTexture.index >= 0))
      ++left_out_["normal, occlusion, emissive and metallic-roughness textures (materials)"];
    auto app = make_node("Appearance");
    app->set("material", make_node_value(std::move(mat)));
    if (textured) app->set("texture", make_node_value(texture(m)));
    return appearances_[key] = app;
  }

  // The ImageTexture of material `m`'s base-colour texture.
  NodePtr texture(int m) {
    const int index = base_color_texture(model_, m)->index;
    if (auto it = textures_.find(index); it != textures_.end()) return it->second;
    const scene::SceneTexture st = material_texture(model_, m);
    auto t = make_node("ImageTexture");
    const std::string url =
        st.encoded.empty() ? st.filename : data_uri(image_mime_type(st.encoded), st.encoded);
    if (!url.empty()) t->set("url", scene::make_strings({url}));
    if (!st.repeat_s) t->set("repeatS", scene::make_bool(false));
    if (!st.repeat_t) t->set("repeatT", scene::make_bool(false));
    return textures_[index] = t;
  }

  // `name` as a DEF name no other node has: characters other than letters,
  // digits and '_' made '_', not starting with a digit, not a keyword.
  // Empty for an empty name.
  std::string def_name(const std::string& name) {
    if (name.empty()) return "";
    std::string out;
    for (unsigned char c : name) out += std::isalnum(c) || c == '_' ? char(c) : '_';
    if (std::isdigit(static_cast<unsigned char>(out[0]))) out = "_" + out;
    if (kKeywords.count(out)) out += '_';
    std::string unique = out;
    for (int k = 2; !names_.insert(unique).second; ++k) unique = fmt::format("{}_{}", out, k);
    return unique;
  }

  void warn_left_out() {
    if (!model_.animations.empty()) left_out_["animations"] += model_.animations.size();
    if (model_.scenes.size() > 1) left_out_["scenes but the shown one"] += model_.scenes.size() - 1;
    if (left_out_.empty()) return;
    std::string list;
    for (const auto& [what, n] : left_out_)
      list += fmt::format("{}{} ({})", list.empty() ? "" : ", ", what, n);
    log_.warn(LogCategory::kParse,
              fmt::format("glTF content a VRML97 / X3D scene cannot hold, left out: {}", list));
  }

  const tinygltf::Model& model_;
  Log& log_;
  std::map<int, std::vector<NodePtr>> meshes_;
  std::map<std::tuple<int, bool, bool>, NodePtr> appearances_;
  std::map<int, NodePtr> textures_;
  std::set<std::string> names_;
  std::map<std::string, std::size_t> left_out_;
};

}  // namespace

scene::Scene gltf_to_vrml97(const tinygltf::Model& model, Log& log) {
  return Converter(model, log).run();
}

}  // namespace lodforge::gltf
