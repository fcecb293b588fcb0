// The glTF LOD pipeline (gltf_lod.h). Levels come from choose_levels, as
// for every scene format; what is glTF's own is how they are stored (shared
// vertex sets, index accessors, level meshes and nodes) and announced
// (MSFT_lod and MSFT_screencoverage, the extensions of Microsoft's glTF
// vendor extension specifications that Babylon.js implements).
#include "lodforge/lod/gltf_lod.h"

#include <fmt/core.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/io/gltf/accessor_data.h"
#include "lodforge/io/gltf/node_matrices.h"
#include "lodforge/io/gltf/primitive_mesh.h"
#include "lodforge/io/gltf/texture_transform.h"
#include "lodforge/lod/choose_levels.h"

namespace lodforge {
namespace {

using tinygltf::Model;
using tinygltf::Value;

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

bool is_triangles(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

std::size_t round4(std::size_t n) {
  return (n + 3) / 4 * 4;
}

// New buffer views, all in one buffer that gltf_lod appends to the model.
class BufferAppender {
 public:
  explicit BufferAppender(Model& m) : m_(m), buffer_(int(m.buffers.size())) {
    m_.buffers.emplace_back();
  }
  int add_view(const std::vector<unsigned char>& bytes, int target, std::size_t stride) {
    auto& data = m_.buffers[std::size_t(buffer_)].data;
    data.resize(round4(data.size()), 0);
    tinygltf::BufferView v;
    v.buffer = buffer_;
    v.byteOffset = data.size();
    v.byteLength = bytes.size();
    v.byteStride = stride;
    v.target = target;
    data.insert(data.end(), bytes.begin(), bytes.end());
    m_.bufferViews.push_back(std::move(v));
    return int(m_.bufferViews.size() - 1);
  }
  // A buffer nothing was added to is removed (a glTF buffer is never empty).
  void finish() {
    if (m_.buffers[std::size_t(buffer_)].data.empty()) m_.buffers.pop_back();
  }

 private:
  Model& m_;
  int buffer_;
};

// Bounding radius about the box centre, as the VRML pipeline takes it.
double bounding_radius(const std::vector<Vec3>& points) {
  return box_centred_sphere(points).radius;
}

double node_scale(const gltf::NodePlacement& p) {
  const double s = p.world.max_scale();
  return s > 0 && std::isfinite(s) ? s : 1.0;
}

// One triangle primitive's levels and where they are stored.
struct PrimitiveLevels {
  int primitive = -1;
  std::vector<Vec3> positions;  ///< the input's (what else it held is not needed once simplified)
  double radius = 0;
  std::size_t triangles = 0;              ///< level 0
  std::vector<ChosenLevel> levels;        ///< levels 1..n
  std::vector<double> distances;          ///< switch distance of each, unit scale
  double vanish = 0;                      ///< where it is dropped, unit scale
  std::vector<int> index_accessors;       ///< per level 1..n (-1: not written)
  std::map<std::string, int> attributes;  ///< the shared vertex set of levels 1..n
  /// Its morph targets over that vertex set (a moved vertex takes its
  /// source vertex's displacement).
  std::vector<std::map<std::string, int>> targets;
};

// One level of a mesh: per primitive of the mesh, -1 (left out), 0 (the
// input primitive) or the primitive's level k.
struct MeshLevel {
  double distance = 0;  ///< unit scale
  std::vector<int> choice;
  std::size_t triangles = 0, vertices = 0;
  double error = 0;
};

struct MeshJob {
  int mesh = -1;
  std::vector<int> nodes;
  double radius = 0;
  double vanish = 0;                        ///< unit scale
  std::vector<PrimitiveLevels> primitives;  ///< the simplified ones
  std::vector<MeshLevel> levels;            ///< levels 1..m
  std::vector<int> level_meshes;
  ShapeStatistics stats;
};

std::string mesh_label(const Model& m, int mesh) {
  const std::string& name = m.meshes[std::size_t(mesh)].name;
  return name.empty() ? fmt::format("mesh {}", mesh) : fmt::format("mesh {} '{}'", mesh, name);
}

double camera_angle_of(const Model& m, const LodOptions& o) {
  if (o.camera_angle_given) return o.range.camera_angle;
  for (const auto& c : m.cameras)
    if (c.type == "perspective" && c.perspective.yfov > 0 && c.perspective.yfov < kPi)
      return c.perspective.yfov;
  return o.range.camera_angle;
}

// Why a mesh stays at full detail ("" if it need not): vertex data held by a
// compression extension (KHR_draco_mesh_compression, EXT_meshopt_compression)
// is not simplified.
std::string full_detail_reason(const Model& m, const MeshJob& job) {
  for (const auto& p : m.meshes[std::size_t(job.mesh)].primitives) {
    if (p.extensions.count("KHR_draco_mesh_compression"))
      return "a primitive has the extension KHR_draco_mesh_compression";
    auto attributes = p.attributes;
    if (p.indices >= 0) attributes["indices"] = p.indices;
    for (const auto& target : p.targets)
      for (const auto& [name, index] : target) attributes["target " + name] = index;
    for (const auto& [name, index] : attributes) {
      const auto& a = m.accessors[std::size_t(index)];
      if (a.bufferView < 0 && !a.sparse.isSparse)
        return fmt::format("its {} accessor has no data (compressed?)", name);
      if (a.bufferView >= 0 && !m.bufferViews[std::size_t(a.bufferView)].extensions.empty())
        return fmt::format("its {} data is in a buffer view with the extension {}", name,
                           m.bufferViews[std::size_t(a.bufferView)].extensions.begin()->first);
    }
  }
  return "";
}

// The vertices the levels of a primitive draw, over all its levels: each
// distinct (input vertex, position) once, numbered from 0 in the order the
// levels meet them, with the input vertex it stands for (its other
// attributes) and where it is (moved by the simplifier or not). A set in
// which nothing moved is drawn through the input's own accessors instead.
class VertexSet {
 public:
  VertexSet(const std::vector<Vec3>& input, bool positions_float)
      : input_(input), float_(positions_float) {}
  std::uint32_t add(const SimplifyResult& level, std::uint32_t v) {
    const std::uint32_t src = v < level.vertex_map.size() ? level.vertex_map[v] : kNone;
    if (src >= input_.size()) throw DataError("a simplified vertex without a source vertex");
    const Vec3 q = input_[src];
    // Positions that are not floats stay the source's (no moved position
    // could be stored in them).
    const Vec3 p = float_ ? level.mesh.positions[v] : q;
    const bool moved = std::memcmp(&p, &q, sizeof p) != 0;
    Key key{src, 0, 0, 0};
    std::memcpy(&key[1], &p, sizeof p);
    auto [it, added] = index_.try_emplace(key, std::uint32_t(sources_.size()));
    if (added) {
      sources_.push_back(src);
      positions_.push_back(p);
      any_moved_ = any_moved_ || moved;
    }
    return it->second;
  }
  std::size_t size() const { return sources_.size(); }
  /// Per vertex of the set: the input vertex it stands for, its position.
  const std::vector<std::uint32_t>& sources() const { return sources_; }
  const std::vector<Vec3>& positions() const { return positions_; }
  bool any_moved() const { return any_moved_; }

 private:
  const std::vector<Vec3>& input_;
  bool float_;
  bool any_moved_ = false;
  using Key = std::array<std::uint32_t, 4>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0;
      for (std::uint32_t v : k) h = (h ^ v) * 0x100000001B3ull;
      return std::size_t(h ^ (h >> 29));
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> index_;
  std::vector<std::uint32_t> sources_;
  std::vector<Vec3> positions_;
};

// What a vertex-set accessor holds: a vertex attribute, POSITION (moved
// vertices take their new position; min and max) or a morph target's POSITION
// displacement (min and max).
enum class SetElement { kAttribute, kPosition, kTargetPosition };

// Accessor `index` taken over the vertices of `set`: each vertex's source
// element (its position, for POSITION). Raw bytes where the accessor has a
// buffer view, else decoded as floats.
int set_accessor(BufferAppender& out, Model& m, int index, const VertexSet& set, SetElement what) {
  const bool position = what == SetElement::kPosition;
  const tinygltf::Accessor a = m.accessors[std::size_t(index)];
  const std::size_t total = set.size();
  const auto& sources = set.sources();
  const auto components = std::size_t(tinygltf::GetNumComponentsInType(std::uint32_t(a.type)));
  tinygltf::Accessor e;
  e.type = a.type;
  e.count = total;
  std::vector<unsigned char> bytes;
  std::size_t stride = 0;
  const bool raw = a.bufferView >= 0 && !a.sparse.isSparse;
  const bool float_positions = position && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (raw) {
    const auto& view = m.bufferViews[std::size_t(a.bufferView)];
    const std::size_t in_stride = std::size_t(a.ByteStride(view));
    const std::size_t element =
        components * std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType)));
    const unsigned char* base =
        m.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    stride = round4(element);
    bytes.assign(stride * total, 0);
    for (std::size_t i = 0; i < total; ++i) {
      if (float_positions)
        std::memcpy(bytes.data() + i * stride, &set.positions()[i], sizeof(Vec3));
      else
        std::memcpy(bytes.data() + i * stride, base + sources[i] * in_stride, element);
    }
    e.componentType = a.componentType;
    e.normalized = a.normalized;
  } else {
    const gltf::AccessorValues v = gltf::read_accessor(m, index);
    stride = components * 4;
    bytes.assign(stride * total, 0);
    for (std::size_t i = 0; i < total; ++i)
      for (std::size_t c = 0; c < components; ++c) {
        const float f =
            position ? (&set.positions()[i].x)[c] : float(v.values[sources[i] * components + c]);
        std::memcpy(bytes.data() + i * stride + c * 4, &f, 4);
      }
    e.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  }
  if (what != SetElement::kAttribute) {
    const gltf::AccessorValues v = gltf::read_accessor(m, index);
    e.minValues.assign(components, INFINITY);
    e.maxValues.assign(components, -INFINITY);
    for (std::size_t i = 0; i < total; ++i)
      for (std::size_t c = 0; c < components; ++c) {
        const double x =
            position ? (&set.positions()[i].x)[c] : v.values[sources[i] * components + c];
        e.minValues[c] = std::min(e.minValues[c], x);
        e.maxValues[c] = std::max(e.maxValues[c], x);
      }
  }
  e.bufferView = out.add_view(bytes, kArrayBuffer, stride);
  m.accessors.push_back(std::move(e));
  return int(m.accessors.size() - 1);
}

