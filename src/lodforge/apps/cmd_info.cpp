// `lodforge info SCENE|MESH [--json]`: what a scene holds — node counts per
// type, the shape counts the original tool showed, vertices, triangles,
// bounds; for a mesh file its counts, bounds and topology.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/info_gltf.h"
#include "lodforge/apps/info_vrml97.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/apps/lod_vrml97.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/mesh/adjacency.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/scene/statistics.h"

namespace lodforge::apps {
namespace {

// A mesh file: counts, bounds and the topology a simplifier cares about.
int mesh_info(const std::string& path, bool json) {
  const TriangleMesh mesh = read_mesh(path);
  const TopologyReport t = mesh_topology_report(mesh);
  Box3 bounds;
  for (const Vec3& p : mesh.positions) bounds.add(p);
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = path;
    j["vertices"] = t.vertices;
    j["triangles"] = t.triangles;
    j["edges"] = t.edges;
    j["components"] = t.components;
    j["boundary_edges"] = t.boundary_edges;
    j["non_manifold_edges"] = t.non_manifold_edges;
    j["non_manifold_vertices"] = t.non_manifold_vertices;
    j["inconsistent_edges"] = t.inconsistent_edges;
    j["degenerate_triangles"] = t.degenerate_triangles;
    j["isolated_vertices"] = t.isolated_vertices;
    j["normals"] = mesh.has_normals();
    j["colors"] = mesh.has_colors();
    j["texcoords"] = !mesh.texcoords.empty();
    j["bounds"] = bounds_json(bounds);
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  fmt::print("{}\n", path);
  fmt::print("  triangles {}, vertices {}, edges {}{}{}{}\n", t.triangles, t.vertices, t.edges,
             mesh.has_normals() ? ", normals" : "", mesh.has_colors() ? ", colours" : "",
             mesh.texcoords.empty() ? "" : ", texture coordinates");
  fmt::print(
      "  components {}, boundary edges {}, non-manifold edges {}, non-manifold vertices {}, "
      "inconsistently oriented edges {}, degenerate triangles {}, unused vertices {}\n",
      t.components, t.boundary_edges, t.non_manifold_edges, t.non_manifold_vertices,
      t.inconsistent_edges, t.degenerate_triangles, t.isolated_vertices);
  if (!bounds.empty())
    fmt::print("  bounds [{} {} {}] .. [{} {} {}], diagonal {}\n", bounds.lo.x, bounds.lo.y,
               bounds.lo.z, bounds.hi.x, bounds.hi.y, bounds.hi.z, bounds.diagonal());
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, Runner& run) {
  struct Settings {
    std::string input;
    bool json = false;
    SceneReadSettings read;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Show what a VRML 1.0, Open Inventor, VRML97, X3D classic or glTF scene, or a mesh file, "
      "holds");
  cmd->add_option(
         "SCENE", s->input,
         "VRML 1.0 or Inventor file (.wrl, .iv, optionally .gz; - = stdin), VRML97 or X3D "
         "classic or XML (.wrl, .x3dv, .x3d, optionally .gz), glTF (.gltf, .glb), or a mesh (.ply, "
         ".obj, .off, .stl)")
      ->required();
  cmd->add_flag("--json", s->json, "Print JSON on stdout");
  add_scene_read_options(*cmd, s->read);
  cmd->callback([s, &run] {
    run = [s] {
      if (gltf::is_gltf_path(s->input)) return print_gltf_info(s->input, s->json, s->read.quiet);
      if (is_vrml97_input(s->input)) return print_vrml97_info(s->input, s->json, s->read.quiet);
      if (!is_scene_path(s->input) && format_from_path(s->input) != MeshFormat::kAuto)
        return mesh_info(s->input, s->json);
      SceneReadSettings read = s->read;
      read.quiet = read.quiet || s->json;
      vrml1::ReadResult r = read_scene(s->input, read);
      scene::SceneStatistics st = scene::scene_statistics(r.scene);
      auto count = [&](const char* t) {
        auto it = st.node_counts.find(t);
        return it == st.node_counts.end() ? std::size_t(0) : it->second;
      };
      const char* shapes[] = {"IndexedFaceSet", "IndexedLineSet", "Cylinder",
                              "Cone",           "Sphere",         "Cube"};
      // Open Inventor's, shown when the scene has them.
      const char* inventor_shapes[] = {"FaceSet", "TriangleStripSet", "IndexedTriangleStripSet",
                                       "QuadMesh", "LineSet"};
      if (s->json) {
        nlohmann::ordered_json j;
        j["file"] = s->input;
        j["header"] = r.scene.header;
        j["node_counts"] = st.node_counts;
        for (const char* t : shapes) j["shapes"][t] = count(t);
        for (const char* t : inventor_shapes)
          if (count(t)) j["shapes"][t] = count(t);
        j["shapes_traversed"] = st.shapes_traversed;
        j["ifs_faces"] = st.ifs_faces;
        j["ifs_triangles"] = st.ifs_triangles;
        j["ils_segments"] = st.ils_segments;
        j["coordinate_points"] = st.coordinate_points;
        j["triangles"] = st.total_triangles;
        j["vertices"] = st.total_vertices;
        j["bounds"] = bounds_json(st.bounds);
        std::vector<std::string> warnings;
        for (const auto& d : r.log.entries()) warnings.push_back(d.text);
        for (const auto& p : st.problems) warnings.push_back(p);
        j["warnings"] = warnings;
        fmt::print("{}\n", j.dump(2));
        return 0;
      }
      for (const auto& p : st.problems) fmt::print(stderr, "warning: {}\n", p);
      fmt::print("{}\n", s->input);
      fmt::print(
          "  IndexedFaceSets {}, IndexedLineSets {}, Cylinders {}, Cones {}, Spheres {}, "
          "Cubes {}\n",
          count("IndexedFaceSet"), count("IndexedLineSet"), count("Cylinder"), count("Cone"),
          count("Sphere"), count("Cube"));
      std::string more;
      for (const char* t : inventor_shapes)
        if (count(t)) more += fmt::format("{}{}s {}", more.empty() ? "" : ", ", t, count(t));
      if (!more.empty()) fmt::print("  {}\n", more);
      fmt::print("  triangles {} (IndexedFaceSets {} in {} faces), vertices {}, line segments {}\n",
                 st.total_triangles, st.ifs_triangles, st.ifs_faces, st.total_vertices,
                 st.ils_segments);
      if (!st.bounds.empty())
        fmt::print("  bounds [{} {} {}] .. [{} {} {}], diagonal {}\n", st.bounds.lo.x,
                   st.bounds.lo.y, st.bounds.lo.z, st.bounds.hi.x, st.bounds.hi.y, st.bounds.hi.z,
                   st.bounds.diagonal());
      fmt::print("  nodes:");
      for (const auto& [type, n] : st.node_counts) fmt::print(" {} {},", type, n);
      fmt::print("\n");
      return 0;
    };
  });
}

}  // namespace lodforge::apps
