#include "lodforge/io/vrml97/write_vrml97.h"

#include <fmt/format.h>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/io/vrml97/read_vrml97.h"

namespace lodforge::vrml97 {
namespace {

void check_header(const scene::Scene& scene) {
  if (!is_vrml97_header(scene.header))
    throw DataError(fmt::format("cannot write a scene with header '{}' as VRML97 / X3D classic",
                                scene.header.substr(0, 40)));
}

}  // namespace

std::string write_vrml97(const scene::Scene& scene) {
  check_header(scene);
  return vrml1::write_vrml1(scene);
}

void write_vrml97_file(const scene::Scene& scene, const std::string& path,
                       const vrml1::WriteOptions& options) {
  check_header(scene);
  vrml1::write_vrml1_file(scene, path, options);
}

}  // namespace lodforge::vrml97
