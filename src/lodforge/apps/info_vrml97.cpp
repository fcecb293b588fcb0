#include "lodforge/apps/info_vrml97.h"

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/scene/traverse.h"

namespace lodforge::apps {
namespace {

// The geometry node types a Shape may hold, drawn or not.
constexpr const char* kGeometry[] = {"IndexedFaceSet", "IndexedTriangleSet",
                                     "TriangleSet",    "IndexedQuadSet",
                                     "ElevationGrid",  "Box",
                                     "Sphere",         "Cone",
                                     "Cylinder",       "IndexedLineSet",
                                     "PointSet"};

struct Read {
  vrml97::ReadResult scene;
  FlatVrml97 flat;
  std::vector<std::string> warnings;
};

Read read(const std::string& path, const FlattenVrml97Options& options) {
  Read r;
  r.scene = vrml97::read_vrml97_file(path, {.source_name = path});
  Log log;
  r.flat = flatten_vrml97(r.scene.scene, options, log);
  for (const auto& d : r.scene.log.entries()) r.warnings.push_back(d.text);
  for (const auto& d : log.entries()) r.warnings.push_back(d.text);
  for (const auto& [type, n] : r.flat.skipped)
    r.warnings.push_back(fmt::format("{} {} node{} not drawn (not flattened into the surface)", n,
                                     type, n == 1 ? "" : "s"));
  return r;
}

}  // namespace

nlohmann::ordered_json bounds_json(const Box3& bounds) {
  if (bounds.empty()) return nullptr;
  return {{"min", {bounds.lo.x, bounds.lo.y, bounds.lo.z}},
          {"max", {bounds.hi.x, bounds.hi.y, bounds.hi.z}},
          {"diagonal", bounds.diagonal()}};
}

FlatVrml97 load_vrml97(const std::string& path, const FlattenVrml97Options& options, bool quiet) {
  Read r = read(path, options);
  if (!quiet)
    for (const auto& w : r.warnings) fmt::print(stderr, "warning: {}: {}\n", path, w);
  return std::move(r.flat);
}

std::size_t vrml97_lod_level_count(const std::string& path) {
  const vrml97::ReadResult r = vrml97::read_vrml97_file(path, {.source_name = path});
  std::size_t count = 1;
  scene::for_each_node(r.scene,
                       [&](const scene::Node& n) {
                         if (n.type != "LOD") return;
                         for (const char* field : {"level", "children"})
                           if (const scene::FieldValue* v = n.value(field))
                             count = std::max(count, v->nodes.size());
                       },
                       {.field_nodes = true});
  return count;
}

float vrml97_field_of_view(const std::string& path) {
  const vrml97::ReadResult r = vrml97::read_vrml97_file(path, {.source_name = path});
  float angle = 0;
  scene::for_each_node(
      r.scene,
      [&](const scene::Node& n) {
        const scene::FieldValue* v = n.type == "Viewpoint" ? n.value("fieldOfView") : nullptr;
        if (!angle && v && !v->floats.empty() && v->floats[0] > 0 && v->floats[0] < kPi)
          angle = v->floats[0];
      },
      {.field_nodes = true});
  return angle > 0 ? angle : float(kPi / 4);
}

int print_vrml97_info(const std::string& path, bool json, bool quiet) {
  const Read r = read(path, {});
  std::map<std::string, std::size_t> counts;
  scene::for_each_node(r.scene.scene, [&](const scene::Node& n) { ++counts[n.type]; },
                       {.field_nodes = true});
  auto count = [&](const char* t) {
    auto it = counts.find(t);
    return it == counts.end() ? std::size_t(0) : it->second;
  };
  const TriangleMesh& mesh = r.flat.flat.mesh;
  const Box3 bounds = mesh.bounds();
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = path;
    j["header"] = r.scene.scene.header;
    j["node_counts"] = counts;
    for (const char* t : kGeometry) j["shapes"][t] = count(t);
    j["shapes_traversed"] = r.flat.shapes;
    j["triangles"] = mesh.triangle_count();
    j["vertices"] = mesh.vertex_count();
    j["bounds"] = bounds_json(bounds);
    j["warnings"] = r.warnings;
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  if (!quiet)
    for (const auto& w : r.warnings) fmt::print(stderr, "warning: {}: {}\n", path, w);
  fmt::print("{} ({})\n", path, r.scene.scene.header);
  std::string shapes;
  for (const char* t : kGeometry)
    if (count(t)) shapes += fmt::format("{}{} {}", shapes.empty() ? "" : ", ", t, count(t));
  fmt::print("  geometry: {}\n", shapes.empty() ? "none" : shapes);
  fmt::print("  shapes drawn {}, triangles {}, vertices {}\n", r.flat.shapes, mesh.triangle_count(),
             mesh.vertex_count());
  if (!bounds.empty())
    fmt::print("  bounds [{} {} {}] .. [{} {} {}], diagonal {}\n", bounds.lo.x, bounds.lo.y,
               bounds.lo.z, bounds.hi.x, bounds.hi.y, bounds.hi.z, bounds.diagonal());
  fmt::print("  nodes:");
  for (const auto& [type, n] : counts) fmt::print(" {} {},", type, n);
  fmt::print("\n");
  return 0;
}

}  // namespace lodforge::apps
