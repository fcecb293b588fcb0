#include "lodforge/apps/lod_vrml97.h"

#include "lodforge/apps/common_options.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <unordered_set>

#include "lodforge/apps/info_vrml97.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/scene_to_gltf.h"
#include "lodforge/io/gltf/write_gltf.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/io/vrml97/write_x3d_xml.h"
#include "lodforge/lod/flatten_vrml97.h"
#include "lodforge/lod/generate_lod_vrml97.h"
#include "lodforge/lod/vrml97_geometry.h"

namespace lodforge::apps {
namespace {

bool ends_with(const std::string& s, std::string_view e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

// The names of VRML97 and X3D files (after a .gz).
constexpr std::string_view kVrml97FamilySuffixes[] = {".wrl",   ".wrz", ".x3dv",
                                                      ".x3dvz", ".x3d", ".x3dz"};

// VRML97's access keywords of interface declarations, and X3D's for them.
constexpr std::pair<std::string_view, std::string_view> kAccessNames[] = {
    {"field", "initializeOnly"},
    {"exposedField", "inputOutput"},
    {"eventIn", "inputOnly"},
    {"eventOut", "outputOnly"},
};

// `text` (a PROTO or EXTERNPROTO kept verbatim) with the access keywords
// outside strings and comments replaced: VRML97's by X3D's (`to_x3d`), or
// X3D's by VRML97's.
std::string access_names(std::string_view text, bool to_x3d) {
  std::string out;
  out.reserve(text.size());
  auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '"' || c == '#') {  // a string or a comment, copied as it is
      std::size_t end = i + 1;
      while (end < text.size() && text[end] != (c == '"' ? '"' : '\n')) {
        if (c == '"' && text[end] == '\\') ++end;
        ++end;
      }
      end = std::min(end + 1, text.size());
      out.append(text.substr(i, end - i));
      i = end;
      continue;
    }
    if (word_char(c) && (i == 0 || !word_char(text[i - 1]))) {
      std::size_t end = i;
      while (end < text.size() && word_char(text[end])) ++end;
      std::string_view word = text.substr(i, end - i);
      for (const auto& [vrml, x3d] : kAccessNames)
        if (word == (to_x3d ? vrml : x3d)) {
          word = to_x3d ? x3d : vrml;
          break;
        }
      out.append(word);
      i = end;
      continue;
    }
    out += c;
    ++i;
  }
  return out;
}

// A node's interface declarations (PROTO bodies, Script and shader fields)
// in X3D's access names (`to_x3d`) or VRML97's.
void rename_access(scene::Node& n, bool to_x3d) {
  if (n.statement && (n.type == "PROTO" || n.type == "EXTERNPROTO"))
    n.raw_body = access_names(n.raw_body, to_x3d);
  for (auto& f : n.fields)
    if (f.name.find(' ') != std::string::npos || f.name == "PROTO" || f.name == "EXTERNPROTO") {
      f.name = access_names(f.name, to_x3d);
      f.raw = access_names(f.raw, to_x3d);
    }
}

// A VRML97 scene as X3D classic: the header and profile X3D requires, LOD's
// `level` renamed `children`, and interface declarations (of PROTOs and
// Scripts) in X3D's access names.
void vrml97_to_x3d(scene::Scene& s) {
  s.header = "#X3D V3.0 utf8";
  auto profile = scene::make_node("PROFILE");
  profile->statement = true;
  profile->raw_body = "Immersive";
  s.roots.insert(s.roots.begin(), std::move(profile));
  std::unordered_set<const scene::Node*> done;
  std::function<void(const scene::NodePtr&)> walk = [&](const scene::NodePtr& n) {
    if (!n || !done.insert(n.get()).second) return;
    rename_access(*n, true);
    for (auto& f : n->fields) {
      if (n->type == "LOD" && f.name == "level") f.name = "children";
      for (const auto& c : f.value.nodes) walk(c);
    }
  };
  for (const auto& r : s.roots) walk(r);
}

// VRML97's 54 node types (ISO/IEC 14772-1, 6).
constexpr std::string_view kVrml97Nodes[] = {"Anchor",
                                             "Appearance",
                                             "AudioClip",
                                             "Background",
                                             "Billboard",
                                             "Box",
                                             "Collision",
                                             "Color",
                                             "ColorInterpolator",
                                             "Cone",
                                             "Coordinate",
                                             "CoordinateInterpolator",
                                             "Cylinder",
                                             "CylinderSensor",
                                             "DirectionalLight",
                                             "ElevationGrid",
                                             "Extrusion",
                                             "Fog",
                                             "FontStyle",
                                             "Group",
                                             "ImageTexture",
                                             "IndexedFaceSet",
                                             "IndexedLineSet",
                                             "Inline",
                                             "LOD",
                                             "Material",
                                             "MovieTexture",
                                             "NavigationInfo",
                                             "Normal",
                                             "NormalInterpolator",
                                             "OrientationInterpolator",
                                             "PixelTexture",
                                             "PlaneSensor",
                                             "PointLight",
                                             "PointSet",
                                             "PositionInterpolator",
                                             "ProximitySensor",
                                             "ScalarInterpolator",
                                             "Script",
                                             "Shape",
                                             "Sound",
                                             "Sphere",
                                             "SphereSensor",
                                             "SpotLight",
                                             "Switch",
                                             "Text",
                                             "TextureCoordinate",
                                             "TextureTransform",
                                             "TimeSensor",
                                             "TouchSensor",
                                             "Transform",
                                             "Viewpoint",
                                             "VisibilitySensor",
                                             "WorldInfo"};

// An X3D IndexedTriangleSet, TriangleSet or IndexedQuadSet made the
// IndexedFaceSet that draws the same faces (its attributes, indexed like the
// coordinates, need no index of their own); false for any other node.
bool as_indexed_face_set(scene::Node& n) {
  if (n.type != "IndexedTriangleSet" && n.type != "TriangleSet" && n.type != "IndexedQuadSet")
    return false;
  const std::size_t per = vrml97_geometry::corners_per_face(n);
  const std::vector<std::int32_t> order = vrml97_geometry::set_corner_order(n);
  std::vector<std::int32_t> faces;
  for (std::size_t f = 0; f + per <= order.size(); f += per) {
    faces.insert(faces.end(), order.begin() + std::ptrdiff_t(f),
                 order.begin() + std::ptrdiff_t(f + per));
    faces.push_back(-1);
  }
  std::erase_if(n.fields, [](const scene::Field& f) { return f.name == "index"; });
  n.type = "IndexedFaceSet";
  n.set("coordIndex", scene::make_longs(std::move(faces)));
  return true;
}

// An X3D classic scene as VRML97: the header, LOD's `children` as `level`
// and Switch's as `choice`, VRML97's access names, and without the header
// statements VRML97 has not (PROFILE, COMPONENT, META, UNIT, IMPORT,
// EXPORT) and `metadata` fields, and its triangle and quad sets as
// IndexedFaceSets. Other node types VRML97 has not (and no PROTO of the file declares) are
// kept and named in a warning: a VRML97 reader will not know them.
void x3d_to_vrml97(scene::Scene& s, Log& log) {
  s.header = "#VRML V2.0 utf8";
  std::map<std::string, std::size_t> dropped, unknown, converted;
  std::set<std::string> protos;
  std::erase_if(s.roots, [&](const scene::NodePtr& n) {
    static constexpr std::string_view kHeaderStatements[] = {"PROFILE", "COMPONENT", "META",
                                                             "UNIT",    "IMPORT",    "EXPORT"};
    if (!n->statement) return false;
    if (n->type == "PROTO" || n->type == "EXTERNPROTO") {
      std::istringstream body(n->raw_body);
      std::string name;
      body >> name;
      protos.insert(name);
    }
    const bool header = std::find(std::begin(kHeaderStatements), std::end(kHeaderStatements),
                                  n->type) != std::end(kHeaderStatements);
    if (header) ++dropped[n->type];
    return header;
  });
  std::unordered_set<const scene::Node*> done;
  std::function<void(const scene::NodePtr&)> walk = [&](const scene::NodePtr& n) {
    if (!n || !done.insert(n.get()).second) return;
    rename_access(*n, false);
    const std::string type = n->type;
    if (as_indexed_face_set(*n)) ++converted[type];
    if (std::erase_if(n->fields, [](const scene::Field& f) { return f.name == "metadata"; }))
      ++dropped["metadata field"];
    if (!n->statement && !protos.count(n->type) &&
        std::find(std::begin(kVrml97Nodes), std::end(kVrml97Nodes), n->type) ==
            std::end(kVrml97Nodes))
      ++unknown[n->type];
    for (auto& f : n->fields) {
      if (n->type == "LOD" && f.name == "children") f.name = "level";
      if (n->type == "Switch" && f.name == "children") f.name = "choice";
      for (const auto& c : f.value.nodes) walk(c);
    }
  };
  for (const auto& r : s.roots) walk(r);
  auto list = [](const std::map<std::string, std::size_t>& m) {
    std::string out;
    for (const auto& [type, n] : m)
      out += fmt::format("{}{} ({})", out.empty() ? "" : ", ", type, n);
    return out;
  };
  if (!dropped.empty())
    log.warn(LogCategory::kParse,
             fmt::format("X3D statements and fields VRML97 has not, left out: {}", list(dropped)));
  if (!converted.empty())
    log.warn(LogCategory::kParse,
             fmt::format("X3D geometry written as VRML97 IndexedFaceSets: {}", list(converted)));
  if (!unknown.empty())
    log.warn(LogCategory::kParse,
             fmt::format("X3D node types VRML97 has not, kept as they are (a VRML97 reader may "
                         "refuse them): {}",
                         list(unknown)));
}

}  // namespace

