#include "lodforge/studio/level_geometry.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "lodforge/core/error.h"
#include "lodforge/metrics/colorize_deviation.h"
#include "lodforge/metrics/triangle_bvh.h"
#include "lodforge/scene/shape_mesh.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::studio {
namespace {

// Appends "[a,b,...]" of the shortest forms that read back to each float.
template <class Range, class Fn>
void append_list(std::string& out, const Range& range, Fn each) {
  out += '[';
  bool first = true;
  for (const auto& item : range) each(out, item, first);
  out += ']';
}

void append_number(std::string& out, float v, bool& first) {
  if (!first) out += ',';
  first = false;
  fmt::format_to(std::back_inserter(out), "{}", v);
}

// One shape as drawn: its mesh in object space and the transform to world.
struct DrawnMesh {
  std::string type;
  int line = 0;
  Mat4 transform;
  TriangleMesh mesh;
  std::vector<float> deviation;          ///< per vertex, when computed
  const scene::Node* texture = nullptr;  ///< the Texture2 drawn, if the mesh has texcoords
};

// "texture":{"file":NAME} (as the Texture2 gives it, relative to the scene's
// folder) or {"image":[w,h,components,pixel,...]} (its SFImage), and the
// texture coordinates.
void append_texture(std::string& out, const DrawnMesh& drawn) {
  const scene::FieldValue* name = drawn.texture->applied_value("filename");
  const scene::FieldValue* image = drawn.texture->applied_value("image");
  if (name && !name->strings.empty() && !name->strings[0].empty())
    out += R"(,"texture":{"file":)" + nlohmann::json(name->strings[0]).dump() + "}";
  else if (image && image->ints.size() > 3)
    out += R"(,"texture":{"image":)" + nlohmann::json(image->ints).dump() + "}";
  else
    return;
  out += R"(,"texcoords":)";
  append_list(out, drawn.mesh.texcoords, [](std::string& o, const Vec2& t, bool& first) {
    append_number(o, t.x, first);
    append_number(o, t.y, first);
  });
}

void append_vectors(std::string& out, const std::vector<Vec3>& values) {
  append_list(out, values, [](std::string& o, const Vec3& p, bool& first) {
    append_number(o, p.x, first);
    append_number(o, p.y, first);
    append_number(o, p.z, first);
  });
}

std::string mesh_text(const DrawnMesh& drawn, float deviation_max) {
  const TriangleMesh& m = drawn.mesh;
  std::string out;
  out.reserve(64 + m.positions.size() * 40 + m.triangles.size() * 24);
  fmt::format_to(std::back_inserter(out), R"({{"type":{},"line":{},"matrix":)",
                 nlohmann::json(drawn.type).dump(), drawn.line);
  std::vector<float> matrix(16);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) matrix[std::size_t(c * 4 + r)] = drawn.transform.m[r][c];
  append_list(out, matrix, append_number);
  out += R"(,"positions":)";
  append_vectors(out, m.positions);
  if (m.has_colors()) {
    out += R"(,"colors":)";
    append_vectors(out, m.colors);
  }
  if (drawn.texture && m.texcoords.size() == m.vertex_count()) append_texture(out, drawn);
  if (drawn.deviation.size() == m.vertex_count()) {
    out += R"(,"deviation":)";
    append_list(out, drawn.deviation, append_number);
    out += R"(,"deviation_colors":)";
    append_vectors(out, colorize_deviation(m, drawn.deviation, deviation_max));
  }
  const auto append_index = [](std::string& o, std::uint32_t i, bool& first) {
    if (!first) o += ',';
    first = false;
    fmt::format_to(std::back_inserter(o), "{}", i);
  };
  out += R"(,"indices":[)";
  bool first = true;
  for (const auto& t : m.triangles)
    for (std::uint32_t i : t) append_index(out, i, first);
  out += R"(],"lines":[)";
  first = true;
  for (const auto& s : m.lines)
    for (std::uint32_t i : s) append_index(out, i, first);
  out += "]}";
  return out;
}

struct LodInstance {
  const scene::Node* node = nullptr;
  std::vector<std::vector<DrawnMesh>> levels;
  std::vector<int> filled_in_pass;  ///< per level: the traversal that drew it, -1 none yet
  std::optional<Mat4> transform;    ///< at the node
  bool exact = false;               ///< transform read from a direct child
};

std::string lod_text(const LodInstance& lod, float deviation_max) {
  const scene::Node& n = *lod.node;
  const scene::FieldValue* c = n.value("center");
  Vec3 center =
      c && c->floats.size() >= 3 ? Vec3{c->floats[0], c->floats[1], c->floats[2]} : Vec3{0, 0, 0};
  if (lod.transform) center = lod.transform->transform_point(center);
  std::string out;
  fmt::format_to(std::back_inserter(out), R"({{"line":{},"name":{},"center":[{},{},{}],)",
                 n.first_line, nlohmann::json(n.name).dump(), center.x, center.y, center.z);
  const scene::FieldValue* range = n.value("range");
  out += R"("ranges":)";
  append_list(out, range ? range->floats : std::vector<float>{}, append_number);
  out += R"(,"levels":[)";
  for (std::size_t l = 0; l < lod.levels.size(); ++l) {
    out += l ? ",[" : "[";
    for (std::size_t k = 0; k < lod.levels[l].size(); ++k) {
      if (k) out += ',';
      out += mesh_text(lod.levels[l][k], deviation_max);
    }
    out += ']';
  }
  out += "]}";
  return out;
}

