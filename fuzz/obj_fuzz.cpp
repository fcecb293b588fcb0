// libFuzzer target for the OBJ reader: any input must give a mesh or a
// lodforge::DataError, never a crash, a hang or another exception.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    lodforge::TriangleMesh m = lodforge::read_mesh_data(text, lodforge::MeshFormat::kObj, "fuzz");
    for (const lodforge::Triangle& t : m.triangles)
      for (std::uint32_t v : t)
        if (v >= m.vertex_count()) __builtin_trap();
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