int index_accessor(BufferAppender& out, Model& m, const std::vector<std::uint32_t>& indices,
                   std::size_t vertices) {
  tinygltf::Accessor a;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = indices.size();
  std::vector<unsigned char> bytes;
  // The largest value of the type is the primitive restart value, which glTF forbids.
  if (vertices < 65535) {
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    bytes.resize(indices.size() * 2);
    for (std::size_t i = 0; i < indices.size(); ++i) {
      const auto v = std::uint16_t(indices[i]);
      std::memcpy(bytes.data() + 2 * i, &v, 2);
    }
  } else {
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    bytes.resize(indices.size() * 4);
    std::memcpy(bytes.data(), indices.data(), bytes.size());
  }
  a.bufferView = out.add_view(bytes, kElementArrayBuffer, 0);
  m.accessors.push_back(std::move(a));
  return int(m.accessors.size() - 1);
}

// The shared vertex set and the index accessors of the levels of `pl` that
// `used` marks (1-based level numbers).
void store_levels(BufferAppender& out, Model& m, PrimitiveLevels& pl,
                  const std::vector<char>& used) {
  const auto& attributes = pl.attributes;
  const auto position = attributes.find("POSITION");
  const bool positions_float =
      m.accessors[std::size_t(position->second)].componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  VertexSet set(pl.positions, positions_float);
  std::vector<std::vector<std::uint32_t>> indices(pl.levels.size());
  for (std::size_t k = 0; k < pl.levels.size(); ++k) {
    if (!used[k + 1]) continue;
    const SimplifyResult& level = pl.levels[k].measured.level;
    for (const auto& t : level.mesh.triangles)
      for (std::uint32_t v : t) indices[k].push_back(set.add(level, v));
  }
  pl.index_accessors.assign(pl.levels.size(), -1);
  if (!set.any_moved()) {
    // No vertex moved: the levels draw the input's vertices through its
    // own accessors.
    for (std::size_t k = 0; k < pl.levels.size(); ++k) {
      if (!used[k + 1]) continue;
      for (std::uint32_t& v : indices[k]) v = set.sources()[v];
      pl.index_accessors[k] = index_accessor(out, m, indices[k], pl.positions.size());
    }
    return;
  }
  for (std::size_t k = 0; k < pl.levels.size(); ++k)
    if (used[k + 1]) pl.index_accessors[k] = index_accessor(out, m, indices[k], set.size());
  std::map<std::string, int> over_set;
  for (const auto& [name, accessor] : attributes)
    over_set[name] = set_accessor(
        out, m, accessor, set, name == "POSITION" ? SetElement::kPosition : SetElement::kAttribute);
  pl.attributes = std::move(over_set);
  for (auto& target : pl.targets)
    for (auto& [name, accessor] : target)
      accessor =
          set_accessor(out, m, accessor, set,
                       name == "POSITION" ? SetElement::kTargetPosition : SetElement::kAttribute);
}

