#include "lodforge/apps/lod_gltf.h"

#include <fmt/core.h>

#include "lodforge/apps/common_options.h"
#include "lodforge/core/error.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/write_gltf.h"
#include "lodforge/lod/gltf_lod.h"

namespace lodforge::apps {
namespace {

// The output's encoding (lod_gltf_file's rule): true for GLB.
bool binary_output(const std::string& input, const std::string& output, const std::string& format) {
  if (format == "glb" || format == "gltf") return format == "glb";
  if (!format.empty())
    throw DataError(
        fmt::format("a glTF scene is written as glTF (--format gltf or glb), not {}", format));
  if (name_ends_with(output, ".glb") || name_ends_with(output, ".gltf"))
    return name_ends_with(output, ".glb");
  if (output != "-")
    throw DataError(
        fmt::format("{}: a glTF scene is written as .gltf or .glb (or give --format)", output));
  return name_ends_with(input, ".glb");
}

}  // namespace

bool is_gltf_input(const std::string& input) {
  return gltf::is_gltf_path(input);
}

LodResult lod_gltf_file(const std::string& input, const std::string& output,
                        const std::string& format, const LodOptions& options) {
  const bool binary = binary_output(input, output, format);
  gltf::GltfReadResult read = gltf::read_gltf_file(input);
  Log log;
  for (const auto& w : read.warnings) log.warn(LogCategory::kParse, input + ": " + w);
  LodResult result = gltf_lod(read.scene, options);
  log.merge(result.log);
  result.log = std::move(log);
  gltf::write_gltf_file(std::move(read.scene), output, {.binary = binary});
  return result;
}

void format_gltf_file(const std::string& input, const std::string& output,
                      const std::string& format, Log& log) {
  const bool binary = binary_output(input, output, format);
  gltf::GltfReadResult read = gltf::read_gltf_file(input);
  for (const auto& w : read.warnings) log.warn(LogCategory::kParse, input + ": " + w);
  gltf::write_gltf_file(std::move(read.scene), output, {.binary = binary});
}

}  // namespace lodforge::apps
