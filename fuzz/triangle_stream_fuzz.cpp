// libFuzzer target for the streaming reader (mesh/triangle_stream.h) and the
// out-of-core clustering on it: any file must stream or throw
// lodforge::DataError, never crash, hang or throw another exception; what
// streams must hold indices in range and finite corners, and the clustering
// must give triangles of three distinct vertices in range. The stream reads
// files, so each input is written to a file of this process first. Run on
// the PLY and STL corpora:
//   build-fuzz/fuzz/triangle_stream_fuzz -max_total_time=60 fuzz/corpus/ply fuzz/corpus/stl
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "lodforge/core/error.h"
#include "lodforge/mesh/triangle_stream.h"
#include "lodforge/simplify/out_of_core_clustering.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // PLY by content; anything else is tried as binary STL.
  static const std::string path = "/tmp/lodforge_stream_fuzz_" + std::to_string(getpid()) + ".stl";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const lodforge::TriangleStream stream(path, {.chunk_triangles = 7});
    const std::uint64_t vertices = stream.vertex_count();
    stream.for_each_triangle([&](std::span<const lodforge::StreamedTriangle> chunk, std::uint64_t) {
      for (const lodforge::StreamedTriangle& t : chunk)
        for (int c = 0; c < 3; ++c)
          if (t.vertex[c] >= vertices || !std::isfinite(t.corner[c].x) ||
              !std::isfinite(t.corner[c].y) || !std::isfinite(t.corner[c].z))
            __builtin_trap();
    });
    const lodforge::SimplifyResult r = lodforge::out_of_core_clustering(stream, {.grid = 8});
    for (const lodforge::Triangle& t : r.mesh.triangles) {
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) __builtin_trap();
      for (std::uint32_t v : t)
        if (v >= r.mesh.vertex_count()) __builtin_trap();
    }
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