ChooseLevelsOptions choose_options(const LodOptions& o, const RangeOptions& range) {
  ChooseLevelsOptions c{.method = o.method,
                        .min_diff = o.min_diff,
                        .spacing = {.spacing = o.level_spacing, .max_ratio = o.level_ratio},
                        .range = range,
                        .max_simplified = o.max_levels >= 2 ? o.max_levels - 2 : 0,
                        .measure_samples = o.measure_samples,
                        .threads = o.threads};
  const auto manual = o.manual.find("polygon");
  if (manual != o.manual.end()) c.quality = manual->second.quality;
  return c;
}

// The meshes the shown scene draws, each with the nodes that draw it.
std::vector<MeshJob> collect_jobs(const Model& m, const std::vector<gltf::NodePlacement>& placed) {
  std::vector<MeshJob> jobs(m.meshes.size());
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    if (placed[n].in_scene && m.nodes[n].mesh >= 0)
      jobs[std::size_t(m.nodes[n].mesh)].nodes.push_back(int(n));
  std::vector<MeshJob> used;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (!jobs[i].nodes.empty()) {
      jobs[i].mesh = int(i);
      used.push_back(std::move(jobs[i]));
    }
  return used;
}

// Level 0 of the job in its statistics: the triangles of its triangle primitives.
void level0_statistics(const Model& m, MeshJob& job) {
  LevelStatistics l0;
  for (const auto& p : m.meshes[std::size_t(job.mesh)].primitives) {
    if (!is_triangles(p.mode)) continue;
    const TriangleMesh t = gltf::primitive_mesh(m, p, job.mesh);
    l0.triangles += t.triangle_count();
    l0.vertices += t.vertex_count();
  }
  job.stats.levels.assign(1, l0);
}