std::size_t max_lod_children(const scene::Scene& scene) {
  std::size_t most = 1;
  scene::traverse(scene, [&](const scene::ShapeVisit& v) {
    for (const auto* p : v.path)
      if (p->type == "LOD") most = std::max(most, p->children.size());
  });
  return most;
}

// Level 0 of an LOD instance as one world-space surface.
TriangleMesh world_surface(const std::vector<DrawnMesh>& level) {
  TriangleMesh out;
  for (const auto& d : level) {
    const auto base = std::uint32_t(out.positions.size());
    for (const Vec3& p : d.mesh.positions) out.positions.push_back(d.transform.transform_point(p));
    for (const auto& t : d.mesh.triangles)
      out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

// Fills every level's per-vertex deviation from level 0 (the world-space
// distance of each vertex to level 0's surface, as `compare` measures a
// vertex of A against B); returns the largest.
float measure_deviation(LodInstance& lod) {
  if (lod.levels.empty()) return 0;
  const TriangleMesh reference = world_surface(lod.levels[0]);
  const TriangleBvh bvh(reference);
  float most = 0;
  for (std::size_t l = 0; l < lod.levels.size(); ++l)
    for (auto& d : lod.levels[l]) {
      d.deviation.assign(d.mesh.vertex_count(), 0.f);
      if (l == 0 || reference.triangles.empty()) continue;
      std::uint32_t hint = ClosestPoint::kNone;
      for (std::size_t v = 0; v < d.mesh.vertex_count(); ++v) {
        const ClosestPoint c =
            bvh.closest_point(d.transform.transform_point(d.mesh.positions[v]), hint);
        hint = c.triangle;
        d.deviation[v] = std::sqrt(c.distance_squared);
        most = std::max(most, d.deviation[v]);
      }
    }
  return most;
}

}  // namespace

std::string level_geometry(const scene::Scene& scene, const LevelGeometryOptions& options,
                           Log* log) {
  std::map<std::vector<std::size_t>, LodInstance> lods;  // by the path to the node
  std::vector<DrawnMesh> shapes;
  std::size_t triangles = 0;
  scene::ShapeMeshOptions mesh_options{.world_space = false, .appearance = true};
  // The traversal draws one child of every LOD node; traversal k draws child
  // k (clamped), so as many traversals as the largest LOD has children see
  // every level once.
  const std::size_t passes = max_lod_children(scene);
  for (std::size_t pass = 0; pass < passes; ++pass) {
    scene::TraverseOptions t;
    t.lod_level = int(pass);
    scene::traverse(
        scene,
        [&](const scene::ShapeVisit& v) {
          std::optional<std::size_t> at;  // the innermost LOD on the path
          for (std::size_t i = 0; i < v.path.size(); ++i)
            if (v.path[i]->type == "LOD") at = i;
          if (!at && pass > 0) return;
          const std::size_t level =
              at && *at + 1 < v.path.size() ? v.path_index[*at + 1] : v.child_index;
          LodInstance* lod = nullptr;
          if (at) {
            const std::vector<std::size_t> key(v.path_index.begin(),
                                               v.path_index.begin() + std::ptrdiff_t(*at + 1));
            lod = &lods[key];
            if (!lod->node) {
              lod->node = v.path[*at];
              lod->levels.resize(lod->node->children.size());
              lod->filled_in_pass.assign(lod->node->children.size(), -1);
            }
            int& filled = lod->filled_in_pass[level];
            if (filled >= 0 && filled != int(pass)) return;  // drawn by an earlier traversal
            filled = int(pass);
            const bool direct = *at + 1 == v.path.size();
            if (direct && !lod->exact) {
              lod->transform = v.state.transform;
              lod->exact = true;
            } else if (!lod->transform && level == 0) {
              lod->transform = v.state.transform;
            }
          }
          scene::ShapeSurface surface = scene::shape_surface(v, mesh_options, log);
          triangles += surface.mesh.triangles.size();
          if (triangles > options.max_triangles)
            throw DataError(
                fmt::format("the levels hold more than {} triangles, too many for the 3D view",
                            options.max_triangles));
          DrawnMesh drawn{.type = v.shape.type,
                          .line = v.shape.first_line,
                          .transform = v.state.transform,
                          .mesh = std::move(surface.mesh),
                          .texture = surface.texture};
          if (lod)
            lod->levels[level].push_back(std::move(drawn));
          else
            shapes.push_back(std::move(drawn));
        },
        t);
  }
  // One scale for the whole scene, as `compare --colored --color-max` with
  // the largest deviation of all levels: colours of different shapes compare.
  float deviation_max = 0;
  if (options.deviation)
    for (auto& [key, lod] : lods) deviation_max = std::max(deviation_max, measure_deviation(lod));
  std::string out = R"({"lods":[)";
  bool first = true;
  for (const auto& [key, lod] : lods) {
    if (!first) out += ',';
    first = false;
    out += lod_text(lod, deviation_max);
  }
  out += R"(],"shapes":[)";
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    if (options.deviation) shapes[i].deviation.assign(shapes[i].mesh.vertex_count(), 0.f);
    if (i) out += ',';
    out += mesh_text(shapes[i], deviation_max);
  }
  fmt::format_to(std::back_inserter(out), R"(],"deviation_max":{}}})", deviation_max);
  return out;
}

}  // namespace lodforge::studio
