// libFuzzer target: the VRML 1.0 reader, and the writer on whatever it reads
// (the written text must read back). Bad input may only raise DataError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/statistics.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    auto r = lodforge::vrml1::read_vrml1(text, {.source_name = "fuzz", .max_depth = 200});
    lodforge::scene::scene_statistics(r.scene);
    std::string out = lodforge::vrml1::write_vrml1(r.scene);
    auto back = lodforge::vrml1::read_vrml1(out, {.source_name = "fuzz-out", .max_depth = 200});
    if (!lodforge::scene::equal(r.scene, back.scene)) __builtin_trap();
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
