#include "lodforge/studio/level_geometry.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <optional>

#include "lodforge/core/error.h"
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

std::string mesh_text(const scene::ShapeVisit& visit, const scene::ShapeSurface& surface) {
  const TriangleMesh& m = surface.mesh;
  std::string out;
  out.reserve(64 + m.positions.size() * 40 + m.triangles.size() * 24);
  fmt::format_to(std::back_inserter(out), R"({{"type":{},"line":{},"matrix":)",
                 nlohmann::json(visit.shape.type).dump(), visit.shape.first_line);
  std::vector<float> matrix(16);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) matrix[std::size_t(c * 4 + r)] = visit.state.transform.m[r][c];
  append_list(out, matrix, append_number);
  out += R"(,"positions":)";
  append_list(out, m.positions, [](std::string& o, const Vec3& p, bool& first) {
    append_number(o, p.x, first);
    append_number(o, p.y, first);
    append_number(o, p.z, first);
  });
  if (m.has_colors()) {
    out += R"(,"colors":)";
    append_list(out, m.colors, [](std::string& o, const Vec3& c, bool& first) {
      append_number(o, c.x, first);
      append_number(o, c.y, first);
      append_number(o, c.z, first);
    });
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
  std::vector<std::vector<std::string>> levels;
  std::vector<int> filled_in_pass;  ///< per level: the traversal that drew it, -1 none yet
  std::optional<Mat4> transform;    ///< at the node
  bool exact = false;               ///< transform read from a direct child
};

std::string lod_text(const LodInstance& lod) {
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
    for (std::size_t k = 0; k < lod.levels[l].size(); ++k) out += (k ? "," : "") + lod.levels[l][k];
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

}  // namespace

std::string level_geometry(const scene::Scene& scene, const LevelGeometryOptions& options,
                           Log* log) {
  std::map<std::vector<std::size_t>, LodInstance> lods;  // by the path to the node
  std::vector<std::string> shapes;
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
          const scene::ShapeSurface surface = scene::shape_surface(v, mesh_options, log);
          triangles += surface.mesh.triangles.size();
          if (triangles > options.max_triangles)
            throw DataError(
                fmt::format("the levels hold more than {} triangles, too many for the 3D view",
                            options.max_triangles));
          std::string text = mesh_text(v, surface);
          if (lod)
            lod->levels[level].push_back(std::move(text));
          else
            shapes.push_back(std::move(text));
        },
        t);
  }
  std::string out = R"({"lods":[)";
  bool first = true;
  for (const auto& [key, lod] : lods) {
    if (!first) out += ',';
    first = false;
    out += lod_text(lod);
  }
  out += R"(],"shapes":[)";
  for (std::size_t i = 0; i < shapes.size(); ++i) out += (i ? "," : "") + shapes[i];
  out += "]}";
  return out;
}

}  // namespace lodforge::studio