// The texture coordinate set the primitive's material samples its textures
// with (a KHR_texture_transform's texCoord counts; the base colour's first, then the normal,
// occlusion, emissive and metallic-roughness textures'); -1 when it has no texture.
int textured_coordinates(const Model& m, const tinygltf::Primitive& p) {
  if (p.material < 0 || std::size_t(p.material) >= m.materials.size()) return -1;
  const tinygltf::Material& mat = m.materials[std::size_t(p.material)];
  const auto& pbr = mat.pbrMetallicRoughness;
  auto set = [](const auto& info) {
    return gltf::texture_transform(info.texCoord, info.extensions).set;
  };
  for (const auto& [index, coordinates] :
       {std::pair{pbr.baseColorTexture.index, set(pbr.baseColorTexture)},
        {mat.normalTexture.index, set(mat.normalTexture)},
        {mat.occlusionTexture.index, set(mat.occlusionTexture)},
        {mat.emissiveTexture.index, set(mat.emissiveTexture)},
        {pbr.metallicRoughnessTexture.index, set(pbr.metallicRoughnessTexture)}})
    if (index >= 0) return coordinates;
  return -1;
}

// `input` (primitive_mesh of `p`) with the texture coordinates its material's
// textures use and its COLOR_0 (RGB), where they have one element per
// vertex: the simplifier then keeps the seams where they differ between
// coincident vertices (texture islands, colour borders), and each level
// vertex's source vertex lies on its triangle's side of them. Normals are
// not given: a flat-shaded mesh splits every vertex by them, and a seam at
// every vertex would leave nothing to simplify.
void add_seam_attributes(const Model& m, const tinygltf::Primitive& p, TriangleMesh& input) {
  // The attribute's values when it has one element of `components` (or
  // more) per vertex.
  auto per_vertex = [&](const std::string& name, int components) {
    const auto a = p.attributes.find(name);
    std::optional<gltf::AccessorValues> v;
    if (a != p.attributes.end()) v = gltf::read_accessor(m, a->second);
    if (v && (v->count != input.positions.size() || v->components < components)) v.reset();
    return v;
  };
  const int set = textured_coordinates(m, p);
  if (const auto t = set < 0 ? std::nullopt : per_vertex(fmt::format("TEXCOORD_{}", set), 2))
    for (std::size_t i = 0; i < t->count; ++i)
      input.texcoords.push_back({float(t->values[i * std::size_t(t->components)]),
                                 float(t->values[i * std::size_t(t->components) + 1])});
  if (const auto c = per_vertex("COLOR_0", 3))
    for (std::size_t i = 0; i < c->count; ++i) {
      const double* rgb = &c->values[i * std::size_t(c->components)];
      input.colors.push_back({float(rgb[0]), float(rgb[1]), float(rgb[2])});
    }
}

