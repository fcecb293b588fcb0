// libFuzzer target for the .mco reader and extraction: any input must give a
// model or a lodforge::DataError, never a crash, a hang or another exception,
// and a model that is accepted must extract every level with indices inside
// its vertex table and exactly the triangle count its accumulation table
// promises. Checksums are not verified (McoReadOptions::verify_checksums), so
// that mutations reach the structural checks behind them.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/mcoctree/extract_mc_mesh.h"
#include "lodforge/mcoctree/mco_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    lodforge::McLodModel m = lodforge::read_mco_data(bytes, "fuzz", {.verify_checksums = false});
    std::vector<lodforge::Triangle> out;
    const std::uint32_t last = m.priorities();
    for (std::uint32_t n : {0u, last / 2, last}) {
      std::size_t count = lodforge::extract_mc_indices(m, n, out);
      if (count != m.accumulated[n] || out.size() < count) __builtin_trap();
      for (std::size_t i = 0; i < count; ++i)
        for (std::uint32_t v : out[i])
          if (v >= m.positions.size()) __builtin_trap();
    }
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
