// libFuzzer target: the VRML 1.0 reader, and the writer on whatever it reads
// (the written text must read back to the same scene). Bad input may only
// raise DataError.
// "The same scene": fuzz/round_trip.h.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/scene/statistics.h"
#include "round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  // Small expansion limits: an input may not make one run take seconds.
  const lodforge::vrml1::ReadOptions options{.source_name = "fuzz",
                                             .max_depth = 200,
                                             .max_instances = 100'000,
                                             .max_triangles = 1'000'000};
  try {
    auto r = lodforge::vrml1::read_vrml1(text, options);
    lodforge::scene::scene_statistics(r.scene);
    std::string out = lodforge::vrml1::write_vrml1(r.scene);
    auto read_back = options;
    read_back.source_name = "fuzz-out";
    auto back = lodforge::vrml1::read_vrml1(out, read_back);
    if (r.scene.header != back.scene.header || r.scene.roots.size() != back.scene.roots.size())
      __builtin_trap();
    lodforge::fuzz::RoundTripComparer same(r.scene);
    for (std::size_t i = 0; i < r.scene.roots.size(); ++i)
      if (!same.nodes(r.scene.roots[i], back.scene.roots[i])) __builtin_trap();
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