// The largest scale a job's mesh is drawn at (its statistics' scale).
double job_scale(const MeshJob& job, const std::vector<gltf::NodePlacement>& placed) {
  double scale = 0;
  for (int n : job.nodes) scale = std::max(scale, node_scale(placed[std::size_t(n)]));
  return scale;
}

// --differentiate-by-size: each job's manual level count from its size
// (bounding radius of all its primitives, as simplify_primitives takes it,
// times its largest scale) against the largest mesh's; read before any mesh
// is simplified. A mesh that cannot be read keeps `quality` here (its error
// is the simplification's, which names the first such mesh in order).
std::vector<int> sized_qualities(const Model& m, const std::vector<MeshJob>& jobs,
                                 const std::vector<gltf::NodePlacement>& placed, int quality) {
  std::vector<double> radius(jobs.size(), 0);
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t i) {
    std::vector<Vec3> all;
    try {
      for (const auto& p : m.meshes[std::size_t(jobs[i].mesh)].primitives) {
        const TriangleMesh mesh = gltf::primitive_mesh(m, p, jobs[i].mesh);
        all.insert(all.end(), mesh.positions.begin(), mesh.positions.end());
      }
    } catch (const DataError&) {
      return;
    }
    radius[i] = bounding_radius(all);
  });
  double largest = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    largest = std::max(largest, radius[i] * job_scale(jobs[i], placed));
  std::vector<int> out(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i)
    out[i] = sized_quality(quality, radius[i], job_scale(jobs[i], placed), largest);
  return out;
}

// The levels of each triangle primitive, and the mesh's bounding radius.
void simplify_primitives(const Model& m, MeshJob& job, const ChooseLevelsOptions& c) {
  std::vector<Vec3> all;
  const auto& primitives = m.meshes[std::size_t(job.mesh)].primitives;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const auto& p = primitives[i];
    TriangleMesh input = gltf::primitive_mesh(m, p, job.mesh);
    all.insert(all.end(), input.positions.begin(), input.positions.end());
    if (!is_triangles(p.mode) || !p.attributes.count("POSITION")) continue;
    add_seam_attributes(m, p, input);
    PrimitiveLevels pl;
    pl.primitive = int(i);
    pl.radius = bounding_radius(input.positions);
    pl.triangles = input.triangle_count();
    pl.attributes = p.attributes;
    pl.targets = p.targets;
    if (pl.triangles > 0) {
      ChosenLevels chosen = choose_levels(input, pl.radius, c);
      pl.levels = std::move(chosen.levels);
      job.stats.method = chosen.method;
      job.stats.stop_reason = chosen.stop_reason;
    }
    pl.positions = std::move(input.positions);
    job.primitives.push_back(std::move(pl));
  }
  job.radius = bounding_radius(all);
}

// --ranges [polygon=]a,b,...: the first switch distances (mesh units, as a
// VRML LOD's range) are the given ones, the vanishing one too when given.
void apply_manual_ranges(MeshJob& job, const LodOptions& o) {
  const auto manual = o.manual.find("polygon");
  if (manual == o.manual.end() || manual->second.ranges.empty() || job.levels.empty()) return;
  std::vector<float> ranges;
  for (const MeshLevel& l : job.levels) ranges.push_back(float(l.distance));
  ranges.push_back(float(job.vanish));
  apply_given_ranges(ranges, manual->second.ranges);
  for (std::size_t k = 0; k < job.levels.size(); ++k) job.levels[k].distance = ranges[k];
  job.vanish = ranges.back();
}

