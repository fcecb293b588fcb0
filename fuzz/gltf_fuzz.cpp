// libFuzzer target: the glTF 2.0 reader (JSON and GLB), the writer on
// whatever it reads (both containers must read back with the same objects),
// the geometry readers on the checked model, and its VRML97 conversion (the
// written text must read back). Bad input may only raise DataError. External
// files are never read (no base folder).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/core/log.h"
#include "lodforge/io/gltf/gltf_to_vrml97.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/gltf/scene_mesh.h"
#include "lodforge/io/gltf/write_gltf.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const lodforge::gltf::GltfReadOptions options{.source_name = "fuzz", .max_objects = 10'000};
  try {
    auto r = lodforge::gltf::read_gltf(bytes, options);
    lodforge::gltf::scene_mesh(r.scene.model, 0);
    lodforge::gltf::scene_mesh(r.scene.model, 1);
    for (bool binary : {true, false}) {
      const std::string out = lodforge::gltf::write_gltf(r.scene, {.binary = binary});
      auto back = lodforge::gltf::read_gltf(out, {.source_name = "fuzz-out"});
      const auto& a = r.scene.model;
      const auto& b = back.scene.model;
      if (a.nodes != b.nodes || a.meshes != b.meshes || a.accessors.size() != b.accessors.size() ||
          a.images.size() != b.images.size())
        __builtin_trap();
    }
    lodforge::Log log;
    const std::string text =
        lodforge::vrml97::write_vrml97(lodforge::gltf::gltf_to_vrml97(r.scene.model, log));
    try {
      lodforge::vrml97::read_vrml97(text, {.source_name = "fuzz-vrml97"});
    } catch (const lodforge::DataError&) {
      __builtin_trap();
    }
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
