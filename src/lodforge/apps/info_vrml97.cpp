#include "lodforge/apps/info_vrml97.h"

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "lodforge/core/file_io.h"
#include "lodforge/io/gltf/gltf_to_vrml97.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
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

// The reader's and the flattening's warnings, and what was not drawn.
std::vector<std::string> warnings_of(const vrml97::ReadResult& scene, const Log& log,
                                     const FlatVrml97& flat) {
  std::vector<std::string> out;
  for (const auto& d : scene.log.entries()) out.push_back(d.text);
  for (const auto& d : log.entries()) out.push_back(d.text);
  for (const auto& [type, n] : flat.skipped)
    out.push_back(fmt::format("{} {} node{} not drawn (not flattened into the surface)", n, type,
                              n == 1 ? "" : "s"));
  return out;
}

}  // namespace

nlohmann::ordered_json bounds_json(const Box3& bounds) {
  if (bounds.empty()) return nullptr;
  return {{"min", {bounds.lo.x, bounds.lo.y, bounds.lo.z}},
          {"max", {bounds.hi.x, bounds.hi.y, bounds.hi.z}},
          {"diagonal", bounds.diagonal()}};
}

vrml97::ReadResult read_vrml97_input(const std::string& path) {
  if (gltf::is_gltf_path(path)) {
    gltf::GltfReadResult g = gltf::read_gltf_file(path);
    vrml97::ReadResult r;
    for (const auto& w : g.warnings) r.log.warn(LogCategory::kParse, path + ": " + w);
    r.scene = gltf::gltf_to_vrml97(g.scene.model, r.log);
    return r;
  }
  // The encoding by the content where it tells (a `.x3d` holding the
  // classic encoding, an X3D document named otherwise), else by the name.
  std::string head = path == "-" ? std::string() : read_head(path, 256);
  if (head.starts_with("\xEF\xBB\xBF")) head.erase(0, 3);
  const std::size_t first = head.find_first_not_of(" \t\r\n");
  const char c = first == std::string::npos ? '\0' : head[first];
  if (c == '<' || (c != '#' && vrml97::is_x3d_xml_path(path)))
    return vrml97::read_x3d_xml_file(path);
  return vrml97::read_vrml97_file(path, {.source_name = path});
}

FlatVrml97 flatten_vrml97_input(const vrml97::ReadResult& scene, const std::string& path,
                                const FlattenVrml97Options& options, bool quiet) {
  Log log;
  FlatVrml97 flat = flatten_vrml97(scene.scene, options, log);
  if (!quiet)
    for (const auto& w : warnings_of(scene, log, flat))
      fmt::print(stderr, "warning: {}: {}\n", path, w);
  return flat;
}

FlatVrml97 load_vrml97(const std::string& path, const FlattenVrml97Options& options, bool quiet) {
  return flatten_vrml97_input(read_vrml97_input(path), path, options, quiet);
}

std::size_t vrml97_lod_level_count(const scene::Scene& scene) {
  std::size_t count = 1;
  scene::for_each_node(scene,
                       [&](const scene::Node& n) {
                         if (n.type != "LOD") return;
                         for (const char* field : {"level", "children"})
                           if (const scene::FieldValue* v = n.value(field))
                             count = std::max(count, v->nodes.size());
                       },
                       {.field_nodes = true});
  return count;
}

int print_vrml97_info(const std::string& path, bool json, bool quiet) {
  const vrml97::ReadResult scene = read_vrml97_input(path);
  Log log;
  const FlatVrml97 flat = flatten_vrml97(scene.scene, {}, log);
  const std::vector<std::string> warnings = warnings_of(scene, log, flat);
  std::map<std::string, std::size_t> counts;
  scene::for_each_node(scene.scene, [&](const scene::Node& n) { ++counts[n.type]; },
                       {.field_nodes = true});
  auto count = [&](const char* t) {
    auto it = counts.find(t);
    return it == counts.end() ? std::size_t(0) : it->second;
  };
  const TriangleMesh& mesh = flat.flat.mesh;
  const Box3 bounds = mesh.bounds();
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = path;
    j["header"] = scene.scene.header;
    j["node_counts"] = counts;
    for (const char* t : kGeometry) j["shapes"][t] = count(t);
    j["shapes_traversed"] = flat.shapes;
    j["triangles"] = mesh.triangle_count();
    j["vertices"] = mesh.vertex_count();
    j["bounds"] = bounds_json(bounds);
    j["warnings"] = warnings;
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  if (!quiet)
    for (const auto& w : warnings) fmt::print(stderr, "warning: {}: {}\n", path, w);
  fmt::print("{} ({})\n", path, scene.scene.header);
  std::string shapes;
  for (const char* t : kGeometry)
    if (count(t)) shapes += fmt::format("{}{} {}", shapes.empty() ? "" : ", ", t, count(t));
  fmt::print("  geometry: {}\n", shapes.empty() ? "none" : shapes);
  fmt::print("  shapes drawn {}, triangles {}, vertices {}\n", flat.shapes, mesh.triangle_count(),
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
