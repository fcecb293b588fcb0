#pragma once
/// glTF 2.0 writer: the model of a GltfScene as `.glb` (one binary file) or
/// `.gltf` (one JSON file with its buffer embedded as a `data:` URI, so the
/// output is a single file written atomically, like every other output).
///
/// All buffers are merged into one (each buffer view re-pointed, every view
/// 4-byte aligned), which in a `.glb` is its BIN chunk. Images stay what they
/// were: a buffer-view image stays in the buffer; an image read from a
/// `data:` URI is written as a `data:` URI with the same bytes; an external
/// image keeps its file, its relative URI rewritten to resolve from
/// output_dir. Everything else in the model is written as tinygltf holds it.
#include <string>

#include "lodforge/io/gltf/read_gltf.h"

namespace lodforge::gltf {

struct GltfWriteOptions {
  bool binary = true;  ///< `.glb`; false: `.gltf` (JSON)
  /// Folder the output is read from: relative URIs of external images are
  /// rewritten from GltfScene::base_dir to it. Empty: written unchanged.
  std::string output_dir;
  bool pretty = true;  ///< `.gltf`: indented JSON
};

/// The file's bytes. Throws DataError if the model cannot be serialized
/// (a merged buffer of 4 GiB or more in a `.glb`). The scene is taken by
/// value: a caller done with it moves it in, and its bytes are not copied.
std::string write_gltf(GltfScene scene, const GltfWriteOptions& options = {});

/// Writes the file atomically (core/file_io.h: "-" is standard output, a
/// ".gz" name is written gzip-compressed); sets output_dir from the path
/// when it is empty. Throws DataError. A `.glb`'s buffer goes to the file
/// from the model's own bytes (no copy of them is made; move the scene in).
void write_gltf_file(GltfScene scene, const std::string& path, GltfWriteOptions options = {});

}  // namespace lodforge::gltf
