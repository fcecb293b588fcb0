#include "lodforge/apps/write_scene_vrml97.h"

#include <fmt/core.h>

#include "lodforge/apps/common_options.h"
#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "lodforge/io/vrml97/vrml1_to_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/io/vrml97/write_x3d_xml.h"

namespace lodforge::apps {

std::string vrml97_format_of(const std::string& format, const std::string& target) {
  if (format == "vrml97" || format == "x3dv" || format == "x3d") return format;
  if (!format.empty()) return "";
  if (target.ends_with(".x3dv") || target.ends_with(".x3dv.gz")) return "x3dv";
  return vrml97::is_x3d_xml_path(target) ? "x3d" : "";
}

void write_scene_vrml97(const scene::Scene& scene, const std::string& target,
                        const std::string& encoding, bool quiet, const vrml1::WriteOptions& write) {
  Log log;
  const scene::Scene out = vrml97::vrml1_to_vrml97(scene, {.x3d = encoding != "vrml97"}, log);
  if (!quiet) print_diagnostics(log.entries());
  if (encoding == "x3d")
    vrml97::write_x3d_xml_file(out, target);
  else
    vrml97::write_vrml97_file(out, target, write);
}

}  // namespace lodforge::apps
