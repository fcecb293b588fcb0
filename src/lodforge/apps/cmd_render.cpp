// `lodforge render SCENE_OR_MESH -o OUT.png [--level K | --levels |
// --distances d1,d2,...] [--size WxH] [--view azimuth,elevation] [--no-colors]
// [--no-textures] [--wireframe] [--flat]`: a headless picture of a mesh file
// (PLY, OBJ, OFF, STL) with its vertex colours, so a `compare --colored`
// output shows where the error is, or of a VRML 1.0 / Inventor scene
// (flattened at LOD level K) in its materials' colours and its textures, or with --levels
// a contact sheet of every LOD level side by side with its triangle count
// under it (the original's Figure 5.5), or with --distances what a browser
// shows from each distance (every LOD choosing by its own distance; a glTF
// node its MSFT_lod level by screen coverage) beside the same view at full
// detail, so popping shows.
#include <fmt/core.h>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/info_vrml97.h"
#include "lodforge/apps/load_geometry.h"
#include "lodforge/apps/lod_vrml97.h"
#include "lodforge/core/error.h"
#include "lodforge/core/output_path.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/metrics/colorize_deviation.h"
#include "lodforge/render/color_bar.h"
#include "lodforge/render/contact_sheet.h"
#include "lodforge/render/render_mesh.h"
#include "lodforge/render/texture_image.h"
#include "lodforge/render/write_png.h"
#include "lodforge/scene/flatten_scene.h"
#include "lodforge/scene/schema.h"

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

// "2,10.5,40" -> the distances, each finite and > 0. Throws DataError (exit
// 1) naming the bad item.
std::vector<double> parse_distances(const std::string& text) {
  const auto bad = [](std::string_view why) {
    return DataError(fmt::format(
        "--distances: {}; expected positive numbers separated by commas, e.g. 2,10,40", why));
  };
  if (text.empty()) throw bad("the list is empty");
  std::vector<double> out;
  for (std::size_t begin = 0; begin <= text.size();) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string_view item = std::string_view(text).substr(begin, end - begin);
    double d = 0;
    const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), d);
    if (item.empty() || ec != std::errc{} || ptr != item.data() + item.size() || !std::isfinite(d))
      throw bad(fmt::format("'{}' is not a number", item));
    if (d <= 0) throw bad(fmt::format("{} is not a distance > 0", item));
    out.push_back(d);
    begin = end + 1;
  }
  return out;
}

// The images of flattened scenes' textures. A file name is relative to the
// folder of the scene file; a file read once serves every level. A texture
// that cannot be read is a warning naming it (once), and its triangles are
// drawn in their surface colour.
class TextureLoader {
 public:
  TextureLoader(const std::string& scene_path, bool enabled, bool quiet)
      : folder_(scene_path == "-" ? std::filesystem::path(".")
                                  : std::filesystem::path(scene_path).parent_path()),
        scene_(scene_path == "-" ? "<stdin>" : scene_path),
        enabled_(enabled),
        quiet_(quiet) {}

  std::vector<Texture> load(const std::vector<scene::SceneTexture>& textures) {
    std::vector<Texture> out;
    if (!enabled_) return out;
    for (const scene::SceneTexture& t : textures) {
      Texture image;
      try {
        image = !t.encoded.empty()   ? decode_texture(t.encoded, scene_ + ": embedded image")
                : t.filename.empty() ? sfimage_texture(t.image)
                                     : file(t.filename);
      } catch (const DataError& e) {
        warn(t, e.what());
      }
      image.repeat_s = t.repeat_s;
      image.repeat_t = t.repeat_t;
      image.modulates = t.modulates;
      image.alpha_cutoff = t.alpha_cutoff;
      out.push_back(std::move(image));
    }
    return out;
  }

 private:
  Texture file(const std::string& name) {
    if (name.find("://") != std::string::npos)
      throw DataError(fmt::format("texture {}: URLs are not fetched", name));
    const std::filesystem::path path = folder_ / name;
    auto it = files_.find(path.string());
    if (it == files_.end()) {
      try {
        it = files_.emplace(path.string(), read_texture(path.string())).first;
      } catch (const DataError&) {
        files_.emplace(path.string(), Texture{});
        throw;
      }
    }
    return it->second;
  }

  void warn(const scene::SceneTexture& t, const std::string& why) {
    const std::string key = t.filename.empty() ? std::to_string(t.line) : t.filename;
    if (quiet_ || !warned_.insert(key).second) return;
    fmt::print(stderr, "warning: {}:{}: Texture2 {}: {}; drawn without it\n", scene_, t.line,
               t.filename.empty() ? "image" : t.filename, why);
  }

  std::filesystem::path folder_;
  std::string scene_;
  bool enabled_, quiet_;
  std::map<std::string, Texture> files_;
  std::set<std::string> warned_;
};

// A flattened scene with its texture images, ready to draw.
struct Drawing {
  scene::FlatScene flat;
  std::vector<Texture> textures;
  Appearance appearance() const { return {.textures = textures, .opacity = flat.opacity}; }
};

