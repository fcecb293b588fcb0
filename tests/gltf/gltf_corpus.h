#pragma once
// The glTF and GLB files of ../shared/data/gltf, for tests that run over the corpus.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "lodforge/io/gltf/read_gltf.h"

namespace lodforge::testing {

inline std::vector<std::string> gltf_corpus_files() {
  std::vector<std::string> files;
  const std::filesystem::path root = std::filesystem::path(LODFORGE_SHARED_DATA) / "gltf";
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) return files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(root))
    if (e.is_regular_file() && gltf::is_gltf_path(e.path().string()))
      files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// A test name from a path: its last two components, letters and digits only.
inline std::string gltf_test_name(const std::string& path) {
  const std::filesystem::path p(path);
  std::string name = p.parent_path().filename().string() + "_" + p.filename().string();
  for (auto& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

}  // namespace lodforge::testing
