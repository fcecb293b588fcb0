// libFuzzer target: the VRML97 / X3D classic reader, the writer on whatever it
// reads (the written text must read back to the same scene: fuzz/round_trip.h)
// and, for small scenes, the LOD pipeline. Bad input may only raise DataError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/io/vrml97/write_vrml97.h"
#include "lodforge/lod/generate_lod_vrml97.h"
#include "round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    lodforge::scene::Scene scene = lodforge::fuzz::round_trip(
        text,
        [](std::string_view t, const char* source) {
          return lodforge::vrml97::read_vrml97(t, {.source_name = source, .max_depth = 200});
        },
        [](const lodforge::scene::Scene& s) { return lodforge::vrml97::write_vrml97(s); });
    if (size < 4096) lodforge::generate_lod_vrml97(std::move(scene), {.threads = 1});
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