Drawing drawing(scene::FlatScene flat, TextureLoader& loader) {
  Drawing d{std::move(flat), {}};
  d.textures = loader.load(d.flat.textures);
  return d;
}

// The VRML 1.0 / Inventor scene of a contact sheet showing its LOD nodes.
scene::Scene read_lod_scene(const std::string& path, std::string_view option,
                            const SceneReadSettings& read) {
  if (!is_scene_path(path) && format_from_path(path) != MeshFormat::kAuto)
    throw DataError(
        fmt::format("{}: {} needs a scene with LOD nodes (VRML 1.0, Inventor, VRML97, X3D or glTF)",
                    path, option));
  return read_scene(path, read).scene;
}

void write_sheet(std::span<const ContactSheetPanel> panels, const ContactSheetOptions& options,
                 const std::string& output, std::string_view what) {
  const ContactSheetResult sheet = render_contact_sheet(panels, options);
  write_png(sheet.image, output);
  fmt::print(stderr, "render: {} ({}x{}, {})\n", output, sheet.image.width, sheet.image.height,
             what);
}

// Panels per row of a sheet of `n` panels: up to four in one row, then rows
// of about equal length.
int sheet_columns(std::size_t n) {
  if (n <= 4) return int(n);
  return int(std::ceil(std::sqrt(double(n))));
}

// One panel per LOD level of a scene, all seen by the same camera.
int render_levels(const std::string& input, const std::string& output, const RenderOptions& options,
                  const SceneReadSettings& read, TextureLoader& loader) {
  std::vector<Drawing> levels;
  if (gltf::is_gltf_path(input)) {
    for (scene::FlatScene& flat : load_gltf_levels(input, read))
      levels.push_back(drawing(std::move(flat), loader));
  } else if (is_vrml97_input(input)) {
    const vrml97::ReadResult scene = read_vrml97_input(input);
    const std::size_t count = vrml97_lod_level_count(scene.scene);
    for (std::size_t k = 0; k < count; ++k)
      levels.push_back(drawing(
          flatten_vrml97_input(scene, input, {.lod_level = int(k)}, read.quiet || k > 0).flat,
          loader));
  } else {
    const scene::Scene scene = read_lod_scene(input, "--levels", read);
    const std::size_t count = scene::lod_level_count(scene);
    for (std::size_t k = 0; k < count; ++k)
      levels.push_back(
          drawing(scene::flatten_scene_appearance(scene, {.lod_level = int(k)}), loader));
  }
  const std::size_t count = levels.size();
  std::vector<ContactSheetPanel> panels;
  for (std::size_t k = 0; k < count; ++k)
    panels.push_back({.mesh = &levels[k].flat.mesh,
                      .labels = lod_labels(levels[k].flat.mesh.triangle_count(), k),
                      .appearance = levels[k].appearance()});
  write_sheet(panels, {.panel = options, .columns = sheet_columns(count)}, output,
              fmt::format("{} levels", count));
  return 0;
}

// The vertical angle of view: the scene's first PerspectiveCamera's
// heightAngle, else the VRML default, pi/4.
float height_angle(const scene::Scene& scene) {
  const scene::Node* camera = nullptr;
  scene::traverse(scene, [&](const scene::ShapeVisit& v) {
    if (!camera) camera = v.camera;
  });
  const scene::FieldValue* a = camera ? scene::field_or_default(*camera, "heightAngle") : nullptr;
  return a && !a->floats.empty() && a->floats[0] > 0 ? a->floats[0] : float(kPi / 4);
}

