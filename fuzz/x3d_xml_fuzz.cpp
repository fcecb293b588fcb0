// libFuzzer target: the X3D XML reader and the X3D XML writer on whatever it
// reads (the written text must read back to the same scene: fuzz/round_trip.h).
// Bad input may only raise DataError. The scenes are the classic reader's, whose
// LOD pipeline vrml97_fuzz covers; this target links the reader's module only.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/io/x3dxml/read_x3d_xml.h"
#include "lodforge/io/x3dxml/write_x3d_xml.h"
#include "round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    lodforge::fuzz::round_trip(
        text,
        [](std::string_view t, const char* source) {
          return lodforge::x3dxml::read_x3d_xml(t, {.source_name = source, .max_depth = 200});
        },
        [](const lodforge::scene::Scene& s) { return lodforge::x3dxml::write_x3d_xml(s); });
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
