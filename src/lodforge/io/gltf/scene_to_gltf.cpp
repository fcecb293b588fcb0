// A VRML 1.0 / Inventor scene graph to glTF: the world-space shapes each LOD
// node's children draw (scene::collect_lod_shapes), with their appearance,
// become a node per child, the first one carrying MSFT_lod.
#include "lodforge/io/gltf/scene_to_gltf.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/mesh/vertex_normals.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/lod_shapes.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/shape_mesh.h"

namespace lodforge::gltf {
namespace {

using scene::DrawnShape;
using scene::LodGroup;
using scene::Node;
using scene::ShapeSurface;
using tinygltf::Value;

constexpr double kDefaultCameraAngle = 0.7853981633974483;  // VRML's pi/4

// Smooth vertex normals; glTF wants unit length for every vertex, also one
// that only degenerate triangles (or none) use: it gets +z.
std::vector<Vec3> unit_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> n = angle_weighted_normals(mesh);
  for (Vec3& v : n)
    if (!is_finite(v) || std::abs(length(v) - 1.0f) > 1e-3f) v = {0, 0, 1};
  return n;
}

// Builds the model: one buffer, views and accessors appended as they come.
class ModelBuilder {
 public:
  explicit ModelBuilder(std::string base_dir) : base_dir_(std::move(base_dir)) {
    model_.asset.version = "2.0";
    model_.asset.generator = "lodforge";
    model_.buffers.emplace_back();
    model_.scenes.emplace_back();
    model_.defaultScene = 0;
  }