bool is_vrml97_input(const std::string& path) {
  if (path == "-") return false;
  if (ends_with(path, ".x3dv") || vrml97::is_x3d_xml_path(path)) return true;
  // (Of a gzip file, .wrl.gz or .wrz, the header of what it holds; an X3D
  // XML document by its root element.)
  const std::string head = read_head(path, 512);
  const std::size_t first = head.find('<');
  const bool xml = first != std::string::npos &&
                   head.find_first_not_of(" \t\r\n\xEF\xBB\xBF") == first &&
                   head.find("<X3D") != std::string::npos;
  return xml || vrml97::is_vrml97_header(head);
}

bool writes_x3d_xml(const std::string& output, const std::string& format) {
  return format == "x3d" || (format.empty() && vrml97::is_x3d_xml_path(output));
}

vrml97::ReadResult read_vrml97_as(const std::string& input, const std::string& output,
                                  const std::string& format) {
  vrml97::ReadResult r = read_vrml97_input(input);
  const bool x3d_in = vrml97::is_x3d_header(r.scene.header);
  std::string to = format;
  if (to.empty())
    to = ends_with(output, ".x3dv") || ends_with(output, ".x3dv.gz") ? "x3dv"
         : writes_x3d_xml(output, format)                            ? "x3d"
                                                                     : "";
  if (to == "vrml97" && x3d_in) x3d_to_vrml97(r.scene, r.log);  // .wrl alone keeps X3D
  if ((to == "x3dv" || to == "x3d") && !x3d_in) vrml97_to_x3d(r.scene);
  return r;
}

