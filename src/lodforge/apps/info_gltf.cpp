#include "lodforge/apps/info_gltf.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "lodforge/io/gltf/node_matrices.h"
#include "lodforge/io/gltf/primitive_mesh.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/scene_mesh.h"

namespace lodforge::apps {
namespace {

const char* mode_name(int mode) {
  static const char* kNames[] = {"POINTS",    "LINES",          "LINE_LOOP",   "LINE_STRIP",
                                 "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return mode >= 0 && mode <= 6 ? kNames[mode] : "?";
}

nlohmann::ordered_json describe(const std::string& path, const tinygltf::Model& m,
                                const std::vector<std::string>& warnings) {
  nlohmann::ordered_json j;
  j["file"] = path;
  j["generator"] = m.asset.generator;
  j["counts"] = {{"scenes", m.scenes.size()},         {"nodes", m.nodes.size()},
                 {"meshes", m.meshes.size()},         {"materials", m.materials.size()},
                 {"textures", m.textures.size()},     {"images", m.images.size()},
                 {"animations", m.animations.size()}, {"skins", m.skins.size()},
                 {"cameras", m.cameras.size()}};
  j["extensions_used"] = m.extensionsUsed;
  j["extensions_required"] = m.extensionsRequired;
  const auto placed = gltf::node_placements(m);
  std::vector<std::vector<int>> users(m.meshes.size());
  std::size_t with_lod = 0;
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    if (m.nodes[n].extensions.count("MSFT_lod")) ++with_lod;
    if (placed[n].in_scene && m.nodes[n].mesh >= 0)
      users[std::size_t(m.nodes[n].mesh)].push_back(int(n));
  }
  j["nodes_with_msft_lod"] = with_lod;
  j["meshes"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < m.meshes.size(); ++i) {
    nlohmann::ordered_json mj{{"index", i}, {"name", m.meshes[i].name}, {"nodes", users[i]}};
    mj["primitives"] = nlohmann::ordered_json::array();
    for (const auto& p : m.meshes[i].primitives) {
      const TriangleMesh t = gltf::primitive_mesh(m, p, int(i));
      mj["primitives"].push_back({{"mode", mode_name(p.mode)},
                                  {"vertices", t.vertex_count()},
                                  {"triangles", t.triangle_count()},
                                  {"segments", t.lines.size()},
                                  {"material", p.material},
                                  {"morph_targets", p.targets.size()}});
    }
    j["meshes"].push_back(std::move(mj));
  }
  const TriangleMesh world = gltf::scene_mesh(m);
  j["triangles"] = world.triangle_count();
  j["vertices"] = world.vertex_count();
  const Box3 b = world.bounds();
  if (b.empty())
    j["bounds"] = nullptr;
  else
    j["bounds"] = {{"min", {b.lo.x, b.lo.y, b.lo.z}},
                   {"max", {b.hi.x, b.hi.y, b.hi.z}},
                   {"diagonal", b.diagonal()}};
  j["warnings"] = warnings;
  return j;
}

}  // namespace

int print_gltf_info(const std::string& path, bool json, bool quiet) {
  const gltf::GltfReadResult r = gltf::read_gltf_file(path);
  const nlohmann::ordered_json j = describe(path, r.scene.model, r.warnings);
  if (json) {
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  if (!quiet)
    for (const auto& w : r.warnings) fmt::print(stderr, "warning: {}: {}\n", path, w);
  fmt::print("{}\n  glTF 2.0", path);
  for (const auto& [what, n] : j["counts"].items())
    fmt::print(", {} {}", what, n.get<std::size_t>());
  fmt::print("\n  triangles {} (drawn by the scene, world space), vertices {}\n",
             j["triangles"].get<std::size_t>(), j["vertices"].get<std::size_t>());
  if (!j["bounds"].is_null())
    fmt::print("  bounds {} .. {}, diagonal {}\n", j["bounds"]["min"].dump(),
               j["bounds"]["max"].dump(), j["bounds"]["diagonal"].get<double>());
  if (!r.scene.model.extensionsUsed.empty())
    fmt::print("  extensions used: {}\n", fmt::join(r.scene.model.extensionsUsed, ", "));
  for (const auto& mj : j["meshes"]) {
    fmt::print("  mesh {} '{}' (nodes {}):\n", mj["index"].get<std::size_t>(),
               mj["name"].get<std::string>(), mj["nodes"].dump());
    for (const auto& p : mj["primitives"])
      fmt::print("    {} vertices {}, triangles {}, segments {}, material {}{}\n",
                 p["mode"].get<std::string>(), p["vertices"].get<std::size_t>(),
                 p["triangles"].get<std::size_t>(), p["segments"].get<std::size_t>(),
                 p["material"].get<int>(),
                 p["morph_targets"].get<std::size_t>() ? ", morph targets" : "");
  }
  return 0;
}

}  // namespace lodforge::apps
