#include "lodforge/studio/studio_server.h"

#include <fmt/core.h>
#include <httplib.h>

#include <atomic>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/scene_to_gltf.h"
#include "lodforge/io/gltf/write_gltf.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "lodforge/io/vrml97/vrml1_to_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/io/vrml97/write_x3d_xml.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/scene/relocate_references.h"
#include "lodforge/scene/statistics.h"
#include "lodforge/scene/traverse.h"
#include "lodforge/studio/level_geometry.h"
#include "lodforge/studio/lod_request.h"
#include "lodforge/studio/scene_tree.h"

namespace lodforge::studio {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// An answer other than 200, carried to the handler's end.
struct ApiError : std::runtime_error {
  ApiError(int status, const std::string& text) : std::runtime_error(text), status(status) {}
  int status;
};

json diagnostics_json(const std::vector<Diagnostic>& entries) {
  json out = json::array();
  for (const auto& d : entries)
    out.push_back(
        {{"category", to_string(d.category)}, {"level", to_string(d.level)}, {"text", d.text}});
  return out;
}

// The statistics of a run as the page shows them: per shape its levels with
// the distance from which each is drawn.
json result_json(const LodResult& r) {
  json j;
  j["camera_angle"] = r.camera_angle;
  j["joined"] = r.joined;
  j["shapes"] = json::array();
  std::size_t original = 0;
  for (const auto& s : r.shapes) {
    json levels = json::array();
    for (std::size_t i = 0; i < s.levels.size(); ++i) {
      const auto& l = s.levels[i];
      json level = {{"triangles", l.triangles}, {"vertices", l.vertices}, {"error", l.error}};
      level["from_distance"] = i == 0 ? 0.0 : (i - 1 < s.ranges.size() ? s.ranges[i - 1] : -1.0);
      levels.push_back(std::move(level));
    }
    j["shapes"].push_back({{"type", s.type},
                           {"name", s.name},
                           {"line", s.line},
                           {"occurrences", s.occurrences},
                           {"method", s.method},
                           {"radius", s.radius},
                           {"ranges", s.ranges},
                           {"stop_reason", s.stop_reason},
                           {"levels", std::move(levels)}});
    if (!s.levels.empty()) original += s.levels[0].triangles * s.occurrences;
  }
  j["triangles"] = original;
  j["triangles_by_distance"] = json::array();
  for (const auto& [d, t] : r.triangles_by_distance)
    j["triangles_by_distance"].push_back({{"distance", d}, {"triangles", t}});
  return j;
}

struct LodJob {
  std::string state = "idle";  // running, done, failed
  std::string command_line, error, stage;
  std::uint64_t done = 0, total = 0;
  std::shared_ptr<LodResult> result;
  json result_json;
  std::string format;         // LodRequest::format, for Save
  vrml1::WriteOptions write;  // LodRequest::write, for Save
};

// The language Save writes, as `lodforge lod` decides it for a VRML 1.0
// scene (apps/cmd_lod.cpp: vrml97_format_of, gltf_binary_name, which live in
// the executable): --format, else the output's name (.glb / .gltf glTF,
// .x3dv X3D classic, .x3d X3D XML, optionally .gz), else VRML 1.0.
//   format given        | output name         | written as
//   gltf / glb          | any                 | glTF JSON / binary glTF
//   vrml97 / x3dv / x3d | any                 | VRML97 / X3D classic / X3D XML
//   none                | .glb / .gltf (.gz)  | binary glTF / glTF JSON
//   none                | .x3dv (.gz)         | X3D classic
//   none                | .x3d (.gz), .x3dz   | X3D XML
//   none           | anything else       | VRML 1.0 (the writer options apply)
std::string save_format(const std::string& format, const std::string& output) {
  if (!format.empty()) return format;
  std::string lower = output;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (gltf::is_gltf_path(lower)) {
    if (lower.ends_with(".gz")) lower.resize(lower.size() - 3);
    return lower.ends_with(".glb") ? "glb" : "gltf";
  }
  if (output.ends_with(".x3dv") || output.ends_with(".x3dv.gz")) return "x3dv";
  if (vrml97::is_x3d_xml_path(output)) return "x3d";
  return "vrml1";
}

// Writes the LOD scene to `out` in `format` (save_format); the conversion's
// warnings go to `log`.
void write_lod_scene(const scene::Scene& scene, const fs::path& out, const std::string& format,
                     const vrml1::WriteOptions& write, double camera_angle, Log& log) {
  if (format == "gltf" || format == "glb") {
    const std::string folder = out.parent_path().string();
    gltf::write_gltf_file(
        gltf::scene_to_gltf(scene, {.camera_angle = camera_angle, .base_dir = folder}, log),
        out.string(), {.binary = format == "glb", .output_dir = folder});
  } else if (format == "x3d") {
    vrml97::write_x3d_xml_file(vrml97::vrml1_to_vrml97(scene, {.x3d = true}, log), out.string());
  } else if (format == "vrml97" || format == "x3dv") {
    vrml97::write_vrml97_file(vrml97::vrml1_to_vrml97(scene, {.x3d = format == "x3dv"}, log),
                              out.string());
  } else {
    vrml1::write_vrml1_file(scene, out.string(), write);
  }
}

struct LoadedScene {
  std::string path;  // canonical
  std::size_t size = 0;
  std::optional<scene::Scene> scene;
  std::string error;
  std::vector<Diagnostic> warnings;
  json counts;  // shape type -> count
  std::size_t triangles = 0;
  LodJob job;
  std::optional<std::string> edited;  // the text re-parsed in place of the file's
};

// The default LOD output beside a scene: NAME_lod.EXT, a gzip suffix kept
// last (packed.wrl.gz gives packed_lod.wrl.gz, written gzip-compressed).
std::string lod_output_name(const fs::path& in) {
  const std::string ext = in.extension().string();
  std::string lower = ext;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool gz = lower == ".gz";
  const fs::path base = gz ? in.parent_path() / in.stem() : in;
  return (base.parent_path() /
          (base.stem().string() + "_lod" + base.extension().string() + (gz ? ext : "")))
      .string();
}

bool is_under(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p)
    if (p == path.end() || *p != *f) return false;
  return true;
}

}  // namespace