bool writes_vrml97_family(const std::string& output, const std::string& format) {
  if (!format.empty()) return format == "vrml97" || format == "x3dv" || format == "x3d";
  return std::any_of(std::begin(kVrml97FamilySuffixes), std::end(kVrml97FamilySuffixes),
                     [&](std::string_view e) { return name_ends_with(output, e); });
}

bool writes_gltf(const std::string& output, const std::string& format) {
  return format == "gltf" || format == "glb" || (format.empty() && gltf::is_gltf_path(output));
}

void warn_unused_writer_options(const vrml1::WriteOptions& write, const std::string& input,
                                const std::string& output, const std::string& format, Log& log) {
  const bool gltf = writes_gltf(output, format) ||
                    (gltf::is_gltf_path(input) && !writes_vrml97_family(output, format));
  if (!gltf && !writes_x3d_xml(output, format)) return;
  const vrml1::WriteOptions d;
  std::vector<std::string> given;
  if (write.floats_per_line != d.floats_per_line) given.push_back("--floats-per-line");
  if (write.ints_per_line != d.ints_per_line) given.push_back("--ints-per-line");
  if (write.no_tabs) given.push_back("--no-tabs");
  if (write.minimize) given.push_back("--minimize");
  if (given.empty()) return;
  log.warn(LogCategory::kGeneral, fmt::format("{} {} not used for {}", fmt::join(given, ", "),
                                              given.size() == 1 ? "is" : "are",
                                              gltf ? "a glTF output" : "an X3D XML output"));
}

void write_vrml97_as(const scene::Scene& scene, const std::string& input, const std::string& output,
                     const std::string& format, double camera_angle, Log& log,
                     const vrml1::WriteOptions& write) {
  if (writes_gltf(output, format)) {
    const Vrml97LodShapes shapes = vrml97_lod_shapes(scene, log);
    if (!shapes.skipped.empty()) {
      std::string list;
      for (const auto& [type, n] : shapes.skipped)
        list += fmt::format("{}{} ({})", list.empty() ? "" : ", ", type, n);
      log.warn(LogCategory::kParse, fmt::format("not drawn, so not in the glTF output: {}", list));
    }
    if (camera_angle <= 0)
      camera_angle = viewpoint_field_of_view(scene).value_or(kDefaultFieldOfView);
    const std::filesystem::path in(input), out(output);
    gltf::GltfScene g = gltf::lod_shapes_to_gltf(
        shapes.shapes,
        {.camera_angle = camera_angle,
         .base_dir = input == "-" || !in.has_parent_path() ? "." : in.parent_path().string()},
        log);
    gltf::write_gltf_file(
        std::move(g), output,
        {.binary = format.empty() ? !output.ends_with(".gltf") && !output.ends_with(".gltf.gz")
                                  : format == "glb",
         .output_dir = output == "-" || !out.has_parent_path() ? "." : out.parent_path().string()});
  } else if (writes_x3d_xml(output, format)) {
    vrml97::write_x3d_xml_file(scene, output);
  } else {
    vrml97::write_vrml97_file(scene, output, write);
  }
}

LodResult lod_vrml97_file(const std::string& input, const std::string& output,
                          const std::string& format, const LodOptions& options, bool quiet,
                          const vrml1::WriteOptions& write) {
  vrml97::ReadResult r = read_vrml97_as(input, output, format);
  LodResult result = generate_lod_vrml97(std::move(r.scene), options);
  result.log.merge(r.log);
  // A glTF output takes its images from the input's folder instead.
  if (!writes_gltf(output, format)) relocate_to_output(result.scene, input, output, quiet);
  write_vrml97_as(result.scene, input, output, format, result.camera_angle, result.log, write);
  return result;
}

}  // namespace lodforge::apps
