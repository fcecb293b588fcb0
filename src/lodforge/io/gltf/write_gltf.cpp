#include "lodforge/io/gltf/write_gltf.h"

#include <fmt/core.h>

#include <climits>
#include <filesystem>
#include <sstream>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge::gltf {
namespace {

namespace fs = std::filesystem;

std::string base64(const std::vector<unsigned char>& data) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const std::uint32_t b0 = data[i], b1 = i + 1 < data.size() ? data[i + 1] : 0,
                        b2 = i + 2 < data.size() ? data[i + 2] : 0;
    const std::uint32_t v = b0 << 16 | b1 << 8 | b2;
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += i + 1 < data.size() ? kDigits[v >> 6 & 63] : '=';
    out += i + 2 < data.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// A URI with a scheme ("data:", "http:") or an absolute path is not relative.
bool is_relative_uri(const std::string& uri) {
  if (uri.empty() || uri[0] == '/') return false;
  const auto colon = uri.find(':');
  return colon == std::string::npos || uri.find('/') < colon;
}

struct ImageContext {
  std::string base_dir, output_dir;
};

// tinygltf's image writer callback: the image as the reader kept it.
bool write_image(const std::string*, const std::string*, const tinygltf::Image* image, bool,
                 std::string* out_uri, void* user) {
  const auto& context = *static_cast<const ImageContext*>(user);
  if (image->as_is && !image->image.empty()) {
    const std::string mime = image->mimeType.empty() ? "application/octet-stream" : image->mimeType;
    *out_uri = "data:" + mime + ";base64," + base64(image->image);
    return true;
  }
  if (context.output_dir.empty() || !is_relative_uri(image->uri)) return false;
  const fs::path from = fs::absolute(context.base_dir.empty() ? "." : context.base_dir);
  const fs::path to = fs::absolute(context.output_dir);
  const fs::path target = (from / image->uri).lexically_normal();
  const fs::path relative = target.lexically_relative(to.lexically_normal());
  if (relative.empty()) return false;
  *out_uri = relative.generic_string();
  return true;
}

// One buffer holding all the model's buffers, each 4-byte aligned, with the
// buffer views re-pointed into it.
void merge_buffers(tinygltf::Model& m) {
  if (m.buffers.size() <= 1) {
    if (!m.buffers.empty()) m.buffers[0].uri.clear();  // external or data: URI, now embedded
    return;
  }
  std::vector<std::size_t> offsets;
  tinygltf::Buffer merged;
  merged.name = m.buffers[0].name;
  merged.extras = m.buffers[0].extras;
  merged.extensions = m.buffers[0].extensions;
  for (const auto& b : m.buffers) {
    merged.data.resize((merged.data.size() + 3) / 4 * 4, 0);
    offsets.push_back(merged.data.size());
    merged.data.insert(merged.data.end(), b.data.begin(), b.data.end());
  }
  for (auto& v : m.bufferViews) {
    v.byteOffset += offsets[std::size_t(v.buffer)];
    v.buffer = 0;
  }
  m.buffers.assign(1, std::move(merged));
}

}  // namespace

std::string write_gltf(const GltfScene& scene, const GltfWriteOptions& options) {
  tinygltf::Model model = scene.model;
  merge_buffers(model);
  if (options.binary && !model.buffers.empty() && model.buffers[0].data.size() >= UINT_MAX - 64)
    throw DataError(fmt::format("a GLB holds less than 4 GiB, the buffer has {} bytes",
                                model.buffers[0].data.size()));
  ImageContext context{scene.base_dir, options.output_dir};
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&write_image, &context);
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, options.pretty, options.binary))
    throw DataError("the glTF model cannot be serialized");
  return std::move(out).str();
}

void write_gltf_file(const GltfScene& scene, const std::string& path, GltfWriteOptions options) {
  if (options.output_dir.empty() && path != "-") {
    const fs::path dir = fs::path(path).parent_path();
    options.output_dir = dir.empty() ? "." : dir.string();
  }
  const std::string bytes = write_gltf(scene, options);
  write_file_atomic(path, bytes);
}

}  // namespace lodforge::gltf
