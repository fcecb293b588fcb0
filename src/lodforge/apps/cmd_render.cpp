// `lodforge render SCENE_OR_MESH -o OUT.png [--level K | --levels] [--size WxH]
// [--view azimuth,elevation] [--no-colors] [--wireframe] [--flat]`: a headless
// picture of a mesh file (PLY, OBJ, OFF, STL) with its vertex colours, so a
// `compare --colored` output shows where the error is, or of a VRML 1.0 scene
// (flattened at LOD level K), or with --levels a contact sheet of every LOD
// level side by side with its triangle count and switch distance under it
// (the original's Figure 5.5).
#include <fmt/core.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/render/contact_sheet.h"
#include "lodforge/render/render_mesh.h"
#include "lodforge/render/write_png.h"
#include "lodforge/scene/flatten_scene.h"

namespace lodforge::apps {
namespace {

constexpr int kMaxSide = 8192;

// "640x480" -> width, height in 1..kMaxSide; false if malformed.
bool parse_size(std::string_view text, int& width, int& height) {
  const auto x = text.find_first_of("xX");
  if (x == std::string_view::npos) return false;
  const auto parse = [](std::string_view part, int& out) {
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
    return ec == std::errc{} && end == part.data() + part.size() && out >= 1 && out <= kMaxSide;
  };
  return parse(text.substr(0, x), width) && parse(text.substr(x + 1), height);
}

// "30,-15" -> azimuth, elevation in degrees (elevation -90..90); false if malformed.
bool parse_view(const std::string& text, float& azimuth, float& elevation) {
  const auto comma = text.find(',');
  if (comma == std::string::npos) return false;
  try {
    std::size_t used_a = 0, used_e = 0;
    azimuth = std::stof(text.substr(0, comma), &used_a);
    elevation = std::stof(text.substr(comma + 1), &used_e);
    return used_a == comma && used_e == text.size() - comma - 1 && std::isfinite(azimuth) &&
           std::isfinite(elevation) && elevation >= -90 && elevation <= 90;
  } catch (const std::exception&) {
    return false;
  }
}

// One panel per LOD level of a scene, all seen by the same camera.
template <typename Settings>
int render_levels(const Settings& s, const RenderOptions& options) {
  if (!is_vrml_path(s.input))
    throw DataError(fmt::format("{}: --levels needs a VRML 1.0 scene with LOD nodes", s.input));
  vrml1::ReadResult r = read_scene(s.input, {});
  SceneLevels levels = scene_levels(r.scene);
  std::vector<TriangleMesh> meshes;
  std::vector<ContactSheetPanel> panels;
  for (std::size_t k = 0; k < levels.count; ++k)
    meshes.push_back(scene::flatten_scene(r.scene, {.lod_level = int(k)}));
  for (std::size_t k = 0; k < levels.count; ++k) {
    float from = k == 0 ? 0.f : (k - 1 < levels.ranges.size() ? levels.ranges[k - 1] : 0.f);
    panels.push_back({&meshes[k], lod_level_labels(k, meshes[k].triangle_count(), from)});
  }
  const ContactSheetResult sheet = render_contact_sheet(panels, {.panel = options});
  write_png(sheet.image, s.output);
  fmt::print(stderr, "render: {} ({}x{}, {} levels)\n", s.output, sheet.image.width,
             sheet.image.height, levels.count);
  return 0;
}

}  // namespace

void add_render_command(CLI::App& app, Runner& run) {
  struct Settings {
    std::string input;
    std::string output;
    std::string size = "640x480";
    std::string view = "30,20";
    bool no_colors = false;
    bool wireframe = false;
    bool flat = false;
    int level = 0;
    bool levels = false;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd =
      app.add_subcommand("render", "Render a mesh or a scene to a PNG picture (headless)");
  cmd->add_option("SCENE_OR_MESH", s->input, "VRML 1.0 scene or mesh file (PLY, OBJ, OFF, STL)")
      ->required();
  auto* level = cmd->add_option("--level", s->level, "LOD level to render (scenes; 0 = finest)")
                    ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--levels", s->levels,
                "Contact sheet of every LOD level with triangles and switch distance (scenes)")
      ->excludes(level);
  cmd->add_option("-o,--output", s->output, "Output PNG file (- = stdout)")->required();
  cmd->add_option("--size", s->size, "Picture size in pixels, WxH (each 1..8192)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& v) {
            int w, h;
            return parse_size(v, w, h) ? std::string{}
                                       : "expected WxH with W and H in 1..8192, e.g. 640x480";
          },
          "WxH", "size"));
  cmd->add_option("--view", s->view,
                  "Camera azimuth,elevation in degrees (0,0 looks along -Z; elevation -90..90)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& v) {
            float a, e;
            return parse_view(v, a, e)
                       ? std::string{}
                       : "expected azimuth,elevation in degrees with elevation in -90..90, "
                         "e.g. 30,20";
          },
          "AZ,EL", "view"));
  cmd->add_flag("--no-colors", s->no_colors, "Ignore the mesh's vertex colours");
  cmd->add_flag("--wireframe", s->wireframe, "Draw triangle edges over the surface");
  cmd->add_flag("--flat", s->flat, "Flat shading (one normal per triangle)");
  cmd->callback([s, &run] {
    run = [s] {
      RenderOptions options;
      parse_size(s->size, options.width, options.height);  // validated by CLI11
      parse_view(s->view, options.azimuth, options.elevation);
      options.use_colors = !s->no_colors;
      options.wireframe = s->wireframe;
      options.shading = s->flat ? Shading::kFlat : Shading::kSmooth;
      if (s->levels) return render_levels(*s, options);
      const TriangleMesh mesh = load_geometry(s->input, s->level);
      if (mesh.triangles.empty() && mesh.lines.empty())
        throw DataError(fmt::format("{}: the mesh has no triangles or lines to render", s->input));
      const RenderResult r = render_mesh(mesh, options);
      write_png(r.image, s->output);
      fmt::print(stderr, "render: {} ({}x{}, {} triangles, {} line segments drawn)\n", s->output,
                 r.image.width, r.image.height, r.triangles_drawn, r.lines_drawn);
      return 0;
    };
  });
}

}  // namespace lodforge::apps