// The levels of the mesh: its primitives' switching points (and the points
// where small primitives vanish), gathered within the level spacing, each
// group switching at its latest point.
void plan_levels(MeshJob& job, const Model& m, const LodOptions& o, const RangeOptions& range) {
  const double r = job.radius;
  if (!(r > 0) || !std::isfinite(r)) return;
  auto unit = [&](double error) { return switch_distance(error, 1.0, r, range); };
  job.vanish = unit(vanishing_error(r));
  std::vector<double> events;
  for (auto& pl : job.primitives) {
    for (const auto& l : pl.levels) pl.distances.push_back(unit(l.switch_error));
    pl.vanish = unit(vanishing_error(pl.radius));
    for (double d : pl.distances)
      if (d < job.vanish) events.push_back(d);
    if (pl.vanish < job.vanish) events.push_back(pl.vanish);
  }
  std::sort(events.begin(), events.end());
  const std::size_t count = m.meshes[std::size_t(job.mesh)].primitives.size();
  const double spacing = std::max(1.0, o.level_spacing);
  std::vector<int> previous(count, 0);
  for (std::size_t i = 0; i < events.size();) {
    std::size_t j = i;
    while (j < events.size() && events[j] <= events[i] * spacing) ++j;
    MeshLevel level{.distance = events[j - 1], .choice = std::vector<int>(count, 0)};
    i = j;
    for (const auto& pl : job.primitives) {
      int& c = level.choice[std::size_t(pl.primitive)];
      if (pl.vanish <= level.distance) {
        c = -1;
        continue;
      }
      c = int(std::upper_bound(pl.distances.begin(), pl.distances.end(), level.distance) -
              pl.distances.begin());
      const auto& l = c > 0 ? pl.levels[std::size_t(c - 1)].measured : MeasuredLevel{};
      level.triangles += c > 0 ? l.level.mesh.triangle_count() : pl.triangles;
      level.vertices += c > 0 ? l.level.mesh.vertex_count() : pl.positions.size();
      level.error = std::max(level.error, c > 0 ? l.error : 0.0);
    }
    if (level.choice == previous) continue;
    if (std::all_of(level.choice.begin(), level.choice.end(), [](int c) { return c < 0; })) {
      job.vanish = level.distance;  // nothing left to draw
      break;
    }
    previous = level.choice;
    job.levels.push_back(std::move(level));
  }
  if (o.max_levels >= 2 && job.levels.size() > o.max_levels - 2)
    job.levels.resize(o.max_levels - 2);
  apply_manual_ranges(job, o);
}

// The level meshes, after the vertex sets and index accessors they use.
void write_level_meshes(BufferAppender& out, Model& m, MeshJob& job) {
  const tinygltf::Mesh input = m.meshes[std::size_t(job.mesh)];
  std::vector<int> which(input.primitives.size(), -1);
  for (std::size_t k = 0; k < job.primitives.size(); ++k) {
    PrimitiveLevels& pl = job.primitives[k];
    which[std::size_t(pl.primitive)] = int(k);
    std::vector<char> used(pl.levels.size() + 1, 0);
    for (const auto& level : job.levels) {
      const int c = level.choice[std::size_t(pl.primitive)];
      if (c > 0) used[std::size_t(c)] = 1;
    }
    store_levels(out, m, pl, used);
  }
  for (std::size_t k = 0; k < job.levels.size(); ++k) {
    tinygltf::Mesh level = input;
    level.primitives.clear();
    if (!input.name.empty()) level.name = fmt::format("{}_lod{}", input.name, k + 1);
    for (std::size_t i = 0; i < input.primitives.size(); ++i) {
      const int c = job.levels[k].choice[i];
      if (c < 0) continue;
      tinygltf::Primitive p = input.primitives[i];
      if (c > 0) {
        const PrimitiveLevels& pl = job.primitives[std::size_t(which[i])];
        p.attributes = pl.attributes;
        p.targets = pl.targets;
        p.indices = pl.index_accessors[std::size_t(c - 1)];
        p.mode = TINYGLTF_MODE_TRIANGLES;
      }
      level.primitives.push_back(std::move(p));
    }
    m.meshes.push_back(std::move(level));
    job.level_meshes.push_back(int(m.meshes.size() - 1));
  }
  // Written: the geometry is freed as the buffer grows (every mesh's levels
  // held until the end made the peak).
  for (PrimitiveLevels& pl : job.primitives) {
    pl.positions = {};
    pl.levels = {};
  }
}

