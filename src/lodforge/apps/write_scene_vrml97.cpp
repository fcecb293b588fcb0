#include "lodforge/apps/write_scene_vrml97.h"

#include <fmt/core.h>

#include "lodforge/apps/common_options.h"
#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/vrml1_to_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"

namespace lodforge::apps {

std::string vrml97_format_of(const std::string& format, const std::string& target) {
  if (format == "vrml97" || format == "x3dv") return format;
  if (format == "x3d")
    throw DataError(
        "--format x3d: a VRML 1.0 or Inventor scene is written as X3D classic (--format x3dv "
        "or an output named .x3dv), not in the XML encoding");
  if (!format.empty()) return "";
  const bool x3dv = target.ends_with(".x3dv") || target.ends_with(".x3dv.gz");
  return x3dv ? "x3dv" : "";
}

void write_scene_vrml97(const scene::Scene& scene, const std::string& target, bool x3d,
                        bool quiet) {
  Log log;
  const scene::Scene out = vrml97::vrml1_to_vrml97(scene, {.x3d = x3d}, log);
  if (!quiet) print_diagnostics(log.entries());
  vrml97::write_vrml97_file(out, target);
}

}  // namespace lodforge::apps
