#pragma once
/// glTF 2.0 reader: `.gltf` (JSON, with external `.bin` buffers or `data:`
/// URIs) and `.glb` (binary container), through tinygltf. The scene model of
/// a glTF file is the tinygltf::Model itself, so everything lodforge does not
/// interpret (materials, textures, samplers, animations, skins, cameras,
/// lights, unknown extensions, extras) is carried through by writing the model
/// back (write_gltf.h).
///
/// Images are never decoded: an image in a `data:` URI keeps its bytes
/// (Image::image, Image::as_is = true, with its mimeType), an image in a
/// buffer view stays there, and an external image keeps its URI (resolved
/// against GltfScene::base_dir; the file is not read).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>

namespace lodforge::gltf {

struct GltfScene {
  tinygltf::Model model;
  /// Folder the model's relative URIs (external images) resolve against;
  /// empty: the current folder.
  std::string base_dir;
};

struct GltfReadOptions {
  /// Name used in messages ("NAME: what is wrong").
  std::string source_name = "<input>";
  /// Folder external buffers are read from; read_gltf_file sets it to the
  /// file's folder. Empty: external buffers are an error.
  std::string base_dir;
  /// At most this many nodes, meshes, accessors and buffer views each: a
  /// bound on the work a small hostile file can cause. 0: no limit.
  std::size_t max_objects = 1'000'000;
};

struct GltfReadResult {
  GltfScene scene;
  std::vector<std::string> warnings;  ///< tinygltf's warnings, one per entry
};

/// Parses a glTF 2.0 asset held in memory: binary (starts with "glTF") or
/// JSON. Checks every index the toolkit follows (scene → node → mesh →
/// primitive → accessor → buffer view → buffer, node children, node cycles)
/// and every accessor's and buffer view's byte range. Throws DataError
/// "NAME: what is wrong" for bad JSON, a bad GLB container, a missing or short
/// buffer, an index out of range, a node hierarchy with a cycle or a node with
/// two parents, or more objects than max_objects.
GltfReadResult read_gltf(std::string_view bytes, const GltfReadOptions& options = {});

/// Reads a file ("-" = standard input; gzip-compressed data is decompressed),
/// setting source_name and base_dir from the path. Throws as read_gltf.
GltfReadResult read_gltf_file(const std::string& path, GltfReadOptions options = {});

/// True if `path` names a glTF file by its extension (.gltf, .glb, any case,
/// optionally followed by .gz).
bool is_gltf_path(std::string_view path);

}  // namespace lodforge::gltf
