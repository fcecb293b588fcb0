// glTF 2.0 reading through tinygltf, followed by the index and range checks
// tinygltf leaves to its users (glTF 2.0 specification, "Accessors", "Buffers
// and Buffer Views", "Nodes and Hierarchy"), so that everything after reading
// may follow an index without checking it again.
#include "lodforge/io/gltf/read_gltf.h"

#include <fmt/core.h>

#include <algorithm>
#include <climits>
#include <filesystem>
#include <sstream>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge::gltf {
namespace {

// Keeps an embedded image's bytes undecoded; an image in a buffer view stays
// there (its bytes are the buffer's).
bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;
  return true;
}

class Checker {
 public:
  Checker(const tinygltf::Model& m, const std::string& source) : m_(m), source_(source) {}

  void check(std::size_t max_objects) {
    check_counts(max_objects);
    for (std::size_t i = 0; i < m_.bufferViews.size(); ++i) check_buffer_view(i);
    for (std::size_t i = 0; i < m_.accessors.size(); ++i) check_accessor(i);
    for (std::size_t i = 0; i < m_.meshes.size(); ++i) check_mesh(i);
    check_nodes();
    for (std::size_t i = 0; i < m_.scenes.size(); ++i)
      for (int n : m_.scenes[i].nodes) index(n, m_.nodes.size(), "scene", i, "node");
    if (m_.defaultScene >= 0 || m_.defaultScene < -1)
      index(m_.defaultScene, m_.scenes.size(), "asset", 0, "scene");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw DataError(fmt::format("{}: {}", source_, what));
  }

  // `value` must be a valid index into `size` objects (of `kind`), in the
  // object `owner`[`at`].
  void index(int value, std::size_t size, const char* owner, std::size_t at,
             const char* kind) const {
    if (value < 0 || std::size_t(value) >= size)
      fail(fmt::format("{} {} refers to {} {}, but there are {}", owner, at, kind, value, size));
  }

  void check_counts(std::size_t max_objects) const {
    if (max_objects == 0) return;
    const std::pair<const char*, std::size_t> counts[] = {{"nodes", m_.nodes.size()},
                                                          {"meshes", m_.meshes.size()},
                                                          {"accessors", m_.accessors.size()},
                                                          {"buffer views", m_.bufferViews.size()}};
    for (const auto& [what, n] : counts)
      if (n > max_objects) fail(fmt::format("{} {}, more than the limit {}", n, what, max_objects));
  }