// One row per distance: the camera that far from the scene's bounding-box
// centre along the --view direction, looking at the centre; on the left every
// LOD choosing its child by its own distance from that eye, on the right every
// LOD at child 0. Each row's cells share its camera, and no cell is re-framed,
// so the scene shrinks with distance as it does in a browser.
int render_distances(const std::string& input, const std::string& output,
                     const std::vector<double>& distances, const RenderOptions& options,
                     const SceneReadSettings& read, TextureLoader& loader) {
  // The scene flattened with every LOD at child 0 (no eye) or as seen from
  // an eye, and its angle of view.
  std::function<scene::FlatScene(std::optional<Vec3>)> flat;
  float angle = 0;
  if (gltf::is_gltf_path(input)) {
    GltfViews views = load_gltf_views(input, read);
    flat = std::move(views.draw);
    angle = views.height_angle;
  } else if (is_vrml97_input(input)) {
    auto scene = std::make_shared<vrml97::ReadResult>(read_vrml97_input(input));
    flat = [&, scene](std::optional<Vec3> eye) {
      return flatten_vrml97_input(*scene, input, {.viewpoint = eye}, read.quiet || eye).flat;
    };
    angle = viewpoint_field_of_view(scene->scene).value_or(kDefaultFieldOfView);
  } else {
    auto scene = std::make_shared<scene::Scene>(read_lod_scene(input, "--distances", read));
    flat = [scene](std::optional<Vec3> eye) {
      return scene::flatten_scene_appearance(*scene, {.lod_level = 0, .viewpoint = eye});
    };
    angle = height_angle(*scene);
  }
  const Drawing level0 = drawing(flat(std::nullopt), loader);
  const FrameSphere bounds = bounding_sphere(level0.flat.mesh);
  if (bounds.radius <= 0)
    throw DataError(fmt::format("{}: the scene has no triangles or lines to render", input));
  const Vec3 towards_eye = view_direction(options.azimuth, options.elevation);
  std::vector<Drawing> chosen;
  std::vector<LookAt> cameras;
  for (const double d : distances) {
    cameras.push_back({.eye = bounds.center + towards_eye * float(d),
                       .target = bounds.center,
                       .height_angle = angle});
    chosen.push_back(drawing(flat(cameras.back().eye), loader));
  }
  std::vector<ContactSheetPanel> panels;
  for (std::size_t i = 0; i < distances.size(); ++i) {
    panels.push_back({&chosen[i].flat.mesh,
                      lod_labels(chosen[i].flat.mesh.triangle_count(), std::nullopt, distances[i]),
                      cameras[i], chosen[i].appearance()});
    panels.push_back({&level0.flat.mesh,
                      lod_labels(level0.flat.mesh.triangle_count(), 0, distances[i]), cameras[i],
                      level0.appearance()});
  }
  write_sheet(panels, {.panel = options, .columns = 2}, output,
              fmt::format("{} distances", distances.size()));
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
    bool no_textures = false;
    double color_bar = 0;
    bool wireframe = false;
    bool flat = false;
    int level = 0;
    bool levels = false;
    std::string distances;
    SceneReadSettings read;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd =
      app.add_subcommand("render", "Render a mesh or a scene to a PNG picture (headless)");
  cmd->add_option("SCENE_OR_MESH", s->input,
                  "VRML 1.0, Open Inventor, VRML97, X3D classic or glTF scene, or mesh file "
                  "(PLY, OBJ, OFF, STL)")
      ->required();
  auto* level = cmd->add_option("--level", s->level, "LOD level to render (scenes; 0 = finest)")
                    ->check(kFiniteNumber)
                    ->check(CLI::NonNegativeNumber);
  auto* levels = cmd->add_flag("--levels", s->levels,
                               "Contact sheet of every LOD level with its triangle count (scenes)")
                     ->excludes(level);
  auto* distances =
      cmd->add_option("--distances", s->distances,
                      "Comma-separated camera distances from the scene's centre, e.g. 2,10,40: one "
                      "row each, every LOD choosing by its own distance (glTF: MSFT_lod by screen "
                      "coverage) beside every LOD at child 0 (scenes)")
          ->excludes(level)
          ->excludes(levels);
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
  cmd->add_flag("--no-colors", s->no_colors,
                "Draw every surface grey: no vertex colours, materials or textures");
  cmd->add_flag("--no-textures", s->no_textures, "Draw a scene's materials without its textures");
  cmd->add_option("--color-bar", s->color_bar,
                  "Draw the deviation scale of 'compare --colored' beside the picture, from 0 "
                  "(blue) to this value (red), e.g. the value compare printed")
      ->check(kFiniteNumber)
      ->check(CLI::PositiveNumber)
      ->excludes(levels)
      ->excludes(distances);
  cmd->add_flag("--wireframe", s->wireframe, "Draw triangle edges over the surface");
  cmd->add_flag("--flat", s->flat, "Flat shading (one normal per triangle)");
  add_expansion_options(*cmd, s->read);
  cmd->callback([s, &run, distances] {
    run = [s, by_distance = distances->count() > 0] {
      RenderOptions options;
      parse_size(s->size, options.width, options.height);  // validated by CLI11
      parse_view(s->view, options.azimuth, options.elevation);
      check_output_paths(std::array{OutputPath{s->output, "the picture"}}, std::array{s->input});
      options.use_colors = !s->no_colors;
      options.wireframe = s->wireframe;
      options.shading = s->flat ? Shading::kFlat : Shading::kSmooth;
      TextureLoader loader(s->input, !s->no_colors && !s->no_textures, s->read.quiet);
      if (s->levels) return render_levels(s->input, s->output, options, s->read, loader);
      if (by_distance)
        return render_distances(s->input, s->output, parse_distances(s->distances), options,
                                s->read, loader);
      const Drawing d = drawing(load_drawing(s->input, s->level, s->read), loader);
      const TriangleMesh& mesh = d.flat.mesh;
      if (mesh.triangles.empty() && mesh.lines.empty())
        throw DataError(fmt::format("{}: the mesh has no triangles or lines to render", s->input));
      options.appearance = d.appearance();
      const RenderResult r = render_mesh(mesh, options);
      write_png(s->color_bar > 0 ? add_deviation_bar(r.image, s->color_bar) : r.image, s->output);
      fmt::print(stderr, "render: {} ({}x{}, {} triangles, {} line segments drawn)\n", s->output,
                 r.image.width, r.image.height, r.triangles_drawn, r.lines_drawn);
      return 0;
    };
  });
}

}  // namespace lodforge::apps