struct StudioServer::Impl {
  StudioOptions options;
  std::vector<fs::path> folders;  // canonical
  std::mutex mutex;               // guards scenes and their jobs
  std::map<std::string, std::unique_ptr<LoadedScene>> scenes;
  std::vector<std::thread> workers;
  std::atomic<bool> running_job{false};
  httplib::Server server;
  int port = 0;
  fs::path upload_folder;  // made at the first upload, removed at the end

  // The canonical form of a path the API was given, if it lies under an
  // allowed folder; ApiError 403 otherwise.
  fs::path allowed(const std::string& given) const {
    if (given.empty()) throw ApiError(400, "no path given");
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(given), ec);
    if (!ec)
      for (const auto& f : folders)
        if (is_under(p, f)) return p;
    std::string list;
    for (const auto& f : folders) list += (list.empty() ? "" : ", ") + f.string();
    throw ApiError(403, fmt::format("{}: refused, the studio opens and writes only files under "
                                    "the folders of the scenes it was started with ({})",
                                    given, list));
  }

  // Takes the scene read for `s` (its counts, triangles and warnings).
  static void adopt(LoadedScene& s, vrml1::ReadResult r) {
    s.warnings = r.log.entries();
    const scene::SceneStatistics stats = scene::scene_statistics(r.scene);
    s.counts = json::object();
    for (const auto& [type, n] : stats.node_counts)
      if (scene::is_shape_type(type) || type == "LOD") s.counts[type] = n;
    s.triangles = stats.total_triangles;
    s.scene = std::move(r.scene);
    s.error.clear();
  }

  LoadedScene& load(const fs::path& path) {
    auto entry = std::make_unique<LoadedScene>();
    entry->path = path.string();
    std::error_code ec;
    entry->size = std::size_t(fs::file_size(path, ec));
    if (ec) throw ApiError(404, fmt::format("{}: {}", path.string(), ec.message()));
    try {
      adopt(*entry, vrml1::read_vrml1_file(path.string()));
    } catch (const DataError& e) {
      entry->error = e.what();
    }
    auto& slot = scenes[entry->path];
    slot = std::move(entry);
    return *slot;
  }

  // The scene's text for the editor: the edited text once re-parsed, the
  // file's (decompressed) otherwise.
  json text(const std::string& path) {
    std::lock_guard lock(mutex);
    LoadedScene& s = scene_of(path);
    if (s.edited) return {{"path", s.path}, {"text", *s.edited}, {"edited", true}};
    try {
      const FileBytes bytes(s.path);
      return {{"path", s.path}, {"text", std::string(bytes.view())}, {"edited", false}};
    } catch (const DataError& e) {
      throw ApiError(400, e.what());
    }
  }

  // Parses edited text in place of the scene's file, writing nothing: the
  // tree, counts and Make LOD then work on it. A syntax error leaves the
  // loaded scene as it was and answers its line and column.
  json parse(const json& body) {
    if (!body.contains("text") || !body["text"].is_string()) throw ApiError(400, "no text given");
    const std::string text = body["text"];
    std::lock_guard lock(mutex);
    LoadedScene& s = scene_of(body.value("path", ""));
    if (running_job) throw ApiError(409, "a LOD run is going on; re-parse when it ends");
    vrml1::ReadOptions read;
    read.source_name = s.path;
    read.base_dir = fs::path(s.path).parent_path().string();
    try {
      adopt(s, vrml1::read_vrml1(text, read));
    } catch (const ParseError& e) {
      return {{"parsed", false}, {"error", e.what()}, {"line", e.line()}, {"column", e.column()}};
    } catch (const DataError& e) {
      return {{"parsed", false}, {"error", e.what()}};
    }
    s.edited = text;
    s.job = LodJob{};
    json j = file_json(s);
    j["parsed"] = true;
    return j;
  }

  // A texture file of a scene (its Texture2 filename, relative to the
  // scene's folder), under the allowed folders only.
  std::string texture(const std::string& path, const std::string& file, std::string& type) {
    fs::path f(file);
    {
      std::lock_guard lock(mutex);
      if (f.is_relative()) f = fs::path(scene_of(path).path).parent_path() / f;
    }
    const fs::path p = allowed(f.string());
    std::string ext = p.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    static const std::map<std::string, std::string> kTypes = {
        {".png", "image/png"}, {".jpg", "image/jpeg"}, {".jpeg", "image/jpeg"},
        {".gif", "image/gif"}, {".bmp", "image/bmp"},  {".webp", "image/webp"}};
    const auto it = kTypes.find(ext);
    if (it == kTypes.end()) throw ApiError(400, file + ": not an image the page can show");
    if (!fs::is_regular_file(p)) throw ApiError(404, file + ": no such texture file");
    type = it->second;
    try {
      return read_file(p.string());
    } catch (const DataError& e) {
      throw ApiError(404, e.what());
    }
  }

  // An uploaded scene goes to the server's own temporary folder (never
  // elsewhere), which then counts as an allowed folder.
  json upload(const json& body) {
    const std::string name = body.value("name", "");
    if (name.empty() || name.find('/') != std::string::npos ||
        name.find('\\') != std::string::npos || name == "." || name == ".." ||
        name.find('\0') != std::string::npos)
      throw ApiError(400, fmt::format("'{}': an upload needs a plain file name", name));
    if (!body.contains("text") || !body["text"].is_string()) throw ApiError(400, "no text given");
    std::lock_guard lock(mutex);
    if (upload_folder.empty()) {
      std::string pattern = (fs::temp_directory_path() / "lodforge-studio-XXXXXX").string();
      if (!mkdtemp(pattern.data())) throw ApiError(500, "cannot make a temporary folder");
      upload_folder = fs::canonical(pattern);
      folders.push_back(upload_folder);
    }
    const fs::path path = upload_folder / name;
    if (running_job && scenes.count(path.string()))
      throw ApiError(409, "a LOD run is going on; upload again when it ends");
    try {
      write_file_atomic(path.string(), body["text"].get<std::string>());
    } catch (const DataError& e) {
      throw ApiError(400, e.what());
    }
    return file_json(load(path));
  }

  LoadedScene& scene_of(const std::string& given) {
    const fs::path p = allowed(given);
    auto it = scenes.find(p.string());
    if (it == scenes.end()) throw ApiError(404, given + ": not loaded (open it first)");
    return *it->second;
  }

  json file_json(const LoadedScene& s) const {
    json j = {{"path", s.path},
              {"size", s.size},
              {"shapes", s.counts.is_null() ? json::object() : s.counts},
              {"triangles", s.triangles},
              {"warnings", diagnostics_json(s.warnings)}};
    if (!s.error.empty()) j["error"] = s.error;
    return j;
  }

  json files() {
    std::lock_guard lock(mutex);
    json j = {{"folders", json::array()}, {"files", json::array()}};
    for (const auto& f : folders) j["folders"].push_back(f.string());
    for (const auto& given : options.scenes) {
      auto it = scenes.find(fs::weakly_canonical(fs::absolute(given)).string());
      if (it != scenes.end()) j["files"].push_back(file_json(*it->second));
    }
    for (const auto& [path, s] : scenes) {
      bool listed = false;
      for (const auto& f : j["files"]) listed = listed || f["path"] == path;
      if (!listed) j["files"].push_back(file_json(*s));
    }
    return j;
  }

  json open(const json& body) {
    const fs::path p = allowed(body.value("path", ""));
    std::lock_guard lock(mutex);
    if (running_job && scenes.count(p.string()))
      throw ApiError(409, "a LOD run is going on; open again when it ends");
    return file_json(load(p));
  }

  json start_lod(const json& body) {
    std::lock_guard lock(mutex);
    LoadedScene& s = scene_of(body.value("path", ""));
    if (!s.scene) throw ApiError(400, s.path + " did not parse: " + s.error);
    if (running_job) throw ApiError(409, "a LOD run is going on already");
    const std::string output = lod_output_name(s.path);
    LodRequest request;
    try {
      request = lod_request(body.contains("options") ? body["options"] : json(), s.path, output);
    } catch (const DataError& e) {
      throw ApiError(400, e.what());
    }
    if (options.threads) request.options.threads = options.threads;
    s.job = LodJob{.state = "running",
                   .command_line = request.command_line,
                   .format = request.format,
                   .write = request.write};
    running_job = true;
    for (auto& w : workers) w.join();
    workers.clear();
    workers.emplace_back([this, &s, request, scene = *s.scene, edited = s.edited]() mutable {
      run_job(s, std::move(request), std::move(scene), std::move(edited));
    });
    return {{"state", "running"}, {"command_line", request.command_line}};
  }

  // Runs the pipeline on `scene`, the loaded one, or on the scene read again
  // (from `edited`, else the file) when the request has reading options.
  void run_job(LoadedScene& s, LodRequest request, scene::Scene scene,
               std::optional<std::string> edited) {
    request.options.progress = [this, &s](std::string_view stage, std::uint64_t done,
                                          std::uint64_t total) {
      std::lock_guard lock(mutex);
      s.job.stage = std::string(stage);
      s.job.done = done;
      s.job.total = total;
    };
    std::shared_ptr<LodResult> result;
    std::string error;
    std::optional<std::vector<Diagnostic>> read_warnings;
    try {
      if (request.reread) {
        // Read with --inline / --max-instances / --max-triangles as the CLI
        // reads the file; the result owns its nodes.
        vrml1::ReadOptions read = request.read;
        read.source_name = s.path;
        read.base_dir = fs::path(s.path).parent_path().string();
        vrml1::ReadResult r =
            edited ? vrml1::read_vrml1(*edited, read) : vrml1::read_vrml1_file(s.path, read);
        read_warnings = r.log.entries();
        result = std::make_shared<LodResult>(generate_lod(std::move(r.scene), request.options));
      } else {
        // The copy shares its nodes with the loaded scene, which the taking
        // overload of generate_lod could change: the copying one is used.
        const scene::Scene& shared = scene;
        result = std::make_shared<LodResult>(generate_lod(shared, request.options));
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard lock(mutex);
    if (result) {
      s.job.result_json = result_json(*result);
      std::vector<Diagnostic> messages = read_warnings ? *read_warnings : s.warnings;
      // With --verbose, the messages `lodforge lod` prints: warnings and
      // errors, and plain messages of the categories given.
      for (const auto& d : result->log.entries())
        if (!request.verbose_given || d.level != LogLevel::kMessage ||
            std::find(request.verbose.begin(), request.verbose.end(), d.category) !=
                request.verbose.end())
          messages.push_back(d);
      s.job.result_json["messages"] = diagnostics_json(messages);
      s.job.result = std::move(result);
      s.job.state = "done";
    } else {
      s.job.error = error;
      s.job.state = "failed";
    }
    running_job = false;
  }

  json lod_status(const std::string& path) {
    std::lock_guard lock(mutex);
    const LodJob& job = scene_of(path).job;
    json j = {{"state", job.state},
              {"command_line", job.command_line},
              {"progress", {{"stage", job.stage}, {"done", job.done}, {"total", job.total}}}};
    if (job.state == "done") j["result"] = job.result_json;
    if (job.state == "failed") j["error"] = job.error;
    return j;
  }

  json save(const json& body) {
    std::shared_ptr<LodResult> result;
    std::string input, format;
    vrml1::WriteOptions write;
    {
      std::lock_guard lock(mutex);
      LoadedScene& s = scene_of(body.value("path", ""));
      if (s.job.state != "done") throw ApiError(400, s.path + ": no LOD result to save (Make LOD)");
      result = s.job.result;
      input = s.path;
      format = s.job.format;
      write = s.job.write;
    }
    const fs::path out = allowed(body.value("output", ""));
    if (out == fs::path(input)) throw ApiError(400, out.string() + ": the output is the input");
    // The result stays as it is for later saves: the references are
    // rewritten on a deep copy.
    scene::Scene copy = result->scene;
    std::unordered_map<const scene::Node*, scene::NodePtr> done;
    for (auto& root : copy.roots) root = scene::copy_subtree(root, done);
    scene::relocate_references(copy, fs::path(input).parent_path(), out.parent_path());
    const std::string as = save_format(format, out.string());
    Log log;
    try {
      write_lod_scene(copy, out, as, write, result->camera_angle, log);
    } catch (const DataError& e) {
      throw ApiError(400, e.what());
    }
    std::error_code ec;
    return {{"written", out.string()},
            {"format", as},
            {"bytes", fs::file_size(out, ec)},
            {"messages", diagnostics_json(log.entries())}};
  }

  std::string geometry(const std::string& path, const std::string& which) {
    std::shared_ptr<LodResult> result;
    std::optional<scene::Scene> input;
    {
      std::lock_guard lock(mutex);
      LoadedScene& s = scene_of(path);
      if (which == "output") {
        if (s.job.state != "done") throw ApiError(400, s.path + ": no LOD result yet");
        result = s.job.result;
      } else {
        if (!s.scene) throw ApiError(400, s.path + " did not parse: " + s.error);
        input = s.scene;
      }
    }
    try {
      return level_geometry(result ? result->scene : *input);
    } catch (const DataError& e) {
      throw ApiError(400, e.what());
    }
  }

  void routes();
};

namespace {

json body_of(const httplib::Request& req) {
  try {
    return req.body.empty() ? json::object() : json::parse(req.body);
  } catch (const json::exception& e) {
    throw ApiError(400, std::string("the request is not JSON: ") + e.what());
  }
}

// Runs an API handler, turning its errors into JSON answers.
template <class Fn>
httplib::Server::Handler api(Fn fn) {
  return [fn](const httplib::Request& req, httplib::Response& res) {
    try {
      fn(req, res);
    } catch (const ApiError& e) {
      res.status = e.status;
      res.set_content(json{{"error", e.what()}}.dump(), "application/json");
    } catch (const std::exception& e) {
      res.status = 500;
      res.set_content(json{{"error", e.what()}}.dump(), "application/json");
    }
  };
}

void send(httplib::Response& res, const json& j) {
  res.set_content(j.dump(), "application/json");
}

}  // namespace

void StudioServer::Impl::routes() {
  server.Get("/api/files", api([this](const auto&, auto& res) { send(res, files()); }));
  server.Post("/api/open",
              api([this](const auto& req, auto& res) { send(res, open(body_of(req))); }));
  server.Get("/api/tree", api([this](const auto& req, auto& res) {
               std::lock_guard lock(mutex);
               LoadedScene& s = scene_of(req.get_param_value("path"));
               if (!s.scene) throw ApiError(400, s.path + " did not parse: " + s.error);
               send(res, scene_tree(*s.scene));
             }));
  server.Get("/api/geometry", api([this](const auto& req, auto& res) {
               res.set_content(geometry(req.get_param_value("path"), req.get_param_value("which")),
                               "application/json");
             }));
  server.Post("/api/lod",
              api([this](const auto& req, auto& res) { send(res, start_lod(body_of(req))); }));
  server.Get("/api/lod", api([this](const auto& req, auto& res) {
               send(res, lod_status(req.get_param_value("path")));
             }));
  server.Get("/api/text", api([this](const auto& req, auto& res) {
               send(res, text(req.get_param_value("path")));
             }));
  server.Get("/api/texture", api([this](const auto& req, auto& res) {
               std::string type;
               std::string bytes =
                   texture(req.get_param_value("path"), req.get_param_value("file"), type);
               res.set_content(std::move(bytes), type);
             }));
  server.Post("/api/parse",
              api([this](const auto& req, auto& res) { send(res, parse(body_of(req))); }));
  server.Post("/api/upload",
              api([this](const auto& req, auto& res) { send(res, upload(body_of(req))); }));
  server.Post("/api/save",
              api([this](const auto& req, auto& res) { send(res, save(body_of(req))); }));
  // Module scripts load only with a JavaScript type.
  server.set_file_extension_and_mimetype_mapping("js", "text/javascript");
  if (!options.three_root.empty() && !server.set_mount_point("/three", options.three_root))
    throw DataError(options.three_root + ": three.js is not there (scripts/install-web-deps.sh)");
  if (!options.codemirror_root.empty() &&
      !server.set_mount_point("/codemirror", options.codemirror_root))
    throw DataError(options.codemirror_root +
                    ": CodeMirror is not there (scripts/install-web-deps.sh)");
  if (!server.set_mount_point("/", options.web_root))
    throw DataError(options.web_root + ": the studio's page is not there");
}

StudioServer::StudioServer(StudioOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  if (impl_->options.scenes.empty()) throw DataError("studio: give at least one scene");
  for (const auto& given : impl_->options.scenes) {
    std::error_code ec;
    const fs::path p = fs::canonical(given, ec);
    if (ec || !fs::is_regular_file(p))
      throw DataError(fmt::format("{}: {}", given, ec ? ec.message() : "not a regular file"));
    const fs::path folder = p.parent_path();
    if (std::find(impl_->folders.begin(), impl_->folders.end(), folder) == impl_->folders.end())
      impl_->folders.push_back(folder);
    impl_->load(p);
  }
  impl_->routes();
}

StudioServer::~StudioServer() {
  stop();
  if (!impl_->upload_folder.empty()) {
    std::error_code ec;
    fs::remove_all(impl_->upload_folder, ec);
  }
}

int StudioServer::bind() {
  Impl& s = *impl_;
  if (s.options.port == 0)
    s.port = s.server.bind_to_any_port(s.options.host);
  else
    s.port = s.server.bind_to_port(s.options.host, s.options.port) ? s.options.port : -1;
  if (s.port <= 0)
    throw DataError(
        fmt::format("cannot listen on {}:{} (in use? try --port)", s.options.host, s.options.port));
  return s.port;
}

void StudioServer::serve() {
  impl_->server.listen_after_bind();
}

void StudioServer::stop() {
  if (!impl_) return;
  impl_->server.stop();
  for (auto& w : impl_->workers)
    if (w.joinable()) w.join();
  impl_->workers.clear();
}

}  // namespace lodforge::studio
