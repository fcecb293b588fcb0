#include "lodforge/io/gltf/write_gltf.h"

#include <fmt/core.h>

#include <climits>
#include <cstring>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lodforge/core/data_uri.h"
#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge::gltf {
namespace {

namespace fs = std::filesystem;

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
    *out_uri = data_uri(mime, image->image);
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
// buffer views re-pointed into it. Each buffer is freed once copied, so the
// bytes are held about once.
void merge_buffers(tinygltf::Model& m) {
  if (m.buffers.size() <= 1) {
    if (!m.buffers.empty()) m.buffers[0].uri.clear();  // external or data: URI, now embedded
    return;
  }
  std::vector<std::size_t> offsets;
  std::size_t total = 0;
  for (const auto& b : m.buffers) {
    offsets.push_back(total);
    total = (total + b.data.size() + 3) / 4 * 4;
  }
  tinygltf::Buffer merged;
  merged.name = m.buffers[0].name;
  merged.extras = m.buffers[0].extras;
  merged.extensions = m.buffers[0].extensions;
  merged.data.reserve(total);
  for (std::size_t i = 0; i < m.buffers.size(); ++i) {
    merged.data.resize(offsets[i], 0);
    merged.data.insert(merged.data.end(), m.buffers[i].data.begin(), m.buffers[i].data.end());
    std::vector<unsigned char>().swap(m.buffers[i].data);
  }
  for (auto& v : m.bufferViews) {
    v.byteOffset += offsets[std::size_t(v.buffer)];
    v.buffer = 0;
  }
  m.buffers.assign(1, std::move(merged));
}

// The model with one buffer and its image URIs as seen from the output's
// folder, serialized by tinygltf: JSON text for a `.gltf`; for a `.glb`, the
// JSON chunk's text only, the buffer's bytes taken out of the model into
// `bin` (tinygltf would copy them to write them).
std::string serialize(tinygltf::Model& model, const std::string& base_dir,
                      const GltfWriteOptions& options, std::vector<unsigned char>& bin) {
  merge_buffers(model);
  if (options.binary && !model.buffers.empty() && model.buffers[0].data.size() >= UINT_MAX - 64)
    throw DataError(fmt::format("a GLB holds less than 4 GiB, the buffer has {} bytes",
                                model.buffers[0].data.size()));
  if (options.binary && !model.buffers.empty()) bin.swap(model.buffers[0].data);
  ImageContext context{base_dir, options.output_dir};
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&write_image, &context);
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, options.pretty, options.binary))
    throw DataError("the glTF model cannot be serialized");
  std::string text = std::move(out).str();
  if (!options.binary) return text;
  // tinygltf's GLB of the model without its bytes: the JSON chunk at 20,
  // its length (spaces included) at 12; the buffer's length set again.
  std::uint32_t length = 0;
  std::memcpy(&length, text.data() + 12, 4);
  text = text.substr(20, length);
  if (!bin.empty()) {
    nlohmann::json json = nlohmann::json::parse(text);
    json["buffers"][0]["byteLength"] = bin.size();
    text = json.dump();
  }
  return text;
}

// A GLB (glTF 2.0 binary container) of the JSON text and the buffer, piece by
// piece to `sink`; chunks padded to 4 bytes, JSON with spaces, BIN with zeros.
void write_glb(const std::string& json, const std::vector<unsigned char>& bin,
               const std::function<void(std::string_view)>& sink) {
  auto word = [&](std::uint32_t v) {
    char b[4];
    for (int i = 0; i < 4; ++i) b[i] = char(v >> (8 * i) & 0xFF);
    sink({b, 4});
  };
  const std::size_t json_padding = (4 - json.size() % 4) % 4,
                    bin_padding = (4 - bin.size() % 4) % 4;
  const std::size_t json_chunk = json.size() + json_padding, bin_chunk = bin.size() + bin_padding;
  sink("glTF");
  word(2);
  word(std::uint32_t(12 + 8 + json_chunk + (bin.empty() ? 0 : 8 + bin_chunk)));
  word(std::uint32_t(json_chunk));
  word(0x4E4F534A);  // "JSON"
  sink(json);
  sink(std::string(json_padding, ' '));
  if (bin.empty()) return;
  word(std::uint32_t(bin_chunk));
  word(0x004E4942);  // "BIN\0"
  sink({reinterpret_cast<const char*>(bin.data()), bin.size()});
  sink(std::string(bin_padding, '\0'));
}

}  // namespace

std::string write_gltf(GltfScene scene, const GltfWriteOptions& options) {
  std::vector<unsigned char> bin;
  std::string text = serialize(scene.model, scene.base_dir, options, bin);
  if (!options.binary) return text;
  std::string out;
  write_glb(text, bin, [&](std::string_view piece) { out += piece; });
  return out;
}

void write_gltf_file(GltfScene scene, const std::string& path, GltfWriteOptions options) {
  if (options.output_dir.empty() && path != "-") {
    const fs::path dir = fs::path(path).parent_path();
    options.output_dir = dir.empty() ? "." : dir.string();
  }
  std::vector<unsigned char> bin;
  std::string text = serialize(scene.model, scene.base_dir, options, bin);
  AtomicFileWriter file(path);
  if (options.binary)
    write_glb(text, bin, [&](std::string_view piece) { file.write(piece); });
  else
    file.write(text);
  file.commit();
}

}  // namespace lodforge::gltf
