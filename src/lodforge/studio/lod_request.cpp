#include "lodforge/studio/lod_request.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "lodforge/core/error.h"

namespace lodforge::studio {
namespace {

using nlohmann::json;

const std::array<const char*, 6> kTypes = {"polygon", "line", "sphere", "cone", "cylinder", "cube"};

// Quotes a word for a POSIX shell when it holds anything but safe characters.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string_view("/._-=,+:").find(c) != std::string_view::npos;
  });
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

double number(const json& value, const std::string& key, double low, double high) {
  if (!value.is_number())
    throw DataError(fmt::format("option {}: expected a number, got {}", key, value.dump()));
  const double v = value.get<double>();
  if (!std::isfinite(v) || v < low || v > high)
    throw DataError(fmt::format("option {}: {} is outside [{}, {}]", key, v, low, high));
  return v;
}

// A whole number in [low, high], as `lodforge lod` reads an integer option
// (2.5 is refused, not truncated).
long long whole(const json& value, const std::string& key, double low, double high) {
  const double v = number(value, key, low, high);
  if (v != std::floor(v))
    throw DataError(fmt::format("option {}: expected a whole number, got {}", key, value.dump()));
  return static_cast<long long>(v);
}

std::string text(const json& value, const std::string& key,
                 std::initializer_list<std::string_view> allowed) {
  if (!value.is_string())
    throw DataError(fmt::format("option {}: expected a string, got {}", key, value.dump()));
  const std::string v = value.get<std::string>();
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
    throw DataError(fmt::format("option {}: unknown value '{}'", key, v));
  return v;
}

// "TYPE=value" (TYPE checked) or, when `type_optional`, "value" alone.
std::pair<std::string, std::string> typed(const std::string& item, const std::string& key,
                                          bool type_optional) {
  const auto eq = item.find('=');
  if (eq == std::string::npos) {
    if (type_optional) return {"", item};
    throw DataError(fmt::format("option {}: expected TYPE=N, got '{}'", key, item));
  }
  const std::string type = item.substr(0, eq);
  if (std::find(kTypes.begin(), kTypes.end(), type) == kTypes.end())
    throw DataError(fmt::format(
        "option {}: unknown shape type '{}' (polygon, line, sphere, cone, cylinder, cube)", key,
        type));
  return {type, item.substr(eq + 1)};
}

std::vector<std::string> strings(const json& value, const std::string& key) {
  std::vector<std::string> out;
  if (value.is_string()) return {value.get<std::string>()};
  if (!value.is_array()) throw DataError(fmt::format("option {}: expected a list of strings", key));
  for (const auto& v : value) {
    if (!v.is_string()) throw DataError(fmt::format("option {}: expected strings", key));
    out.push_back(v.get<std::string>());
  }
  return out;
}

std::vector<float> increasing_ranges(const std::string& list, const std::string& key) {
  std::vector<float> v;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = list.find(',', pos);
    const std::string part = list.substr(pos, comma == std::string::npos ? comma : comma - pos);
    char* end = nullptr;
    const float f = std::strtof(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !(f > 0) || !std::isfinite(f))
      throw DataError(fmt::format("option {}: expected positive numbers, got '{}'", key, part));
    if (!v.empty() && f <= v.back())
      throw DataError(fmt::format("option {}: ranges must increase", key));
    v.push_back(f);
    if (comma == std::string::npos) return v;
    pos = comma + 1;
  }
}

bool flag(const json& value, const std::string& key) {
  if (!value.is_boolean()) throw DataError(fmt::format("option {}: expected true or false", key));
  return value.get<bool>();
}

std::string shortest(double v) {
  return fmt::format("{}", v);
}

}  // namespace

