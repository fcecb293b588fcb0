// `lodforge info SCENE [--json]`: what a scene holds — node counts per type,
// the shape counts the original tool showed, vertices, triangles, bounds.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/info_gltf.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/scene/statistics.h"

namespace lodforge::apps {

void add_info_command(CLI::App& app, Runner& run) {
  struct Settings {
    std::string input;
    bool json = false;
    SceneReadSettings read;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand("info", "Show what a VRML 1.0 or Open Inventor scene holds");
  cmd->add_option(
         "SCENE", s->input,
         "VRML 1.0 or Inventor file (.wrl, .iv, optionally .gz; - = stdin), or glTF (.gltf, .glb)")
      ->required();
  cmd->add_flag("--json", s->json, "Print JSON on stdout");
  add_scene_read_options(*cmd, s->read);
  cmd->callback([s, &run] {
    run = [s] {
      if (gltf::is_gltf_path(s->input)) return print_gltf_info(s->input, s->json, s->read.quiet);
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
        if (!st.bounds.empty()) {
          j["bounds"]["min"] = {st.bounds.lo.x, st.bounds.lo.y, st.bounds.lo.z};
          j["bounds"]["max"] = {st.bounds.hi.x, st.bounds.hi.y, st.bounds.hi.z};
          j["bounds"]["diagonal"] = st.bounds.diagonal();
        } else {
          j["bounds"] = nullptr;
        }
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
