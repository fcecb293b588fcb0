#pragma once
// Where the benchmarks find the shared test meshes: $LODFORGE_SHARED_DATA,
// else ../shared/data beside the repository.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace lodforge::bench {

/// The meshes folder, ending in '/'.
inline std::string shared_mesh_dir() {
  if (const char* env = std::getenv("LODFORGE_SHARED_DATA")) return std::string(env) + "/meshes/";
  return (std::filesystem::path(__FILE__).parent_path() / "../../shared/data/meshes/").string();
}

}  // namespace lodforge::bench