LodRequest lod_request(const json& options, const std::string& scene, const std::string& output) {
  if (!options.is_null() && !options.is_object())
    throw DataError("the options must be a JSON object");
  LodRequest r;
  LodOptions& o = r.options;
  std::vector<std::string> args = {"lodforge", "lod", scene, "-o", output};
  const auto arg = [&](const std::string& key, const std::string& value) {
    args.push_back("--" + key);
    if (!value.empty()) args.push_back(value);
  };
  const json empty = json::object();
  for (const auto& [key, value] : (options.is_null() ? empty : options).items()) {
    if (key == "method") {
      const std::string m = text(value, key, {"cluster", "decimate", "qem"});
      o.method = m == "cluster"    ? SimplifyMethod::kCluster
                 : m == "decimate" ? SimplifyMethod::kDecimate
                                   : SimplifyMethod::kQem;
      arg(key, m);
    } else if (key == "error-range") {
      const double v = number(value, key, 0.0001, 100);
      o.range.error_range = float(v / 100);
      arg(key, shortest(v));
    } else if (key == "camera-angle") {
      const double v = number(value, key, 0.0001, 3.14);
      o.range.camera_angle = float(v);
      o.camera_angle_given = true;
      arg(key, shortest(v));
    } else if (key == "min-diff") {
      const double v = number(value, key, 1, 100);
      o.min_diff = float(v / 100);
      arg(key, shortest(v));
    } else if (key == "level-spacing") {
      o.level_spacing = number(value, key, 1, 100);
      arg(key, shortest(o.level_spacing));
    } else if (key == "level-ratio") {
      o.level_ratio = number(value, key, 0.01, 1);
      arg(key, shortest(o.level_ratio));
    } else if (key == "levels") {
      o.max_levels = std::size_t(number(value, key, 2, 1000));
      arg(key, std::to_string(o.max_levels));
    } else if (key == "quality") {
      for (const auto& q : strings(value, key)) {
        const auto [type, n] = typed(q, key, false);
        char* end = nullptr;
        const long v = std::strtol(n.c_str(), &end, 10);
        if (n.empty() || *end != '\0' || v < 0 || v > 1000)
          throw DataError(fmt::format("option quality: expected TYPE=N with N >= 0, got '{}'", q));
        o.manual[type].quality = int(v);
        arg(key, q);
      }
    } else if (key == "ranges") {
      for (const auto& item : strings(value, key)) {
        const auto [type, list] = typed(item, key, true);
        const std::vector<float> v = increasing_ranges(list, key);
        if (type.empty())
          for (const char* t : kTypes) o.manual[t].ranges = v;
        else
          o.manual[type].ranges = v;
        arg(key, item);
      }
    } else if (key == "differentiate-by-size" || key == "join" || key == "no-lines" ||
               key == "no-quads") {
      if (!flag(value, key)) continue;
      if (key == "join") o.join = true;
      if (key == "no-lines") o.no_lines = true;
      if (key == "no-quads") o.triangulation.keep_quads = false;
      if (key == "differentiate-by-size") o.differentiate_by_size = true;
      arg(key, "");
    } else if (key == "quad-split-angle") {
      const double v = number(value, key, 0, 3.1416);
      o.triangulation.quad_split_angle = float(v);
      arg(key, shortest(v));
    } else if (key == "export") {
      const std::string e = text(value, key, {"spec", "performer", "reducer"});
      o.export_flavour = e == "performer" ? ExportFlavour::kPerformer
                         : e == "reducer" ? ExportFlavour::kReducer
                                          : ExportFlavour::kSpec;
      arg(key, e);
    } else if (key == "extract") {
      o.extract = int(number(value, key, -1, 1000));
      arg(key, std::to_string(*o.extract));
    } else if (key == "format") {
      r.format = text(value, key, {"vrml97", "x3dv", "x3d", "gltf", "glb"});
      arg(key, r.format);
    } else if (key == "inline") {
      if (!flag(value, key)) continue;
      r.read.read_inlines = true;
      r.reread = true;
      arg(key, "");
    } else if (key == "max-instances" || key == "max-triangles") {
      // 2^53: the largest whole number a JSON number carries exactly.
      const auto v = std::uint64_t(whole(value, key, 0, 9007199254740992.0));
      (key == "max-instances" ? r.read.max_instances : r.read.max_triangles) = v;
      r.reread = true;
      arg(key, std::to_string(v));
    } else if (key == "floats-per-line" || key == "ints-per-line") {
      const int v = int(whole(value, key, 1, 1000000));
      (key == "floats-per-line" ? r.write.floats_per_line : r.write.ints_per_line) = v;
      arg(key, std::to_string(v));
    } else if (key == "no-tabs" || key == "minimize") {
      if (!flag(value, key)) continue;
      (key == "no-tabs" ? r.write.no_tabs : r.write.minimize) = true;
      arg(key, "");
    } else if (key == "verbose") {
      for (const auto& item : strings(value, key)) {
        r.verbose_given = true;
        // "coord,face" as the command line's delimiter takes it.
        for (std::size_t pos = 0; pos <= item.size();) {
          const std::size_t comma = std::min(item.find(',', pos), item.size());
          const std::string name = item.substr(pos, comma - pos);
          LogCategory c;
          if (!parse_category(name, c))
            throw DataError(fmt::format(
                "option verbose: unknown category '{}' (coord, material, normal, texcoord, "
                "face, line, join, triangulator)",
                name));
          r.verbose.push_back(c);
          pos = comma + 1;
        }
        arg(key, item);
      }
    } else if (key == "threads") {
      o.threads = int(number(value, key, 0, 1024));
      arg(key, std::to_string(o.threads));
    } else {
      throw DataError(fmt::format("unknown option '{}' (the long options of `lodforge lod`)", key));
    }
  }
  // Appended piece by piece: `" " + word` makes GCC 12 warn of a memcpy
  // overlap that cannot happen (GCC bug 105329).
  for (const auto& a : args) {
    if (!r.command_line.empty()) r.command_line += ' ';
    r.command_line += shell_word(a);
  }
  return r;
}

}  // namespace lodforge::studio