  void check_buffer_view(std::size_t i) const {
    const auto& v = m_.bufferViews[i];
    index(v.buffer, m_.buffers.size(), "bufferView", i, "buffer");
    const std::size_t size = m_.buffers[std::size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
      fail(fmt::format("bufferView {} (bytes {} to {}) goes past the end of buffer {} ({} bytes)",
                       i, v.byteOffset, v.byteOffset + v.byteLength, v.buffer, size));
  }

  // Bytes [offset, offset + (count - 1) * stride + element) must lie in the view.
  void check_range(std::size_t i, const char* what, int view, std::size_t offset, std::size_t count,
                   std::size_t stride, std::size_t element) const {
    index(view, m_.bufferViews.size(), "accessor", i, "bufferView");
    const std::size_t length = m_.bufferViews[std::size_t(view)].byteLength;
    if (count == 0) return;
    const bool fits = offset <= length && element <= length - offset &&
                      (count - 1) <= (length - offset - element) / std::max<std::size_t>(stride, 1);
    if (!fits)
      fail(
          fmt::format("accessor {}: {} of {} elements of {} bytes (stride {}) from byte {} do "
                      "not fit in bufferView {} ({} bytes)",
                      i, what, count, element, stride, offset, view, length));
  }

  void check_accessor(std::size_t i) const {
    const auto& a = m_.accessors[i];
    const int component = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
    if (component <= 0 || components <= 0)
      fail(fmt::format("accessor {} has componentType {} and type {}", i, a.componentType, a.type));
    const std::size_t element = std::size_t(component) * std::size_t(components);
    if (a.bufferView >= 0) {
      index(a.bufferView, m_.bufferViews.size(), "accessor", i, "bufferView");
      const auto& view = m_.bufferViews[std::size_t(a.bufferView)];
      const int stride = a.ByteStride(view);
      if (stride <= 0)
        fail(fmt::format("accessor {}: byteStride {} is invalid", i, view.byteStride));
      check_range(i, "data", a.bufferView, a.byteOffset, a.count, std::size_t(stride), element);
    } else if (a.bufferView < -1) {
      index(a.bufferView, m_.bufferViews.size(), "accessor", i, "bufferView");
    }
    if (!a.sparse.isSparse) return;
    const auto& s = a.sparse;
    if (s.count < 0 || std::size_t(s.count) > a.count)
      fail(fmt::format("accessor {}: sparse count {} for {} elements", i, s.count, a.count));
    const int index_size =
        tinygltf::GetComponentSizeInBytes(std::uint32_t(s.indices.componentType));
    if (index_size <= 0 || index_size == 8 || s.indices.byteOffset < 0 || s.values.byteOffset < 0)
      fail(fmt::format("accessor {}: sparse indices of componentType {}", i,
                       s.indices.componentType));
    check_range(i, "sparse indices", s.indices.bufferView, std::size_t(s.indices.byteOffset),
                std::size_t(s.count), std::size_t(index_size), std::size_t(index_size));
    check_range(i, "sparse values", s.values.bufferView, std::size_t(s.values.byteOffset),
                std::size_t(s.count), element, element);
  }

  void check_mesh(std::size_t i) const {
    for (const auto& p : m_.meshes[i].primitives) {
      for (const auto& [name, a] : p.attributes)
        index(a, m_.accessors.size(), "mesh", i, "accessor");
      if (p.indices != -1) index(p.indices, m_.accessors.size(), "mesh", i, "accessor");
      if (p.material != -1) index(p.material, m_.materials.size(), "mesh", i, "material");
      for (const auto& target : p.targets)
        for (const auto& [name, a] : target) index(a, m_.accessors.size(), "mesh", i, "accessor");
      if (p.mode < 0 || p.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(fmt::format("mesh {} has a primitive of mode {}", i, p.mode));
    }
  }

  // glTF nodes form disjoint trees: every node has at most one parent, and no
  // chain of parents comes back to where it started.
  void check_nodes() const {
    const std::size_t n = m_.nodes.size();
    std::vector<int> parent(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& node = m_.nodes[i];
      if (node.mesh != -1) index(node.mesh, m_.meshes.size(), "node", i, "mesh");
      if (node.skin != -1) index(node.skin, m_.skins.size(), "node", i, "skin");
      if (node.camera != -1) index(node.camera, m_.cameras.size(), "node", i, "camera");
      for (int c : node.children) {
        index(c, n, "node", i, "node");
        if (parent[std::size_t(c)] != -1)
          fail(fmt::format("node {} is a child of nodes {} and {} (glTF nodes form trees)", c,
                           parent[std::size_t(c)], i));
        parent[std::size_t(c)] = int(i);
      }
    }
    // With one parent each, a cycle is a chain of parents that comes back
    // to a node of the chain.
    std::vector<char> state(n, 0);  // 0 unvisited, 1 on the current chain, 2 reaches a root
    std::vector<std::size_t> chain;
    for (std::size_t i = 0; i < n; ++i) {
      chain.clear();
      for (std::size_t at = i; state[at] != 2;) {
        if (state[at] == 1) fail(fmt::format("node {} is its own ancestor", at));
        state[at] = 1;
        chain.push_back(at);
        if (parent[at] == -1) break;
        at = std::size_t(parent[at]);
      }
      for (std::size_t c : chain) state[c] = 2;
    }
  }

  const tinygltf::Model& m_;
  const std::string& source_;
};

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

// File callbacks for a model without a folder: no external file exists.
tinygltf::FsCallbacks no_files() {
  return {.FileExists = [](const std::string&, void*) { return false; },
          .ExpandFilePath = [](const std::string& path, void*) { return path; },
          .ReadWholeFile =
              [](std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
                if (err) *err += "external file " + path + " refused: no folder to read it from\n";
                return false;
              },
          .WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&,
                               void*) { return false; },
          .user_data = nullptr};
}

}  // namespace

GltfReadResult read_gltf(std::string_view bytes, const GltfReadOptions& options) {
  const std::string& source = options.source_name;
  if (bytes.size() > UINT_MAX)
    throw DataError(
        fmt::format("{}: {} bytes, more than a glTF file may hold", source, bytes.size()));
  GltfReadResult result;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  if (options.base_dir.empty()) loader.SetFsCallbacks(no_files());
  std::string err, warn;
  bool ok = false;
  const bool binary = bytes.starts_with("glTF");
  try {
    if (binary)
      ok = loader.LoadBinaryFromMemory(&result.scene.model, &err, &warn,
                                       reinterpret_cast<const unsigned char*>(bytes.data()),
                                       unsigned(bytes.size()), options.base_dir);
    else
      ok = loader.LoadASCIIFromString(&result.scene.model, &err, &warn, bytes.data(),
                                      unsigned(bytes.size()), options.base_dir);
  } catch (const std::exception& e) {
    ok = false;
    err = e.what();
  }
  if (!ok) {
    auto lines = split_lines(err.empty() ? "not a glTF 2.0 asset" : err);
    std::string what = lines.empty() ? "not a glTF 2.0 asset" : lines.front();
    for (std::size_t i = 1; i < lines.size() && i < 4; ++i) what += "; " + lines[i];
    throw DataError(fmt::format("{}: {}{}", source, binary ? "GLB: " : "", what));
  }
  Checker(result.scene.model, source).check(options.max_objects);
  result.scene.base_dir = options.base_dir;
  result.warnings = split_lines(warn);
  return result;
}

GltfReadResult read_gltf_file(const std::string& path, GltfReadOptions options) {
  namespace fs = std::filesystem;
  const std::string bytes = read_file(path);
  options.source_name = path == "-" ? "<stdin>" : path;
  if (path != "-") {
    const fs::path dir = fs::path(path).parent_path();
    options.base_dir = dir.empty() ? "." : dir.string();
  } else if (options.base_dir.empty()) {
    options.base_dir = ".";
  }
  return read_gltf(bytes, options);
}

bool is_gltf_path(std::string_view path) {
  std::string lower(path);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (lower.ends_with(".gz")) lower.resize(lower.size() - 3);
  return lower.ends_with(".gltf") || lower.ends_with(".glb");
}

}  // namespace lodforge::gltf