  // A node drawing `shapes` (nullptr mesh when they draw nothing); -1 when
  // there is nothing to draw.
  int add_node(const std::vector<DrawnShape>& shapes, const std::string& name) {
    tinygltf::Mesh mesh;
    for (const DrawnShape& s : shapes) add_primitives(mesh, s.surface);
    if (mesh.primitives.empty()) return -1;
    mesh.name = name;
    tinygltf::Node node;
    node.name = name;
    node.mesh = int(model_.meshes.size());
    model_.meshes.push_back(std::move(mesh));
    model_.nodes.push_back(std::move(node));
    return int(model_.nodes.size() - 1);
  }
  void show(int node) { model_.scenes[0].nodes.push_back(node); }
  tinygltf::Node& node(int i) { return model_.nodes[std::size_t(i)]; }
  void use_extension(const std::string& name) {
    if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), name) ==
        model_.extensionsUsed.end())
      model_.extensionsUsed.push_back(name);
  }
  tinygltf::Model take() { return std::move(model_); }
  /// Texture2 nodes whose image is inline (left out).
  std::size_t inline_images() const { return inline_images_; }
  /// Texture2 file names that name no file relative to the base folder.
  const std::vector<std::string>& missing_textures() const { return missing_; }
  /// Texture files that are no PNG or JPEG image (glTF's image formats).
  const std::vector<std::string>& unsupported_textures() const { return unsupported_; }

 private:
  template <class T>
  int add_view(const std::vector<T>& data, int target) {
    auto& bytes = model_.buffers[0].data;
    while (bytes.size() % 4) bytes.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    view.byteLength = data.size() * sizeof(T);
    view.target = target;
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    bytes.insert(bytes.end(), p, p + view.byteLength);
    model_.bufferViews.push_back(view);
    return int(model_.bufferViews.size() - 1);
  }

  // An accessor of `count` elements of `type` (floats unless indices).
  template <class T>
  int add_accessor(const std::vector<T>& data, int component, int type, std::size_t count,
                   int target) {
    tinygltf::Accessor a;
    a.bufferView = add_view(data, target);
    a.componentType = component;
    a.type = type;
    a.count = count;
    model_.accessors.push_back(std::move(a));
    return int(model_.accessors.size() - 1);
  }

  int add_positions(const std::vector<Vec3>& positions) {
    std::vector<float> flat;
    Box3 box;
    for (const Vec3& p : positions) {
      flat.insert(flat.end(), {p.x, p.y, p.z});
      box.add(p);
    }
    const int a = add_accessor(flat, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                               positions.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    model_.accessors[std::size_t(a)].minValues = {box.lo.x, box.lo.y, box.lo.z};
    model_.accessors[std::size_t(a)].maxValues = {box.hi.x, box.hi.y, box.hi.z};
    return a;
  }

  int add_vec3(const std::vector<Vec3>& values) {
    std::vector<float> flat;
    for (const Vec3& v : values) flat.insert(flat.end(), {v.x, v.y, v.z});
    return add_accessor(flat, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, values.size(),
                        TINYGLTF_TARGET_ARRAY_BUFFER);
  }

  int add_indices(const std::vector<std::uint32_t>& indices) {
    return add_accessor(indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                        indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  }

  // Colours with opacity (RGBA when some vertex is not opaque).
  int add_colors(const ShapeSurface& s, bool& transparent) {
    transparent = std::any_of(s.opacity.begin(), s.opacity.end(), [](float o) { return o < 1; });
    std::vector<float> flat;
    for (std::size_t i = 0; i < s.mesh.colors.size(); ++i) {
      const Vec3& c = s.mesh.colors[i];
      flat.insert(flat.end(), {c.x, c.y, c.z});
      if (transparent) flat.push_back(i < s.opacity.size() ? s.opacity[i] : 1.0f);
    }
    return add_accessor(flat, TINYGLTF_COMPONENT_TYPE_FLOAT,
                        transparent ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, s.mesh.colors.size(),
                        TINYGLTF_TARGET_ARRAY_BUFFER);
  }

  // glTF's texture origin is the top left, VRML's the bottom left.
  int add_texcoords(const std::vector<Vec2>& uv) {
    std::vector<float> flat;
    for (const Vec2& t : uv) flat.insert(flat.end(), {t.x, 1.0f - t.y});
    return add_accessor(flat, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, uv.size(),
                        TINYGLTF_TARGET_ARRAY_BUFFER);
  }

  // The texture of a Texture2 that names a file (inline images: -1).
  int texture_of(const Node* texture2) {
    if (!texture2) return -1;
    if (auto it = textures_.find(texture2); it != textures_.end()) return it->second;
    const scene::FieldValue* file = scene::field_or_default(*texture2, "filename");
    const std::string name = file && !file->strings.empty() ? file->strings[0] : "";
    int index = -1;
    if (name.empty()) {
      ++inline_images_;
    } else if (!readable_file(name)) {
      missing_.push_back(name);
    } else if (!png_or_jpeg(name)) {
      unsupported_.push_back(name);
    } else {
      tinygltf::Image image;
      image.uri = uri_of(name);
      model_.images.push_back(std::move(image));
      tinygltf::Sampler sampler;
      auto wrap = [&](const char* field) {
        const scene::FieldValue* v = scene::field_or_default(*texture2, field);
        return v && !v->strings.empty() && v->strings[0] == "CLAMP"
                   ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
                   : TINYGLTF_TEXTURE_WRAP_REPEAT;
      };
      sampler.wrapS = wrap("wrapS");
      sampler.wrapT = wrap("wrapT");
      model_.samplers.push_back(std::move(sampler));
      tinygltf::Texture texture;
      texture.source = int(model_.images.size() - 1);
      texture.sampler = int(model_.samplers.size() - 1);
      model_.textures.push_back(std::move(texture));
      index = int(model_.textures.size() - 1);
    }
    textures_[texture2] = index;
    return index;
  }

  // A diffuse-looking material: the colour comes from the vertices (or the
  // texture), both sides lit.
  int material_of(int texture, bool transparent) {
    const auto key = std::make_pair(texture, transparent);
    if (auto it = materials_.find(key); it != materials_.end()) return it->second;
    tinygltf::Material m;
    m.pbrMetallicRoughness.baseColorFactor = {1, 1, 1, 1};
    m.pbrMetallicRoughness.metallicFactor = 0;
    m.pbrMetallicRoughness.roughnessFactor = 1;
    m.pbrMetallicRoughness.baseColorTexture.index = texture;
    m.doubleSided = true;
    if (transparent) m.alphaMode = "BLEND";
    model_.materials.push_back(std::move(m));
    return materials_[key] = int(model_.materials.size() - 1);
  }

  void add_primitives(tinygltf::Mesh& mesh, const ShapeSurface& s) {
    if (s.mesh.positions.empty()) return;
    if (!s.mesh.triangles.empty()) {
      tinygltf::Primitive p;
      p.mode = TINYGLTF_MODE_TRIANGLES;
      p.attributes["POSITION"] = add_positions(s.mesh.positions);
      p.attributes["NORMAL"] = add_vec3(unit_normals(s.mesh));
      bool transparent = false;
      if (s.mesh.has_colors()) p.attributes["COLOR_0"] = add_colors(s, transparent);
      const int texture = s.mesh.has_texcoords() ? texture_of(s.texture) : -1;
      if (texture >= 0) p.attributes["TEXCOORD_0"] = add_texcoords(s.mesh.texcoords);
      std::vector<std::uint32_t> indices;
      for (const auto& t : s.mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
      p.indices = add_indices(indices);
      p.material = material_of(texture, transparent);
      mesh.primitives.push_back(std::move(p));
    }
    if (!s.mesh.lines.empty()) {
      tinygltf::Primitive p;
      p.mode = TINYGLTF_MODE_LINE;
      p.attributes["POSITION"] = add_positions(s.mesh.positions);
      bool transparent = false;
      if (s.mesh.has_colors()) p.attributes["COLOR_0"] = add_colors(s, transparent);
      std::vector<std::uint32_t> indices;
      for (const auto& l : s.mesh.lines) indices.insert(indices.end(), {l[0], l[1]});
      p.indices = add_indices(indices);
      p.material = material_of(-1, transparent);
      mesh.primitives.push_back(std::move(p));
    }
  }

  tinygltf::Model model_;
  std::map<const Node*, int> textures_;
  std::map<std::pair<int, bool>, int> materials_;
  std::size_t inline_images_ = 0;
  std::vector<std::string> missing_, unsupported_;
  std::string base_dir_;

  // True if the file starts as a PNG or a JPEG image does.
  bool png_or_jpeg(const std::string& name) const {
    const std::string head =
        read_head((std::filesystem::path(base_dir_) / std::filesystem::path(name)).string(), 4);
    return head.starts_with("\x89PNG") || head.starts_with("\xFF\xD8\xFF");
  }

  // A relative file name of an existing file under the base folder (a glTF
  // URI may not be absolute, and a missing image makes the file invalid).
  bool readable_file(const std::string& name) const {
    const std::filesystem::path p(name);
    std::error_code ec;
    return p.is_relative() && name.find(':') == std::string::npos &&
           std::filesystem::is_regular_file(std::filesystem::path(base_dir_) / p, ec);
  }
  // A file name as a URI reference: characters outside RFC 3986's
  // unreserved set and '/' percent-encoded.
  static std::string uri_of(const std::string& name) {
    std::string out;
    for (unsigned char c : name) {
      if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/')
        out.push_back(char(c));
      else
        out += fmt::format("%{:02X}", c);
    }
    return out;
  }
};

double camera_angle(const SceneToGltfOptions& options, const Node* camera) {
  if (options.camera_angle > 0) return options.camera_angle;
  if (camera)
    if (const scene::FieldValue* h = scene::field_or_default(*camera, "heightAngle"))
      if (!h->floats.empty() && h->floats[0] > 0 && h->floats[0] < 3.14159f) return h->floats[0];
  return kDefaultCameraAngle;
}

// The bounding sphere of a LOD's first child (about its box centre).
double radius_of(const std::vector<DrawnShape>& shapes) {
  std::vector<Vec3> points;
  for (const auto& s : shapes)
    points.insert(points.end(), s.surface.mesh.positions.begin(), s.surface.mesh.positions.end());
  return box_centred_sphere(points).radius;
}

// One LOD occurrence: its first child's node, MSFT_lod naming the nodes of
// the other children that draw something, coverages and ranges in extras.
void add_lod(ModelBuilder& b, const LodGroup& g, double angle, std::size_t number) {
  const std::string name = g.lod->name.empty() ? fmt::format("LOD{}", number) : g.lod->name;
  int base = b.add_node(g.levels[0], name);
  if (base < 0) return;  // nothing drawn up close: nothing to switch
  b.show(base);
  const scene::FieldValue* range = scene::field_or_default(*g.lod, "range");
  const std::vector<float> ranges = range ? range->floats : std::vector<float>{};
  const double r = radius_of(g.levels[0]);
  const double t = std::tan(angle / 2);
  Value::Array ids, coverage, levels;
  levels.emplace_back(Value::Object{{"switch_distance", Value(0.0)}});
  for (std::size_t i = 1; i < g.levels.size() && i - 1 < ranges.size(); ++i) {
    const double d = ranges[i - 1];
    const int n = b.add_node(g.levels[i], fmt::format("{}_lod{}", name, i));
    levels.emplace_back(Value::Object{{"switch_distance", Value(d)}});
    coverage.emplace_back(d > 0 ? r / (d * t) : 1.0);
    if (n < 0) break;  // an empty child: nothing is drawn from here on
    ids.emplace_back(n);
  }
  if (ids.empty() && coverage.empty()) return;
  if (!ids.empty()) {
    b.use_extension("MSFT_lod");
    b.node(base).extensions["MSFT_lod"] = Value(Value::Object{{"ids", Value(ids)}});
  }
  b.node(base).extras =
      Value(Value::Object{{"MSFT_screencoverage", Value(coverage)},
                          {"lodforge_lod", Value(Value::Object{{"levels", Value(levels)},
                                                               {"bounding_radius", Value(r)},
                                                               {"camera_angle", Value(angle)}})}});
}

}  // namespace

GltfScene scene_to_gltf(const scene::Scene& s, const SceneToGltfOptions& options, Log& log) {
  return lod_shapes_to_gltf(scene::collect_lod_shapes(s, log), options, log);
}

GltfScene lod_shapes_to_gltf(const scene::LodShapes& c, const SceneToGltfOptions& options,
                             Log& log) {
  const double angle = camera_angle(options, c.camera);
  ModelBuilder b(options.base_dir.empty() ? "." : options.base_dir);
  for (std::size_t i = 0; i < c.plain.size(); ++i) {
    const int n = b.add_node({c.plain[i]}, fmt::format("shape{}", i));
    if (n >= 0) b.show(n);
  }
  std::size_t number = 0;
  for (const auto& [key, group] : c.lods) add_lod(b, group, angle, number++);
  const std::size_t inline_images = b.inline_images();
  if (inline_images)
    log.warn(LogCategory::kTexCoord,
             fmt::format("{} Texture2 images are given inline in the file; the glTF output "
                         "leaves them out (their shapes keep their colours)",
                         inline_images));
  for (const std::string& name : b.unsupported_textures())
    log.warn(LogCategory::kTexCoord,
             fmt::format("texture file \"{}\" is no PNG or JPEG image, the formats glTF "
                         "takes; the glTF output leaves it out (its shapes keep their colours)",
                         name));
  for (const std::string& name : b.missing_textures())
    log.warn(LogCategory::kTexCoord,
             fmt::format("Texture2 file \"{}\" is not a file beside the scene; the glTF output "
                         "leaves it out (its shapes keep their colours)",
                         name));
  GltfScene out;
  out.model = b.take();
  // A scene that draws nothing: no buffer (glTF forbids an empty one), and a
  // named scene (an empty one would be written as null).
  if (out.model.buffers[0].data.empty()) out.model.buffers.clear();
  out.model.scenes[0].name = "scene";
  out.base_dir = options.base_dir;
  return out;
}

}  // namespace lodforge::gltf