// The animation channels of node `n`'s morph weights, given to its level
// nodes too (the same samplers), so a level shown in its place moves as it.
void animate_weights_of_levels(Model& m, int n, const Value::Array& level_nodes) {
  for (auto& animation : m.animations) {
    const std::size_t count = animation.channels.size();
    for (std::size_t c = 0; c < count; ++c) {
      if (animation.channels[c].target_node != n || animation.channels[c].target_path != "weights")
        continue;
      for (const Value& id : level_nodes) {
        tinygltf::AnimationChannel copy = animation.channels[c];
        copy.target_node = id.GetNumberAsInt();
        animation.channels.push_back(std::move(copy));
      }
    }
  }
}

// --extract K (>= 1): every node drawing the mesh draws its level K instead
// (beyond the last simplified level, the last: a node keeps a mesh, which
// its skin and morph-weight animations need).
void extract_level(Model& m, const MeshJob& job, std::size_t k) {
  for (int n : job.nodes)
    m.nodes[std::size_t(n)].mesh = job.level_meshes[std::min(k, job.level_meshes.size()) - 1];
}

// MSFT_lod with new level nodes on every node drawing the mesh, and the
// coverages and level table in its extras.
void attach_lod(Model& m, const MeshJob& job, const std::vector<gltf::NodePlacement>& placed,
                double angle, Log& log) {
  const double t = std::tan(angle / 2);
  Value::Array coverage;
  for (const auto& level : job.levels) coverage.emplace_back(job.radius / (level.distance * t));
  coverage.emplace_back(job.radius / (job.vanish * t));
  for (int n : job.nodes) {
    const double s = node_scale(placed[std::size_t(n)]);
    Value::Array ids;
    for (std::size_t k = 0; k < job.levels.size(); ++k) {
      const tinygltf::Node& node = m.nodes[std::size_t(n)];
      tinygltf::Node level;
      if (!node.name.empty()) level.name = fmt::format("{}_lod{}", node.name, k + 1);
      level.mesh = job.level_meshes[k];
      level.skin = node.skin;
      level.weights = node.weights;
      level.matrix = node.matrix;
      level.translation = node.translation;
      level.rotation = node.rotation;
      level.scale = node.scale;
      m.nodes.push_back(std::move(level));
      ids.emplace_back(int(m.nodes.size() - 1));
    }
    animate_weights_of_levels(m, n, ids);
    tinygltf::Node& node = m.nodes[std::size_t(n)];
    node.extensions["MSFT_lod"] = Value(Value::Object{{"ids", Value(std::move(ids))}});
    if (!node.extras.IsObject() && node.extras.Type() != tinygltf::NULL_TYPE) {
      log.warn(LogCategory::kGeneral,
               fmt::format("node {}: its extras are not an object, so MSFT_screencoverage is not "
                           "written (viewers switch by their own rule)",
                           n));
      continue;
    }
    Value::Object extras;
    if (node.extras.IsObject()) extras = node.extras.Get<Value::Object>();
    Value::Array levels;
    levels.emplace_back(Value::Object{{"switch_distance", Value(0.0)},
                                      {"error", Value(0.0)},
                                      {"triangles", Value(int(job.stats.levels[0].triangles))}});
    for (const auto& l : job.levels)
      levels.emplace_back(Value::Object{{"switch_distance", Value(l.distance * s)},
                                        {"error", Value(l.error)},
                                        {"triangles", Value(int(l.triangles))}});
    extras["MSFT_screencoverage"] = Value(coverage);
    extras["lodforge_lod"] = Value(Value::Object{
        {"levels", Value(std::move(levels))},
        {"vanishing_distance", Value(job.vanish * s)},
        {"bounding_radius", Value(job.radius * s)},
        {"camera_angle", Value(angle)},
        {"coverage", Value(std::string("MSFT_screencoverage[i] = bounding_radius / "
                                       "(switch_distance[i + 1] * tan(camera_angle / 2)), the "
                                       "last one at vanishing_distance"))}});
    node.extras = Value(std::move(extras));
  }
}

