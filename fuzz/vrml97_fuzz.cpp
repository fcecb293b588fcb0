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
    auto r = lodforge::vrml97::read_vrml97(text, {.source_name = "fuzz", .max_depth = 200});
    std::string out = lodforge::vrml97::write_vrml97(r.scene);
    auto back = lodforge::vrml97::read_vrml97(out, {.source_name = "fuzz-out", .max_depth = 200});
    if (r.scene.header != back.scene.header || r.scene.roots.size() != back.scene.roots.size())
      __builtin_trap();
    lodforge::fuzz::RoundTripComparer same(r.scene);
    for (std::size_t i = 0; i < r.scene.roots.size(); ++i)
      if (!same.nodes(r.scene.roots[i], back.scene.roots[i])) __builtin_trap();
    if (size < 4096) lodforge::generate_lod_vrml97(std::move(r.scene), {.threads = 1});
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
