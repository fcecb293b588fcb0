#include "lodforge/apps/lod_vrml97.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/lod/generate_lod_vrml97.h"

namespace lodforge::apps {
namespace {

bool ends_with(const std::string& s, std::string_view e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

// VRML97's access keywords of interface declarations, and X3D's for them.
constexpr std::pair<std::string_view, std::string_view> kAccessNames[] = {
    {"field", "initializeOnly"},
    {"exposedField", "inputOutput"},
    {"eventIn", "inputOnly"},
    {"eventOut", "outputOnly"},
};

// `text` (a PROTO or EXTERNPROTO kept verbatim) with the VRML97 access
// keywords outside strings and comments replaced by X3D's.
std::string x3d_access_names(std::string_view text) {
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
        if (word == vrml) word = x3d;
      out.append(word);
      i = end;
      continue;
    }
    out += c;
    ++i;
  }
  return out;
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
    if (n->statement && (n->type == "PROTO" || n->type == "EXTERNPROTO"))
      n->raw_body = x3d_access_names(n->raw_body);
    for (auto& f : n->fields) {
      if (n->type == "LOD" && f.name == "level") f.name = "children";
      if (f.name.find(' ') != std::string::npos || f.name == "PROTO" || f.name == "EXTERNPROTO") {
        f.name = x3d_access_names(f.name);
        f.raw = x3d_access_names(f.raw);
      }
      for (const auto& c : f.value.nodes) walk(c);
    }
  };
  for (const auto& r : s.roots) walk(r);
}

}  // namespace

bool is_vrml97_input(const std::string& path) {
  if (path == "-") return false;
  if (ends_with(path, ".x3dv") || ends_with(path, ".x3d")) return true;
  // (Of a gzip file, .wrl.gz or .wrz, the header of what it holds.)
  return vrml97::is_vrml97_header(read_head(path, 16));
}

vrml97::ReadResult read_vrml97_as(const std::string& input, const std::string& output,
                                  const std::string& format) {
  if (ends_with(input, ".x3d"))
    throw DataError("X3D XML encoding (.x3d) is not read yet; convert it to .x3dv");
  vrml97::ReadResult r = vrml97::read_vrml97_file(input);
  const bool x3d_in = vrml97::is_x3d_header(r.scene.header);
  std::string to = format;
  if (to.empty()) to = ends_with(output, ".x3dv") ? "x3dv" : ends_with(output, ".x3d") ? "x3d" : "";
  if (to == "x3d")
    throw DataError("writing X3D XML encoding (.x3d) is not supported yet; use .x3dv");
  if (to == "vrml97" && x3d_in)  // .wrl without --format keeps X3D
    throw DataError("writing an X3D scene as VRML97 is not supported; use .x3dv");
  if (to == "x3dv" && !x3d_in) vrml97_to_x3d(r.scene);
  return r;
}

LodResult lod_vrml97_file(const std::string& input, const std::string& output,
                          const std::string& format, const LodOptions& options) {
  vrml97::ReadResult r = read_vrml97_as(input, output, format);
  LodResult result = generate_lod_vrml97(std::move(r.scene), options);
  result.log.merge(r.log);
  vrml97::write_vrml97_file(result.scene, output);
  return result;
}

}  // namespace lodforge::apps