// Triangles drawn when every node is seen from each switching distance.
std::vector<std::pair<double, std::size_t>> triangles_by_distance(
    const std::vector<MeshJob>& jobs, const std::vector<gltf::NodePlacement>& placed) {
  std::vector<double> distances{0};
  for (const auto& job : jobs)
    for (int n : job.nodes) {
      const double s = node_scale(placed[std::size_t(n)]);
      if (job.levels.empty()) continue;
      for (const auto& l : job.levels) distances.push_back(l.distance * s);
      distances.push_back(job.vanish * s);
    }
  std::sort(distances.begin(), distances.end());
  distances.erase(std::unique(distances.begin(), distances.end()), distances.end());
  std::vector<std::pair<double, std::size_t>> out;
  for (double d : distances) {
    std::size_t drawn = 0;
    for (const auto& job : jobs)
      for (int n : job.nodes) {
        const double s = node_scale(placed[std::size_t(n)]);
        if (!job.levels.empty() && d >= job.vanish * s) continue;
        std::size_t t = job.stats.levels[0].triangles;
        for (const auto& l : job.levels)
          if (d >= l.distance * s) t = l.triangles;
        drawn += t;
      }
    out.emplace_back(d, drawn);
  }
  return out;
}

// The statistics entry of a job.
void finish_statistics(const Model& m, MeshJob& job,
                       const std::vector<gltf::NodePlacement>& placed) {
  const std::string& name = m.meshes[std::size_t(job.mesh)].name;
  job.stats.type = "mesh";
  job.stats.name = name.empty() ? fmt::format("mesh {}", job.mesh) : name;
  job.stats.occurrences = job.nodes.size();
  job.stats.radius = job.radius;
  job.stats.scale = job_scale(job, placed);
  if (job.stats.method.empty()) job.stats.method = "none";
  if (job.levels.empty()) return;
  for (const auto& l : job.levels) {
    job.stats.levels.push_back({l.triangles, l.vertices, l.error});
    job.stats.ranges.push_back(float(l.distance * job.stats.scale));
  }
  job.stats.ranges.push_back(float(job.vanish * job.stats.scale));
}

}  // namespace

LodResult gltf_lod(gltf::GltfScene& scene, const LodOptions& options) {
  Model& m = scene.model;
  LodResult result;
  const double angle = camera_angle_of(m, options);
  result.camera_angle = angle;
  RangeOptions range = options.range;
  range.camera_angle = float(angle);
  const ChooseLevelsOptions choose = choose_options(options, range);
  const auto placed = gltf::node_placements(m);
  std::vector<MeshJob> jobs = collect_jobs(m, placed);
  const bool no_levels =
      choose.quality == 0 || choose.quality == 1 || (options.extract && *options.extract <= 0);
  // Every mesh's levels, in parallel (the model is only read here); what
  // they add to the model after, in the model's order, so the file is the
  // same for any number of threads.
  std::vector<std::string> kept(jobs.size()), failed(jobs.size());
  std::atomic<std::size_t> done{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    std::vector<int> quality;
    if (options.differentiate_by_size && !no_levels)
      quality = sized_qualities(m, jobs, placed, choose.quality);
    tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t i) {
      MeshJob& job = jobs[i];
      level0_statistics(m, job);
      kept[i] = full_detail_reason(m, job);
      // Manual mode without simplified levels, --extract 0 (level 0) or -1
      // (the scene cleaned): the mesh stays as it is.
      if (kept[i].empty() && !no_levels) {
        try {
          ChooseLevelsOptions c = choose;
          if (!quality.empty()) c.quality = quality[i];
          simplify_primitives(m, job, c);
          plan_levels(job, m, options, range);
        } catch (const DataError& e) {
          failed[i] = fmt::format("{}: {}", mesh_label(m, job.mesh), e.what());
        }
      }
      if (options.progress) options.progress("shapes", ++done, jobs.size());
    });
  });
  for (const std::string& f : failed)
    if (!f.empty()) throw DataError(f);
  BufferAppender out(m);
  bool any = false;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    MeshJob& job = jobs[i];
    if (!kept[i].empty())
      result.log.warn(LogCategory::kGeneral, fmt::format("{}: kept at full detail because {}",
                                                         mesh_label(m, job.mesh), kept[i]));
    if (!job.levels.empty()) {
      write_level_meshes(out, m, job);
      if (options.extract) {
        extract_level(m, job, std::size_t(*options.extract));
      } else {
        attach_lod(m, job, placed, angle, result.log);
        any = true;
      }
    }
    finish_statistics(m, job, placed);
  }
  out.finish();
  if (any && std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), "MSFT_lod") ==
                 m.extensionsUsed.end())
    m.extensionsUsed.push_back("MSFT_lod");
  result.triangles_by_distance = triangles_by_distance(jobs, placed);
  for (auto& job : jobs) result.shapes.push_back(std::move(job.stats));
  return result;
}

}  // namespace lodforge
