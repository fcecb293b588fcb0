#include "lodforge/apps/write_scene_gltf.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "lodforge/apps/common_options.h"
#include "lodforge/io/gltf/scene_to_gltf.h"
#include "lodforge/io/gltf/write_gltf.h"

namespace lodforge::apps {

void write_scene_gltf(const scene::Scene& scene, const std::string& target,
                      const std::string& base_dir, double camera_angle, bool binary, bool quiet) {
  Log log;
  const std::string from = base_dir.empty() ? "." : base_dir;
  const std::filesystem::path folder = std::filesystem::path(target).parent_path();
  gltf::GltfScene g =
      gltf::scene_to_gltf(scene, {.camera_angle = camera_angle, .base_dir = from}, log);
  if (!quiet) print_diagnostics(log.entries());
  gltf::write_gltf_file(
      std::move(g), target,
      {.binary = binary,
       .output_dir = target == "-" || folder.empty() ? std::string(".") : folder.string()});
}

bool gltf_binary_name(const std::string& target) {
  std::string lower = target;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (lower.ends_with(".gz")) lower.resize(lower.size() - 3);
  return lower.ends_with(".glb");
}

}  // namespace lodforge::apps
